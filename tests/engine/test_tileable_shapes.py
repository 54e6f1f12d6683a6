"""Tileable shapes (Fill, Stroke outside a Tile motif) and the seam ratio of angle maps.

In a tileable output a shape is drawn with its images one View period apart, so that a shape
crossing the View's edge comes back on the opposite side (``matloom.engine.rules.fields``,
``periodic.image_shifts``); shapes under a Rotate are warned about (W009).
"""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import prepare
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import Evaluator
from matloom.engine.maps import View
from matloom.engine.tiling import seam_ratio, seam_ratios
from matloom.ops.periodic import image_shifts

BACKENDS = [b for b in ("numpy", "numba") if b in available_backends()]

SHAPES = {
    "ellipse over a corner": "Fill(Ellipse(0.3, 0.45, 0.3, 0.2), feather=0.02)",
    "rounded rect stroke": "Stroke(Rect(1.1, -0.7, 0.6, 0.5, 0.1), 0.05, feather=0.01)",
    "path fill": "Fill(Path(0.2, -0.45, CubicTo(0.6, 0.7, 1.4, -0.2, 1.2, 0.45), "
    "LineTo(0.2, 0.3)), feather=0.01)",
    "even-odd path": "Fill(Path(0, 0, LineTo(1.2, 0.3), LineTo(0.1, 0.45), LineTo(1.1, -0.3)), "
    'mode="EvenOdd")',
    "open path stroke": "Stroke(Path(0.1, 0.2, LineTo(1.3, 0.4)), 0.03)",
    "translated": "Translate(Fill(Ellipse(0, 0, 0.2, 0.2)), 0.3, 0.4)",
    "scaled": "Scale(Stroke(Ellipse(0.1, 0, 0.2, 0.2), 0.03), 0.5, 2)",
    "wider than the View": "Fill(Rect(-1.5, 0.4, 3, 0.05))",
    "warped by periodic offsets": "Translate(Fill(Ellipse(1.2, 0.4, 0.25, 0.15)), "
    "fBm(octaves=2, base_freq=2, seed=3) * 0.05, 0)",
}
VIEW = (0.25, -0.5, 1.25, 0.5)


def doubled(expr: str, backend: str, n: int = 48) -> np.ndarray:
    """``expr`` on twice the View (2n x 2n texels) with the View's periods, float64."""
    x1, y1, x2, y2 = VIEW
    w, h = x2 - x1, y2 - y1
    program = prepare(f"View({x1}, {y1}, {x2}, {y2})\nMaterial(Layer(1).height({expr}))")
    node = program.layers[0].channel("height").args[0]
    x, y = sample_axes(View(x1, y1, x1 + 2 * w, y1 + 2 * h), 2 * n, 2 * n)
    ev = Evaluator(program, x, y, get_backend(backend), periods=(w, h))
    value = np.asarray(ev.field(node), dtype=np.float64)
    return np.broadcast_to(value, (2 * n, 2 * n))


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name", list(SHAPES))
def test_shape_repeats_with_the_view(name: str, backend: str) -> None:
    v = doubled(SHAPES[name], backend)
    n = v.shape[0] // 2
    assert np.isfinite(v).all() and v.max() > 0.5 and v.min() < 0.5
    # float32 sample coordinates: an edge texel may flip where x + W rounds differently
    assert np.mean(np.abs(v[:, n:] - v[:, :n]) > 1e-3) < 0.002
    assert np.mean(np.abs(v[n:] - v[:n]) > 1e-3) < 0.002


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
@pytest.mark.parametrize("name", list(SHAPES))
def test_backends_agree_bit_for_bit(name: str) -> None:
    assert np.array_equal(doubled(SHAPES[name], "numpy"), doubled(SHAPES[name], "numba"))


PROGRAM = """View(0, 0, 1, 1, tileable=True)
Material(
  Layer(1).basecolor(200, 40, 30).height(Fill(Ellipse(0.9, 0.95, 0.3, 0.2), feather=0.02) * 0.02),
  Layer(Stroke(Path(0.1, 0.2, LineTo(1.3, 0.9)), 0.03)).basecolor(20, 20, 200).height(0.03)
)"""


def test_a_shape_across_the_edge_has_no_seam() -> None:
    tiled = matloom.evaluate(PROGRAM, 96, 96, backend=BACKENDS[-1])
    plain = matloom.evaluate(PROGRAM.replace(", tileable=True", ""), 96, 96, backend="numpy")
    for name in ("height", "normal", "ao", "basecolor_linear"):
        assert seam_ratio(getattr(tiled, name)) <= 1.2, name
    assert seam_ratio(plain.height) > 3.0  # the ellipse is cut at the edges


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
def test_tileable_shapes_same_bits_on_both_schedules() -> None:
    a = matloom.evaluate(PROGRAM, 80, 56, backend="numpy")
    b = matloom.evaluate(PROGRAM, 80, 56, backend="numba")  # banded (fused) schedule
    for name, array in a.arrays().items():
        assert np.array_equal(array, getattr(b, name), equal_nan=True), name


def test_image_shifts() -> None:
    # a shape inside the samples: only itself; across the right edge: also one period left
    assert image_shifts((0.2, 0.2, 0.4, 0.4), (1.0, 1.0), (0, 0, 1, 1)) == [(0.0, 0.0)]
    shifts = image_shifts((0.8, 0.2, 1.2, 0.4), (1.0, 1.0), (0, 0, 1, 1))
    assert shifts == [(0.0, 0.0), (-1.0, 0.0)]
    corner = image_shifts((-0.1, -0.1, 0.1, 0.1), (1.0, 1.0), (0, 0, 1, 1))
    assert corner is not None and set(corner) == {(0, 0), (1, 0), (0, 1), (1, 1)}
    assert image_shifts((-100, 0, 100, 0.1), (1.0, 1.0), (0, 0, 1, 1)) is None  # too many
    assert image_shifts((0, 0, float("inf"), 1), (1.0, 1.0), (0, 0, 1, 1)) is None


def test_rotated_shapes_are_warned_about() -> None:
    text = (
        "View(0, 0, 2, 2, tileable=True)\nMaterial(Layer(1).height("
        "Rotate(Fill(Ellipse(0.5, 0.5, 0.3, 0.2)), 30) + Stroke(Rect(1.8, 1, 0.4, 0.2), 0.01)"
        " + Tile(Rotate(Fill(Rect(0, 0, 0.1, 0.1)), 20), 0.5, 0.5, seed=1)))"
    )
    found = [(d.code, d.message) for d in matloom.check(text) if d.code in ("W009", "W010")]
    assert found == [("W009", "tileable: Fill under Rotate cannot repeat with the View")]


def test_seam_ratio_of_angles_goes_round_the_circle() -> None:
    """anisotropy_angle repeats every 180 degrees: 179 and 1 are 2 degrees apart."""
    ramp = np.tile(np.arange(180.0), (4, 1))  # 0, 1, ..., 179 degrees: a smooth turn
    assert seam_ratio(ramp) == pytest.approx(179.0)  # read as numbers: 179 back to 0
    assert seam_ratio(ramp, period=180.0) == pytest.approx(1.0)
    maps = {"anisotropy_angle": ramp, "roughness": ramp / 180.0}
    ratios = seam_ratios(maps)
    assert ratios["anisotropy_angle"] == pytest.approx(1.0)
    assert ratios["roughness"] != pytest.approx(1.0)
