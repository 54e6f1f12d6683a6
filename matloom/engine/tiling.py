"""Tileable output: periods of the View, lattice snapping, wrapped relief and the seam ratio.

A tileable render (``View(..., tileable=True)``, ``--tileable``, ``evaluate(tileable=True)``)
makes every map repeat with the View's width W and height H. The evaluator passes each noise the
periods of its coordinate frame (the View's (W, 0) and (0, H) through the frame's affine map,
see :meth:`matloom.engine.interpret.Evaluator.periods_of`); the noise kernels then make their
lattices periodic (:mod:`matloom.engine.kernels.noise`: fBm's per-octave sublattice, Worley's
snapped cell counts), Tile and Hash wrap their cell indices, shapes are drawn with their images
one period apart (:func:`matloom.engine.rules.fields.wrapped_shape`), and the relief (normals, AO)
is computed on the height padded by wrapping, so that the borders see the opposite edge.

:func:`seam_ratio` measures the result: the mean absolute difference across the wrap edge over
the mean absolute difference between interior neighbours (1: the wrap edge differs as much as
the average pair of neighbours; angle maps compared around their period; see docs/tileable.md
for what one line of texels can and cannot tell);
:func:`matloom.render.seams.seam_ratios_over_offsets` pools it over shifted renders.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = [
    "manifest_entry",
    "map_periods",
    "seam_ratio",
    "seam_ratios",
    "snap_count",
    "wrapped_relief",
]


def snap_count(cells: float) -> int:
    """The whole number of cells (>= 1) nearest to ``cells`` (a period in cell units)."""
    if not math.isfinite(cells):
        return 1
    return max(1, int(round(abs(cells))))


def wrapped_relief(
    relief: Callable[..., np.ndarray], height: np.ndarray, reach: float, *args: Any
) -> np.ndarray:
    """``relief(height, *args)`` as if the height repeated beyond its borders: computed on the
    height padded by wrapping with ``reach`` texels (at least 2) and cropped back."""
    h = np.asarray(height)
    pad = int(math.ceil(min(max(reach, 0.0), 4.0 * max(h.shape)))) + 2
    padded = np.pad(h, pad, mode="wrap")
    out = relief(padded, *args)
    return np.ascontiguousarray(out[pad:-pad, pad:-pad])


def relief_maps(
    height: np.ndarray,
    view: Any,
    radii: tuple[float, float],
    normals: Callable[..., np.ndarray],
    ambient_occlusion: Callable[..., np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """(normal, ao) of the composited ``height`` with a backend's relief functions, wrapped
    around the image edges when ``view`` is tileable."""
    rows, cols = height.shape
    dx, dy = view.texel_size(cols, rows)
    radius_x, radius_y = radii
    if not view.tileable:
        return normals(height, dx, dy), ambient_occlusion(height, dx, radius_x, radius_y)
    reach = max(radius_x, radius_y) + 1
    return (
        wrapped_relief(normals, height, 1, dx, dy),
        wrapped_relief(ambient_occlusion, height, reach, dx, radius_x, radius_y),
    )


def seam_ratio(image: np.ndarray, period: float | None = None) -> float:
    """Mean |difference| across the wrap edges (last column vs first, last row vs first) over
    the mean |difference| between interior neighbours (horizontal and vertical, the wrap pairs
    excluded); 1.0 for a map constant up to float rounding; NaN/inf texels ignored; colour
    maps: all channels. ``period``: the values are angles modulo it (``anisotropy_angle``: 180
    degrees), so differences are taken around the circle (179 and 1 differ by 2)."""
    a = np.asarray(image)
    if a.ndim < 2 or a.shape[0] < 2 or a.shape[1] < 2:
        return 1.0
    edge, inner = seam_parts(a, period)
    return ratio(edge, inner, magnitude(a) if period is None else float(period))


def magnitude(a: np.ndarray) -> float:
    """Largest finite |value| of ``a`` (0 when none)."""
    finite = np.abs(a[np.isfinite(a)])
    return float(finite.max()) if finite.size else 0.0


def seam_ratios(arrays: dict[str, np.ndarray]) -> dict[str, float]:
    """:func:`seam_ratio` of every map (``MaterialMaps`` field names), rounded to 4 decimals,
    angle maps around their period (:func:`map_periods`)."""
    periods = map_periods()
    return {name: round(seam_ratio(a, periods.get(name)), 4) for name, a in arrays.items()}


def map_periods() -> dict[str, float]:
    """``MaterialMaps`` field -> the period of its values, for the maps exported as angles
    (the registry's export rules: ``anisotropy_angle`` repeats every 180 degrees)."""
    from matloom.vocab.layout import LAYOUT

    return {s.sources[0]: float(s.period) for s in LAYOUT.maps if s.period and s.sources}


def manifest_entry(maps: Any, specs: Any) -> dict[str, Any]:
    """The manifest's tiling fields of a render: ``tileable`` and, for tileable maps, the
    ``seam_ratio`` of every exported map (``specs``: the exported maps' ``MapSpec``s; the
    ratio is that of the first ``MaterialMaps`` array each is made from)."""
    view = getattr(maps, "view", None)
    if view is None or not view.tileable:
        return {}
    ratios: dict[str, float] = {}
    for spec in specs:
        source = spec.sources[0] if spec.sources else None
        if source is not None and hasattr(maps, source):
            ratios[spec.name] = round(seam_ratio(getattr(maps, source), spec.period), 4)
    return {
        "tileable": True,
        "seam_ratio": ratios,
        "seam_ratio_note": "mean |difference| across the wrap edges / mean |difference| "
        "between interior neighbours (1 = as smooth as the interior)",
    }


def seam_parts(image: np.ndarray, period: float | None = None) -> tuple[float, float]:
    """(wrap, interior): the mean |difference| across the vertical wrap edge (last column vs
    first) plus that across the horizontal one (last row vs first), and the mean |difference|
    of horizontal interior neighbours plus that of vertical ones (pairs inside the map only:
    the wrap pairs are not interior). Each edge is compared with the neighbours across the same
    direction (a map of vertical stripes has no horizontal seam to dilute). ``period``:
    differences of angles modulo it (the shorter way round)."""
    a = np.asarray(image, dtype=np.float64)
    a = a[:, :, None] if a.ndim == 2 else a
    parts = (
        a[:, -1] - a[:, 0],
        a[-1] - a[0],
        np.diff(a, axis=1),
        np.diff(a, axis=0),
    )
    means = []
    for part in parts:
        values = np.abs(part[np.isfinite(part)])
        if period:
            values = np.mod(values, period)
            values = np.minimum(values, period - values)
        means.append(float(values.mean()) if values.size else 0.0)
    return means[0] + means[1], means[2] + means[3]


def ratio(edge: float, inner: float, scale: float) -> float:
    """edge / inner, 1.0 for a map that is constant up to float rounding (both below a
    millionth of its magnitude), inf for a step on an otherwise constant map."""
    tiny = 1e-6 * max(1.0, scale)
    if inner <= tiny:
        return 1.0 if edge <= tiny else math.inf
    return edge / inner
