"""Relief maps derived from the composited height: tangent-space normals and cavity AO.

Both follow the reference exactly (bit for bit on the parity fixtures):

* normals: central differences of the float32 height (one-sided at the borders, no wrap, zero
  slope on a length-1 axis), the row derivative negated because row 0 is the largest Y, and
  n = (-dH/dX, -dH/dY, 1) / |.|, all in float32 (OpenGL convention, +y toward row 0);
* ambient occlusion: a separable, edge-clamped box mean of the height (horizontal pass, then
  vertical), cavity = clip((mean - H) / (max(R, 1) * dx), 0, 1), ao = clip(1 - s * cavity, 0, 1).

Work is done in bands of rows (columns for the vertical pass) so that the temporaries stay a
small fraction of one map even at 2048x2048 and beyond.

Fractional radii (used for resolution-independent AO, where the radius comes from coordinate
units): a radius R = n + f (0 <= f < 1) uses the 2n + 1 taps at offsets -n..n with weight 1 plus
the two taps at offsets +-(n + 1) with weight f, and divides by 2R + 1, so the weights sum to 1
and the filter varies continuously with R. For integer R this is exactly the reference's box.
Up to :data:`EXACT_TAP_LIMIT` taps the taps are summed in ascending order in float32 like the
reference; wider windows use a float64 prefix-sum (within ~1e-7 relative of the tap sum).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

#: Rows per band for the banded passes (a band of a 2048-wide float32 map is 2 MiB).
BAND_ROWS = 256
#: The reference's export AO radius, in texels, on each axis.
DEFAULT_AO_RADIUS_TEXELS = 8.0
#: The reference's AO strength.
DEFAULT_AO_STRENGTH = 1.0
#: Windows with more taps than this are summed with a float64 prefix sum instead of tap by tap.
EXACT_TAP_LIMIT = 65


def bands(length: int, size: int = BAND_ROWS) -> Iterator[slice]:
    """Consecutive slices of at most ``size`` covering ``range(length)``."""
    for start in range(0, length, size):
        yield slice(start, min(start + size, length))


def _as_height(height: np.ndarray) -> np.ndarray:
    """Validate and return the height as a 2-D float32 array."""
    array = np.asarray(height, dtype=np.float32)
    if array.ndim != 2:
        raise ValueError(f"height must be a 2-D (H, W) array, got shape {array.shape}")
    return array


# --------------------------------------------------------------------------------------------
# Normals


def _slope_along_columns(block: np.ndarray, spacing: float) -> np.ndarray:
    """d(block)/d(column) in float32, as numpy.gradient computes it with a scalar spacing."""
    slope = np.zeros_like(block)
    width = block.shape[1]
    if width < 2:
        return slope
    if width > 2:
        np.divide(block[:, 2:] - block[:, :-2], 2.0 * spacing, out=slope[:, 1:-1])
    slope[:, 0] = (block[:, 1] - block[:, 0]) / spacing
    slope[:, -1] = (block[:, -1] - block[:, -2]) / spacing
    return slope


def _slope_along_rows(height: np.ndarray, rows: slice, spacing: float) -> np.ndarray:
    """d(height)/d(row) for the rows in ``rows`` (needs one neighbour row on each side)."""
    n_rows = height.shape[0]
    index = np.arange(rows.start, rows.stop)
    if n_rows < 2:
        return np.zeros((len(index), height.shape[1]), dtype=np.float32)
    above = np.clip(index - 1, 0, n_rows - 1)
    below = np.clip(index + 1, 0, n_rows - 1)
    slope = height[below] - height[above]
    interior = (index > 0) & (index < n_rows - 1)
    slope[interior] /= np.float32(2.0 * spacing)
    slope[~interior] /= np.float32(spacing)
    return slope


def normals(height: np.ndarray, dx: float, dy: float) -> np.ndarray:
    """Unit tangent-space normals (H, W, 3) float32 from a height map in coordinate units.

    ``dx``/``dy`` are the texel spacings in coordinate units (View.texel_size). A zero spacing
    gives inf/NaN normals, as in the reference (no warning is raised).
    """
    h = _as_height(height)
    out = np.empty(h.shape + (3,), dtype=np.float32)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for rows in bands(h.shape[0]):
            slope_x = _slope_along_columns(h[rows], float(dx))
            slope_y = _slope_along_rows(h, rows, float(dy))
            inv_length = 1 / np.sqrt(slope_x * slope_x + slope_y * slope_y + 1)
            out[rows, :, 0] = -slope_x * inv_length
            out[rows, :, 1] = slope_y * inv_length
            out[rows, :, 2] = inv_length
    return out


# --------------------------------------------------------------------------------------------
# Box mean


def _split_radius(radius: float) -> tuple[int, float]:
    """(whole taps per side, weight of the extra fractional tap) for a radius >= 0."""
    if not (math.isfinite(radius) and radius >= 0):
        raise ValueError(f"AO radius must be finite and >= 0 texels, got {radius!r}")
    whole = math.floor(radius)
    return whole, radius - whole


def _box_sum_taps(block: np.ndarray, whole: int, frac: float) -> np.ndarray:
    """Window sums along axis 1, tap by tap in ascending offset order, in float32."""
    reach = whole + (1 if frac > 0 else 0)
    padded = np.pad(block, ((0, 0), (reach, reach)), mode="edge")
    width = block.shape[1]
    edge = [frac] * (reach - whole)
    weights = edge + [1.0] * (2 * whole + 1) + edge
    acc = np.zeros((block.shape[0], width), dtype=np.float32)
    for offset, weight in enumerate(weights):
        tap = padded[:, offset : offset + width]
        acc += tap if weight == 1.0 else tap * np.float32(weight)
    return acc


def _box_sum_prefix(block: np.ndarray, whole: int, frac: float) -> np.ndarray:
    """Window sums along axis 1 via a float64 prefix sum with closed-form edge clamping."""
    width = block.shape[1]
    values = block.astype(np.float64)
    prefix = np.zeros((block.shape[0], width + 1), dtype=np.float64)
    np.cumsum(values, axis=1, out=prefix[:, 1:])
    centre = np.arange(width)
    first = np.maximum(centre - whole, 0)
    last = np.minimum(centre + whole, width - 1)
    total = prefix[:, last + 1] - prefix[:, first]
    total += np.maximum(whole - centre, 0) * values[:, :1]
    total += np.maximum(centre + whole - (width - 1), 0) * values[:, -1:]
    if frac > 0:
        left = np.clip(centre - whole - 1, 0, width - 1)
        right = np.clip(centre + whole + 1, 0, width - 1)
        total += frac * (values[:, left] + values[:, right])
    return total


def _box_mean_last_axis(block: np.ndarray, radius: float) -> np.ndarray:
    """Edge-clamped box mean of ``block`` along its last axis, float32."""
    whole, frac = _split_radius(radius)
    taps = 2 * whole + 1 + (2 if frac > 0 else 0)
    if taps <= EXACT_TAP_LIMIT:
        total = _box_sum_taps(block, whole, frac)
    else:
        total = _box_sum_prefix(block, whole, frac)
    divisor = 2 * whole + 1 if frac == 0 else 2 * radius + 1
    return (total / divisor).astype(np.float32, copy=False)


def box_mean(height: np.ndarray, radius_x: float, radius_y: float) -> np.ndarray:
    """Separable edge-clamped box mean: horizontal pass (radius_x), then vertical (radius_y)."""
    h = _as_height(height)
    mean = np.empty_like(h)
    for rows in bands(h.shape[0]):
        mean[rows] = _box_mean_last_axis(h[rows], radius_x)
    mean_t = mean.T
    for cols in bands(h.shape[1]):
        mean_t[cols] = _box_mean_last_axis(np.ascontiguousarray(mean_t[cols]), radius_y)
    return mean


def ambient_occlusion(
    height: np.ndarray,
    dx: float,
    radius_x: float = DEFAULT_AO_RADIUS_TEXELS,
    radius_y: float = DEFAULT_AO_RADIUS_TEXELS,
    strength: float = DEFAULT_AO_STRENGTH,
) -> np.ndarray:
    """Cavity ambient occlusion (H, W) float32, 1 = unoccluded.

    Radii are in texels (may be fractional, see the module docstring). The cavity depth is
    normalised by ``max(radius_x, 1) * dx`` (the horizontal radius in coordinate units), as the
    reference does with its single radius.
    """
    h = _as_height(height)
    ao = box_mean(h, radius_x, radius_y)
    depth_scale = max(radius_x, 1) * float(dx)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for rows in bands(h.shape[0]):
            band = ao[rows]
            band -= h[rows]
            band /= np.float32(depth_scale)
            np.clip(band, 0, 1, out=band)
            np.clip(1 - strength * band, 0, 1, out=band)
    return ao


def ao_radius_from_units(units: float, dx: float, dy: float) -> tuple[float, float]:
    """Texel radii (x, y) for an AO radius given in coordinate units (units / texel spacing)."""
    if not (math.isfinite(units) and units >= 0):
        raise ValueError(f"ao_radius_units must be finite and >= 0, got {units!r}")
    if dx == 0 or dy == 0:
        raise ValueError("ao_radius_units needs a non-zero texel size (the View has zero span)")
    return units / abs(dx), units / abs(dy)
