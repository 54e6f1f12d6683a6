"""Domain warping (field parameters of Translate/Scale/Rotate) and Tile instancing."""

from __future__ import annotations

import math

import numpy as np
import pytest

import matloom
import matloom.engine.interpret as interpret
from matloom.engine.backends import available_backends
from matloom.engine.evaluate import evaluate
from matloom.engine.grid import View, sample_axes
from matloom.engine.kernels import tile as T
from matloom.lang.cost import expanded_cost

BACKENDS = available_backends()


#: Defines of the coordinates: passed to a field parameter they vary per sample (X()/Y() written
#: there directly keep their language-1 meaning: evaluated once at the origin).
_COORDS = "Define(_x, X())\nDefine(_y, Y())\n"


def _height(expr: str, n: int = 48, backend: str = "numpy", view: str = "View(0, 0, 4, 4)"):
    program = f"{view}\n{_COORDS}Material(Layer(1).height({expr}))"
    return evaluate(program, n, n, backend=backend).height


def _axes(n: int = 48, view: tuple[float, ...] = (0, 0, 4, 4)):
    x, y = sample_axes(View(*view), n, n)
    return np.broadcast_arrays(x.astype(np.float64), y.astype(np.float64))


# ------------------------------------------------------------------ domain warping
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize(
    ("warped", "constant"),
    [
        (
            "Translate(fBm(seed=1), _x * 0 + 0.3, _y * 0 - 1.7)",
            "Translate(fBm(seed=1), 0.3, -1.7)",
        ),
        ("Scale(Worley(seed=2), _x * 0 + 2, 0.5)", "Scale(Worley(seed=2), 2, 0.5)"),
        ("Rotate(Bricks(), _x * 0 + 30)", "Rotate(Bricks(), 30)"),
        ("Rotate(fBm(seed=3), _y * 0 + 151)", "Rotate(fBm(seed=3), 151)"),
    ],
)
def test_constant_field_parameters_equal_constant_transforms(warped, constant, backend):
    """A field parameter that happens to be constant gives the constant transform, bit for bit."""
    assert np.array_equal(_height(warped, backend=backend), _height(constant, backend=backend))


@pytest.mark.parametrize("backend", BACKENDS)
def test_warps_are_pointwise(backend):
    """Translate(f, dx, dy)(p) = f(x - dx(p), y - dy(p)), and likewise for Scale and Rotate."""
    x, y = _axes()
    got = _height("Translate(X() + Y() * 10, _y * 0.5, _x * 0.25)", backend=backend)
    want = (x - (y * 0.5).astype(np.float32)) + (y - (x * 0.25).astype(np.float32)) * 10
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-5)
    got = _height("Scale(X() * Y(), _x + 1, 2)", backend=backend)
    np.testing.assert_allclose(got, (x / (x + 1)) * (y / 2), rtol=1e-5, atol=1e-6)
    got = _height("Rotate(X(), _x * 20)", backend=backend)
    rad = np.radians(x * 20)
    np.testing.assert_allclose(got, np.cos(rad) * x + np.sin(rad) * y, rtol=1e-5, atol=1e-5)


def test_warps_agree_between_backends():
    if len(BACKENDS) < 2:
        pytest.skip("needs the numba extra (the numba backend is not installed)")
    expr = "Rotate(Translate(fBm(seed=1), fBm(seed=2, base_freq=0.5), 0), Worley(seed=3) * 40)"
    assert np.array_equal(_height(expr, backend="numpy"), _height(expr, backend="numba"))


def test_coordinates_alone_keep_their_language_1_meaning():
    """X()/Y() written directly in a field parameter are evaluated once at the origin (W004),
    as in language 1 and the reference: Translate(X(), X() + 0.25, 0) is X() - 0.25."""
    x, _ = _axes()
    direct = "Material(Layer(1).height(Translate(X(), X() + 0.25, 0)))"
    assert [d.code for d in matloom.check(direct)] == ["W004"]
    got = evaluate("View(0, 0, 4, 4)\n" + direct, 48, 48, backend="numpy").height
    np.testing.assert_array_equal(got, np.broadcast_to((x - 0.25).astype(np.float32), got.shape))
    assert "X() + 0.25" not in matloom.format(matloom.parse(direct))  # printed as the number


def test_warp_parameters_check_print_and_cost():
    text = "Material(Layer(1).height(Translate(fBm(seed=1), fBm(seed=2) * 0.3, 0)))"
    assert matloom.check(text) == []
    assert "fBm(seed=2) * 0.3" in matloom.format(matloom.parse(text))
    # the warp's parameter is evaluated once (one more field than the plain transform)
    plain = expanded_cost(matloom.parse("Material(Layer(1).height(Translate(fBm(seed=1), 1, 0)))"))
    warped = expanded_cost(matloom.parse(text))
    assert warped.arrays > plain.arrays and warped.rotated_frames == 1


# ------------------------------------------------------------------ Tile
_MOTIF = "Fill(Ellipse(0, 0, 0.3, 0.2), feather=0.05)"


@pytest.mark.parametrize("backend", BACKENDS)
def test_tile_with_defaults_is_the_periodic_motif(backend):
    """Defaults: the motif centred in every cell, periodic with the cell size."""
    h = _height(f"Tile({_MOTIF}, 1, 0.5, seed=4)", n=64, backend=backend)
    assert np.array_equal(h[:, :16], h[:, 16:32])  # 64 texels over 4 units: 16 per unit
    assert np.array_equal(h[:8], h[8:16])  # 0.5 units: 8 texels
    x, y = _axes(64)
    cx = np.floor(x) + 0.5
    cy = np.floor(y / 0.5) * 0.5 + 0.25
    # the ellipse coverage at (x - cx, y - cy), computed by the shape kernel directly
    from matloom.engine.kernels import shapes

    ref = shapes.fill(shapes.EllipseGeom(0, 0, 0.3, 0.2), x - cx, y - cy, feather=0.05)
    np.testing.assert_array_equal(h, ref.astype(np.float32))


@pytest.mark.parametrize("backend", BACKENDS)
def test_tile_drops_cells_with_probability(backend):
    assert not _height(f"Tile({_MOTIF}, 1, 1, probability=0, seed=1)", backend=backend).any()
    full = _height(f"Tile({_MOTIF}, 1, 1, seed=1)", backend=backend)
    half = _height(f"Tile({_MOTIF}, 1, 1, probability=0.5, seed=1)", backend=backend)
    kept = np.array([half[i * 12 + 6, j * 12 + 6] > 0 for i in range(4) for j in range(4)])
    assert 0 < kept.sum() < 16 and np.all(half <= full)


def test_tile_instances_are_random_per_cell_and_seed():
    x, y = _axes(32)
    p = T.TileParams(1.0, 1.0, jitter=0.4, rotate=180, scale_min=0.5, scale_max=2, seed=9)
    lx, ly, keep = T.instance(x, y, p, 0, 0)
    q = T.TileParams(1.0, 1.0, jitter=0.4, rotate=180, scale_min=0.5, scale_max=2, seed=10)
    assert not np.array_equal(lx, T.instance(x, y, q, 0, 0)[0])
    # one instance per cell: the local frame maps the cell's samples rigidly (no tearing)
    cell = (np.floor(x) == 1) & (np.floor(y) == 2)
    pts = np.stack([x[cell], y[cell]], 1)
    loc = np.stack([lx[cell], ly[cell]], 1)
    d_world = np.linalg.norm(pts[1:] - pts[0], axis=1)
    d_local = np.linalg.norm(loc[1:] - loc[0], axis=1)
    ratio = d_world / d_local
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-9)  # a single scale in [0.5, 2]
    assert 0.5 <= ratio[0] <= 2 and keep[cell].all()


def test_tile_cos_sin_is_accurate():
    theta = np.linspace(-math.pi, math.pi, 10001)
    cos, sin = T.cos_sin(theta)
    np.testing.assert_allclose(cos, np.cos(theta), atol=1e-12)
    np.testing.assert_allclose(sin, np.sin(theta), atol=1e-12)


@pytest.mark.parametrize(
    "expr",
    [
        f"Tile({_MOTIF}, 1, 1, jitter=0.3, rotate=90, scale_min=0.6, scale_max=1.3, "
        "probability=0.7, offset=0.5, seed=3)",
        f"Tile({_MOTIF} * 0.5 + Stroke(Rect(-0.3, -0.3, 0.6, 0.6), 0.05), 1, 1, seed=3)",
        "Tile(Rotate(Fill(Rect(-0.9, -0.1, 1.8, 0.2)), 30), 0.7, 1, rotate=180, seed=3)",
        f"Tile(fBm(seed=2) * {_MOTIF}, 1, 1, jitter=0.2, seed=3)",
        "Tile(fBm(seed=2), 1, 1, jitter=0.2, seed=3)",  # no support: all 9 everywhere
    ],
)
def test_tile_support_culling_and_backends_agree(expr, monkeypatch):
    """Evaluating the motif only inside its support box gives exactly the values of
    evaluating all 9 instances everywhere, on every backend."""
    results = [_height(expr, backend=b) for b in BACKENDS]
    monkeypatch.setattr(interpret.Evaluator, "motif_support", lambda self, node: None)
    results += [_height(expr, backend=b) for b in BACKENDS]
    for r in results[1:]:
        np.testing.assert_array_equal(r, results[0])


def test_tile_counts_nine_instances_of_its_motif():
    from matloom.vocab import FUNCTIONS

    assert FUNCTIONS["Tile"].instances == len(T.NEIGHBOURS)  # the registry and the kernel agree
    one = expanded_cost(matloom.parse(f"Material(Layer(1).height({_MOTIF}))"))
    tiled = expanded_cost(matloom.parse(f"Material(Layer(1).height(Tile({_MOTIF}, 1, 1)))"))
    assert tiled.arrays == one.arrays * 9


def test_tile_checks_and_prints():
    text = f"Material(Layer(1).height(Tile({_MOTIF}, 1, 0.5, jitter=0.2, seed=1)))"
    assert matloom.check(text) == []
    assert f"Tile({_MOTIF}, 1, 0.5, jitter=0.2, seed=1)" in matloom.format(matloom.parse(text))
    bad = [d.code for d in matloom.check("Material(Layer(1).height(Tile(X(), 0, 1, seed=1)))")]
    assert bad and bad[0].startswith("E")
