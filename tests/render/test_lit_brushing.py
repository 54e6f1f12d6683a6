"""``anisotropy_angle`` is the brushing direction: the lit preview's anisotropic highlight must
stretch the way real grooves along that direction stretch it (across the lines).

The reference render is the preview's own shading of a bump map of parallel grooves with no
anisotropy; the other is a flat surface with ``anisotropy_angle`` = the grooves' direction. The
highlight of a light straight overhead is isolated by subtracting the same render lit from
below (which the surface does not see), and its elongation axis is the principal axis of its
second moments."""

from __future__ import annotations

import math

import numpy as np
import pytest

import matloom
from matloom.render.lit import available_backends, shade_lit
from matloom.render.preview import Light

N = 128
#: Groove cycles across the swatch and their height (enough slope to widen the highlight).
CYCLES, DEPTH = 24, 0.003


def _program(body: str) -> str:
    return (
        "Material(\n  Layer(1)\n    .basecolor(120, 120, 120)\n    .metallic(1)\n"
        f"    .roughness(0.2)\n{body}\n)"
    )


def grooves(brush_deg: float) -> str:
    """Sine grooves running along ``brush_deg``: the height varies across that direction."""
    t = math.radians(brush_deg)
    across = f"((X() * {-math.sin(t):.9f}) + (Y() * {math.cos(t):.9f}))"
    return _program(f"    .height(Sin({across} * {2 * math.pi * CYCLES:.9f}) * {DEPTH})")


def brushed(brush_deg: float) -> str:
    return _program(f"    .anisotropy(0.9)\n    .anisotropy_angle({brush_deg})")


def key_highlight(program: str, backend: str) -> np.ndarray:
    """Luminance of the overhead light's highlight alone (lit from above minus from below)."""
    maps = matloom.evaluate(program, N, N)
    above = shade_lit(maps, key_light=Light(0.0, 90.0), backend=backend)
    below = shade_lit(maps, key_light=Light(0.0, -90.0), backend=backend)
    diff = above.astype(np.float64).mean(-1) - below.astype(np.float64).mean(-1)
    return np.clip(diff, 0.0, None)


def elongation(weights: np.ndarray) -> tuple[float, float]:
    """(axis in degrees counter-clockwise from +x in [0, 180), major / minor std) of the
    weighted second moments; image rows grow downward, the swatch's +y is up."""
    rows, cols = np.mgrid[0 : weights.shape[0], 0 : weights.shape[1]]
    x, y = cols + 0.5, -(rows + 0.5)
    total = weights.sum()
    cx, cy = (weights * x).sum() / total, (weights * y).sum() / total
    cxx = (weights * (x - cx) ** 2).sum() / total
    cyy = (weights * (y - cy) ** 2).sum() / total
    cxy = (weights * (x - cx) * (y - cy)).sum() / total
    axis = math.degrees(0.5 * math.atan2(2 * cxy, cxx - cyy)) % 180.0
    half_trace, root = (cxx + cyy) / 2, math.sqrt(((cxx - cyy) / 2) ** 2 + cxy**2)
    return axis, math.sqrt((half_trace + root) / (half_trace - root))


def axial_gap(a: float, b: float) -> float:
    gap = abs(a - b) % 180.0
    return min(gap, 180.0 - gap)


@pytest.mark.parametrize("backend", available_backends())
@pytest.mark.parametrize("brush_deg", [0.0, 30.0, 90.0, 135.0])
def test_anisotropy_stretches_the_highlight_like_real_grooves(
    brush_deg: float, backend: str
) -> None:
    real_axis, real_ratio = elongation(key_highlight(grooves(brush_deg), backend))
    axis, ratio = elongation(key_highlight(brushed(brush_deg), backend))
    assert real_ratio > 1.15 and ratio > 1.3  # both visibly elongated
    assert axial_gap(real_axis, brush_deg + 90.0) < 20.0, real_axis  # grooves: across the lines
    assert axial_gap(axis, real_axis) < 20.0, (axis, real_axis)
