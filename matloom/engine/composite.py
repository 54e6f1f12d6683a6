"""Per-layer channel conversion, the "over" coverage rule and the height max-composite.

Input: one :class:`RawLayer` per layer (bottom first) holding each channel exactly as evaluated
from the layer's expressions, before any clamp. Output: :class:`MaterialMaps` with the blended
float32 maps plus the normal and AO derived from the composited height.

Reference rules reproduced here (reference-engine.md section 3):

* Clamps: alpha and the seven 0..1 channels to [0, 1]; ior below at 1; emissive strength below
  at 0; colours (0..255 sRGB) are divided by 255, clamped to [0, 1] and decoded to linear per
  layer. Height is unclamped. NaN passes through every clamp. Colours are decoded, and the
  emissive colour x strength product formed, in float64 (the reference's expression grids are
  float64) and then cast to float32; every other channel is cast to float32 first.
* Over rule, walking from the top layer down with running = 1: V_i = a_i * running, then
  running *= 1 - a_i; coverage A = 1 - running; each blended channel is sum(V_i * c_i) / A where
  A > 0 and exactly 0 elsewhere (a NaN coverage also gives 0), the sum taken bottom layer first
  in float32. Emissive c_i is the layer's linear colour times its strength.
* Height: max over layers whose alpha > 0 and whose height is finite; 0 where no layer
  qualifies; -0.0 becomes +0.0.

With these orders and precisions the result is bit-identical to the reference's arrays on the
parity fixtures checked in tests/engine/test_composite.py.

The work runs in bands of rows, accumulating in place in the output arrays, so temporaries stay
small: constant channels (plain floats) are never expanded to full arrays.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from matloom.engine import relief
from matloom.engine.colour import srgb_to_linear
from matloom.engine.maps import SCALAR_CHANNELS, MaterialMaps, View

#: A channel value: a number or an array broadcastable to (H, W).
ArrayOrFloat = np.ndarray | float
#: Reads the current band of rows out of a channel value.
BandReader = Callable[[ArrayOrFloat], np.ndarray]
#: Rows per band while compositing.
BAND_ROWS = relief.BAND_ROWS


@dataclass
class RawLayer:
    """One layer's channels as evaluated from its expressions, before any clamping.

    Each value is a float or an array broadcastable to (H, W). Colours are on the authored
    0..255 sRGB scale; ``emissive`` is (r, g, b, strength). Defaults are the reference's
    defaults for a channel the layer does not write.
    """

    alpha: ArrayOrFloat = 1.0
    basecolor: tuple[ArrayOrFloat, ArrayOrFloat, ArrayOrFloat] = (0.0, 0.0, 0.0)
    metallic: ArrayOrFloat = 0.0
    roughness: ArrayOrFloat = 0.0
    sheen: ArrayOrFloat = 0.0
    coat: ArrayOrFloat = 0.0
    transmission: ArrayOrFloat = 0.0
    subsurface: ArrayOrFloat = 0.0
    anisotropy: ArrayOrFloat = 0.0
    ior: ArrayOrFloat = 1.5
    emissive: tuple[ArrayOrFloat, ArrayOrFloat, ArrayOrFloat, ArrayOrFloat] = (0.0, 0.0, 0.0, 0.0)
    height: ArrayOrFloat = 0.0

    def blended_values(self) -> list[ArrayOrFloat]:
        """The values compositing weights by the layer's visible coverage: basecolor, the seven
        scalars, ior, emissive (r, g, b, strength). The others are ``alpha`` and ``height``."""
        return [
            *self.basecolor,
            *(getattr(self, name) for name in SCALAR_CHANNELS),
            self.ior,
            *self.emissive,
        ]


# --------------------------------------------------------------------------------------------
# Channel conversion (per band)


def _band_of(value: ArrayOrFloat, rows: slice, shape: tuple[int, int]) -> np.ndarray:
    """The rows ``rows`` of a value broadcastable to ``shape`` (scalars stay 0-d)."""
    array = np.asarray(value)
    if array.ndim > 2:
        raise ValueError(
            f"layer channel has shape {array.shape}; expected one broadcastable to {shape}"
        )
    np.broadcast_shapes(array.shape, shape)  # raises ValueError when incompatible
    if array.ndim == 2 and array.shape[0] == shape[0]:
        return array[rows]
    return array


def _as_float32(value: np.ndarray) -> np.ndarray:
    return np.asarray(value, dtype=np.float32)


def clamp_unit(value: np.ndarray) -> np.ndarray:
    """Clamp to [0, 1] in float32; NaN passes through."""
    return np.clip(_as_float32(value), 0, 1)


def clamp_below(value: np.ndarray, floor: float) -> np.ndarray:
    """Clamp below at ``floor`` in float32 (no upper bound); NaN passes through."""
    return np.maximum(_as_float32(value), np.float32(floor))


def _colour_to_linear64(value: np.ndarray) -> np.ndarray:
    """Authored 0..255 sRGB component -> linear float64: clamp(v/255, 0, 1), decoded."""
    scaled = np.asarray(value, dtype=np.float64) / 255.0
    return srgb_to_linear(np.clip(scaled, 0.0, 1.0))


def colour_to_linear(value: np.ndarray) -> np.ndarray:
    """Authored 0..255 sRGB component -> linear float32 (converted in float64, then cast)."""
    return _colour_to_linear64(value).astype(np.float32)


def emitted_radiance(colour: np.ndarray, strength: np.ndarray) -> np.ndarray:
    """Linear emissive colour times max(strength, 0), formed in float64 and cast to float32.

    The reference multiplies before casting (its emissive product is a float64 grid), which
    changes the last bit compared to multiplying two float32 values.
    """
    product = _colour_to_linear64(colour) * np.maximum(np.asarray(strength, np.float64), 0.0)
    return product.astype(np.float32)


# --------------------------------------------------------------------------------------------
# Compositing one band


@dataclass
class _BandAccumulators:
    """Views into the output arrays for one band of rows, accumulated in place."""

    scalars: dict[str, np.ndarray]
    basecolor: np.ndarray
    emissive: np.ndarray
    ior: np.ndarray
    height: np.ndarray
    running: np.ndarray

    def blended(self) -> list[np.ndarray]:
        return [*self.scalars.values(), self.basecolor, self.emissive, self.ior]


def _coverage_weights(
    layers: Sequence[RawLayer], band: BandReader, running: np.ndarray
) -> list[tuple[np.ndarray, np.ndarray]]:
    """(alpha_i, V_i) per layer, bottom first, from the top-down walk.

    ``running`` ends as prod(1 - alpha_i). The reference forms every V_i first and then sums
    V_i * c_i bottom-up; keeping that order keeps the float32 sums bit-identical.
    """
    result: list[tuple[np.ndarray, np.ndarray]] = [(running, running)] * len(layers)
    for index in reversed(range(len(layers))):
        alpha = clamp_unit(band(layers[index].alpha))
        result[index] = (alpha, alpha * running)
        running *= 1 - alpha
    return result


@dataclass
class _WeightedAdder:
    """Adds weight * values to accumulators through one scratch buffer.

    A constant exact zero is skipped when the weight has no NaN: adding weight * 0 = +0.0 to a
    non-negative accumulator changes nothing, so unwritten channels cost nothing.
    """

    weight: np.ndarray
    scratch: np.ndarray
    weight_has_nan: bool

    def add(self, target: np.ndarray, values: np.ndarray) -> None:
        if values.ndim == 0 and values == 0 and not self.weight_has_nan:
            return
        np.multiply(self.weight, values, out=self.scratch)
        target += self.scratch


def _accumulate_layer(
    acc: _BandAccumulators, layer: RawLayer, adder: _WeightedAdder, band: BandReader
) -> None:
    """Add one layer's weighted channels (weight = V_i) to the band accumulators."""
    for name, target in acc.scalars.items():
        adder.add(target, clamp_unit(band(getattr(layer, name))))
    adder.add(acc.ior, clamp_below(band(layer.ior), 1.0))
    for k in range(3):
        adder.add(acc.basecolor[..., k], colour_to_linear(band(layer.basecolor[k])))
    strength = band(layer.emissive[3])
    for k in range(3):
        adder.add(acc.emissive[..., k], emitted_radiance(band(layer.emissive[k]), strength))


def _max_height(height_acc: np.ndarray, alpha: np.ndarray, height: np.ndarray) -> None:
    """height_acc = max(height_acc, height) where alpha > 0 and height is finite."""
    present = (alpha > 0) & np.isfinite(height)
    present = np.broadcast_to(present, height_acc.shape)
    np.maximum(height_acc, height, out=height_acc, where=present)


def _finish_band(acc: _BandAccumulators, coverage: np.ndarray) -> None:
    """Un-premultiply by coverage (0 where coverage is not > 0) and settle the height."""
    np.subtract(1, acc.running, out=coverage)
    uncovered = ~(coverage > 0)
    # Dividing by 1 where uncovered (then overwriting with 0) is faster than a masked divide.
    divisor = np.where(uncovered, np.float32(1), coverage)
    for target in acc.blended():
        if target.ndim == 2:
            target /= divisor
            np.copyto(target, 0, where=uncovered)
        else:
            target /= divisor[..., None]
            np.copyto(target, 0, where=uncovered[..., None])
    np.copyto(acc.height, 0, where=np.isneginf(acc.height))
    acc.height += np.float32(0.0)  # -0.0 + 0.0 == +0.0


def _allocate_maps(width: int, height: int) -> dict[str, np.ndarray]:
    """Zeroed float32 outputs for the blended channels and the height (-inf accumulator)."""
    plane = (height, width)
    maps = {name: np.zeros(plane, np.float32) for name in SCALAR_CHANNELS}
    maps["basecolor_linear"] = np.zeros(plane + (3,), np.float32)
    maps["emissive_linear"] = np.zeros(plane + (3,), np.float32)
    maps["ior"] = np.zeros(plane, np.float32)
    maps["alpha"] = np.zeros(plane, np.float32)
    maps["height"] = np.full(plane, -np.inf, np.float32)
    return maps


def _composite_band(layers: Sequence[RawLayer], maps: dict[str, np.ndarray], rows: slice) -> None:
    """Composite every layer for one band of rows into ``maps`` (in place)."""
    shape = maps["alpha"].shape
    n_rows = rows.stop - rows.start
    acc = _BandAccumulators(
        scalars={name: maps[name][rows] for name in SCALAR_CHANNELS},
        basecolor=maps["basecolor_linear"][rows],
        emissive=maps["emissive_linear"][rows],
        ior=maps["ior"][rows],
        height=maps["height"][rows],
        running=np.ones((n_rows, shape[1]), np.float32),
    )

    def band(value: ArrayOrFloat) -> np.ndarray:
        return _band_of(value, rows, shape)

    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        scratch = np.empty_like(acc.running)
        weights = _coverage_weights(layers, band, acc.running)
        for layer, (alpha, weight) in zip(layers, weights, strict=True):
            adder = _WeightedAdder(weight, scratch, bool(np.isnan(weight).any()))
            _accumulate_layer(acc, layer, adder, band)
            _max_height(acc.height, alpha, _as_float32(band(layer.height)))
        _finish_band(acc, maps["alpha"][rows])


# --------------------------------------------------------------------------------------------
# Public entry point


def _ao_radii(
    view: View, width: int, height: int, texels: float | None, units: float | None
) -> tuple[float, float]:
    """Per-axis AO radius in texels from the keyword options (default: the reference's 8)."""
    if texels is not None and units is not None:
        raise ValueError("give at most one of ao_radius_texels and ao_radius_units")
    if units is not None:
        dx, dy = view.texel_size(width, height)
        return relief.ao_radius_from_units(units, dx, dy)
    radius = relief.DEFAULT_AO_RADIUS_TEXELS if texels is None else float(texels)
    return radius, radius


def composite(
    layers: Sequence[RawLayer],
    width: int,
    height: int,
    view: View,
    *,
    ao_radius_texels: float | None = None,
    ao_radius_units: float | None = None,
) -> MaterialMaps:
    """Composite ``layers`` (bottom first) into float32 maps, then derive normal and AO.

    ``ao_radius_texels`` sets the AO box radius in texels (the reference uses 8, so its AO
    changes with resolution); ``ao_radius_units`` instead gives it in coordinate units, turned
    into texels per axis (units / dx, units / dy) so AO looks the same at every resolution.
    Raises ValueError for an empty layer list or bad sizes.
    """
    if not layers:
        raise ValueError("material has no layers")
    if width < 1 or height < 1:
        raise ValueError(f"width and height must be >= 1, got {width}x{height}")
    radius_x, radius_y = _ao_radii(view, width, height, ao_radius_texels, ao_radius_units)
    maps = _allocate_maps(width, height)
    for rows in relief.bands(height, BAND_ROWS):
        _composite_band(layers, maps, rows)
    dx, dy = view.texel_size(width, height)
    maps["normal"] = relief.normals(maps["height"], dx, dy)
    maps["ao"] = relief.ambient_occlusion(maps["height"], dx, radius_x, radius_y)
    return MaterialMaps(**maps, view=view, n_layers=len(layers))
