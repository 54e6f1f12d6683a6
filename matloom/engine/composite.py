"""Per-layer channel conversion, the "over" coverage rule and the height max-composite.

Input: one :class:`RawLayer` per layer (bottom first) holding each channel exactly as evaluated
from the layer's expressions, before any clamp. Output: :class:`MaterialMaps` with the blended
float32 maps plus the normal and AO derived from the composited height.

Reference rules reproduced here (reference-engine.md section 3):

* Clamps: alpha and the seven 0..1 channels to [0, 1]; ior below at 1; emissive strength below
  at 0; anisotropy_angle (degrees) none, so layers blend the angle linearly; colours (0..255 sRGB) are divided by 255, clamped to [0, 1] and decoded to linear per
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

Besides :func:`composite`, the fused schedule (:mod:`matloom.engine.schedules.banded`) uses the
channel conversions (:func:`convert_scalar`, :func:`colour_to_linear`,
:func:`colour_to_linear64`, :func:`emitted_radiance`) for constant channels, :func:`ao_radii`,
and :func:`allocate_maps` with :func:`composite_band` for what its kernel leaves to numpy.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, make_dataclass
from typing import Any

import numpy as np

from matloom.engine import relief
from matloom.engine.colour import fast_srgb_to_linear, float32_of, srgb_to_linear
from matloom.engine.maps import MaterialMaps, View
from matloom.vocab.layout import LAYOUT, Group

#: A channel value: a number or an array broadcastable to (H, W).
ArrayOrFloat = np.ndarray | float
#: Reads the current band of rows out of a channel value.
BandReader = Callable[[ArrayOrFloat], np.ndarray]
#: Rows per band while compositing.
BAND_ROWS = relief.BAND_ROWS


#: Name of the coverage channel (a layer's alpha).
COVERAGE = LAYOUT.coverage.name


class _Layer:
    """One layer's channels as evaluated from its expressions, before any clamping.

    One keyword field per registry channel (``alpha``, ``basecolor``, ``metallic``, ...); each
    value is a float or an array broadcastable to (H, W); colour channels hold a tuple of their
    arguments on the authored 0..255 sRGB scale (``emissive`` is (r, g, b, strength)). A channel
    the layer does not write keeps the registry's default.
    """

    def set(self, name: str, values: Sequence[ArrayOrFloat]) -> None:
        """Store the evaluated arguments of channel ``name`` (a tuple for colours)."""
        setattr(self, name, values[0] if LAYOUT[name].arity == 1 else tuple(values))

    def blended_values(self) -> list[ArrayOrFloat]:
        """The values compositing weights by the layer's visible coverage, in kernel slot
        order: basecolor, the scalars, ior, emissive (r, g, b, strength). The others are the
        coverage (``alpha``) and the max-blended ``height``."""
        out: list[ArrayOrFloat] = []
        for channel in LAYOUT.blended_in_slot_order:
            value = getattr(self, channel.name)
            if channel.arity > 1:
                out.extend(value)
            else:
                out.append(value)
        return out


#: A layer's channel values: a keyword-only dataclass with one field per registry channel.
RawLayer = make_dataclass(
    "RawLayer",
    [(c.name, Any, field(default=c.default)) for c in LAYOUT.channels],
    bases=(_Layer,),
    namespace={"__doc__": _Layer.__doc__, "__module__": __name__},
    kw_only=True,
)


def map_channels(fn: Callable[..., Any], *layers: Any) -> Any:
    """A :data:`RawLayer` whose every channel value (every component of a colour) is
    ``fn(the values of that channel in layers)``; channels are visited in slot order."""
    values: dict[str, Any] = {}
    for channel in LAYOUT.in_slot_order:
        vs = [getattr(layer, channel.name) for layer in layers]
        values[channel.name] = (
            fn(*vs) if channel.arity == 1 else tuple(fn(*comp) for comp in zip(*vs, strict=True))
        )
    return RawLayer(**values)


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


def convert_scalar(value: np.ndarray, clamp: tuple[float | None, float | None]) -> np.ndarray:
    """A scalar channel's value in float32 clamped to ``clamp`` = (lo, hi), None = unbounded
    (the layout's clamp: [0, 1], below at 1 for ior, none for height); NaN passes through."""
    lo, hi = clamp
    if lo == 0.0 and hi == 1.0:
        return clamp_unit(value)
    if hi is None:
        return _as_float32(value) if lo is None else clamp_below(value, lo)
    return np.clip(_as_float32(value), -np.inf if lo is None else np.float32(lo), np.float32(hi))


def colour_to_linear64(value: np.ndarray) -> np.ndarray:
    """Authored 0..255 sRGB component -> linear float64: clamp(v/255, 0, 1), decoded (with the
    portable power: the same bits on every CPU). The fused schedule decodes a constant emissive
    colour with it before the kernel multiplies by a varying strength."""
    return srgb_to_linear(_scaled_colour(value))


def _scaled_colour(value: np.ndarray) -> np.ndarray:
    return np.clip(np.asarray(value, dtype=np.float64) / 255.0, 0.0, 1.0)


def colour_to_linear(value: np.ndarray) -> np.ndarray:
    """Authored 0..255 sRGB component -> linear float32 (converted in float64, then cast).

    Arrays decode with numpy's fast ``power`` and :func:`float32_of` makes the float32 the same
    on every CPU (the rare texels near a float32 rounding boundary decode portably)."""
    scaled = _scaled_colour(value)
    if scaled.ndim == 0:
        return srgb_to_linear(scaled).astype(np.float32)
    return float32_of(fast_srgb_to_linear(scaled), lambda at: srgb_to_linear(scaled[at]))


def emitted_radiance(colour: np.ndarray, strength: np.ndarray) -> np.ndarray:
    """Linear emissive colour times max(strength, 0), formed in float64 and cast to float32.

    The reference multiplies before casting (its emissive product is a float64 grid), which
    changes the last bit compared to multiplying two float32 values.
    """
    scaled = _scaled_colour(colour)
    gain = np.maximum(np.asarray(strength, np.float64), 0.0)
    if scaled.ndim == 0 and np.ndim(gain) == 0:
        return (srgb_to_linear(scaled) * gain).astype(np.float32)
    scaled, gain = np.broadcast_arrays(scaled, gain)
    return float32_of(
        fast_srgb_to_linear(scaled) * gain, lambda at: srgb_to_linear(scaled[at]) * gain[at]
    )


# --------------------------------------------------------------------------------------------
# Compositing one band


@dataclass
class _BandAccumulators:
    """Views into the output arrays for one band of rows, accumulated in place (by channel
    name: over-blended scalars, colours (rows, W, 3), max-blended channels)."""

    scalars: dict[str, np.ndarray]
    colours: dict[str, np.ndarray]
    maxed: dict[str, np.ndarray]
    running: np.ndarray

    def blended(self) -> list[np.ndarray]:
        return [*self.scalars.values(), *self.colours.values()]


def _coverage_weights(
    layers: Sequence[RawLayer], band: BandReader, running: np.ndarray
) -> list[tuple[np.ndarray, np.ndarray]]:
    """(alpha_i, V_i) per layer, bottom first, from the top-down walk.

    ``running`` ends as prod(1 - alpha_i). The reference forms every V_i first and then sums
    V_i * c_i bottom-up; keeping that order keeps the float32 sums bit-identical.
    """
    result: list[tuple[np.ndarray, np.ndarray]] = [(running, running)] * len(layers)
    for index in reversed(range(len(layers))):
        alpha = clamp_unit(band(getattr(layers[index], COVERAGE)))
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
    for channel in LAYOUT.scalars:
        value = band(getattr(layer, channel.name))
        adder.add(acc.scalars[channel.name], convert_scalar(value, channel.clamp))
    for channel in LAYOUT.colours:
        values, target = getattr(layer, channel.name), acc.colours[channel.name]
        if channel.group is Group.COLOUR_STRENGTH:
            strength = band(values[3])
            for k in range(3):
                adder.add(target[..., k], emitted_radiance(band(values[k]), strength))
        else:
            for k in range(3):
                adder.add(target[..., k], colour_to_linear(band(values[k])))


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
    for top in acc.maxed.values():
        np.copyto(top, 0, where=np.isneginf(top))
        top += np.float32(0.0)  # -0.0 + 0.0 == +0.0


def allocate_maps(width: int, height: int) -> dict[str, np.ndarray]:
    """Zeroed float32 outputs of every channel by ``MaterialMaps`` field, (height, width) or
    (height, width, 3), ready for :func:`composite_band` (max-blended ones hold the -inf
    accumulator start)."""
    maps = {}
    for channel in LAYOUT.channels:
        shape = (height, width) + ((3,) if channel.components == 3 else ())
        start = -np.inf if channel.group is Group.MAX else 0.0
        maps[channel.field] = np.full(shape, start, np.float32)
    return maps


def composite_band(layers: Sequence[RawLayer], maps: dict[str, np.ndarray], rows: slice) -> None:
    """Composite every layer for the rows ``rows`` into ``maps`` (in place): the numpy
    reference compositing of one band.

    ``maps`` are outputs as :func:`allocate_maps` makes them (the rows of max-blended channels
    must hold -inf); each layer value is a float or an array broadcastable to the maps' full
    (H, W) shape, whose rows ``rows`` are read. The fused schedule calls it for the bands and
    texels its kernel leaves to numpy."""
    coverage = maps[LAYOUT.coverage.field]
    shape = coverage.shape
    n_rows = rows.stop - rows.start

    def views(channels: Sequence[Any]) -> dict[str, np.ndarray]:
        return {c.name: maps[c.field][rows] for c in channels}

    acc = _BandAccumulators(
        scalars=views(LAYOUT.scalars),
        colours=views(LAYOUT.colours),
        maxed=views(LAYOUT.maxed),
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
            for name, top in acc.maxed.items():
                _max_height(top, alpha, _as_float32(band(getattr(layer, name))))
        _finish_band(acc, coverage[rows])


# --------------------------------------------------------------------------------------------
# Public entry point


def ao_radii(
    view: View, width: int, height: int, texels: float | None, units: float | None
) -> tuple[float, float]:
    """Per-axis AO radius in texels of a ``width`` x ``height`` render of ``view``, from the
    options ``ao_radius_texels`` / ``ao_radius_units`` of :func:`composite` (at most one;
    default: the reference's 8 texels). Raises ValueError when both are given."""
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
    radius_x, radius_y = ao_radii(view, width, height, ao_radius_texels, ao_radius_units)
    maps = allocate_maps(width, height)
    for rows in relief.bands(height, BAND_ROWS):
        composite_band(layers, maps, rows)
    from matloom.engine.tiling import relief_maps

    maps["normal"], maps["ao"] = relief_maps(
        maps["height"], view, (radius_x, radius_y), relief.normals, relief.ambient_occlusion
    )
    return MaterialMaps(**maps, view=view, n_layers=len(layers))
