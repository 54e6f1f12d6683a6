"""Shapes, Fill and Stroke: parity with the reference's fixtures, plus rule and backend checks.

Point samples come from tests/data/parity/expressions.json; whole-grid checks rebuild the
``height`` maps of fixture programs whose layers are shape coverages (their heights are
constants or coverage * constant), so the reference's arrays pin every texel.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.kernels import shapes as sh
from matloom.engine.kernels.patterns import smooth_coverage
from matloom.engine.kernels.shapes import (
    CubicSeg,
    EllipseGeom,
    LineSeg,
    PathGeom,
    fill,
    flatten_path,
    make_rect,
    stroke,
)

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
EXPRESSIONS = {e["expr"]: e for e in json.loads((PARITY / "expressions.json").read_text())}
F32 = np.float32
BACKENDS = ("numpy", "numba")
Kernel = Callable[[np.ndarray, np.ndarray, str], np.ndarray]

STAR = PathGeom(
    0.5,
    0.9,
    (
        LineSeg(0.2649, 0.1764),
        LineSeg(0.8804, 0.6236),
        LineSeg(0.1196, 0.6236),
        LineSeg(0.7351, 0.1764),
    ),
)
HOOK = PathGeom(0, 0, (LineSeg(1, 1), CubicSeg(1.2, 1.5, -0.5, 2.5, -0.3, 2.7)))

SHAPE_EXPRESSIONS: dict[str, Kernel] = {
    "Fill(Rect(0.05, 0.1, 0.75, 0.45))": lambda x, y, b: fill(
        make_rect(0.05, 0.1, 0.75, 0.45), x, y, backend=b
    ),
    "Fill(Rect(0, 0, 1, 1, 0.3), feather=0.1)": lambda x, y, b: fill(
        make_rect(0, 0, 1, 1, 0.3), x, y, feather=0.1, backend=b
    ),
    "Stroke(Rect(0.1, 0.1, 0.8, 0.6, 0.1), 0.1, feather=0.05)": lambda x, y, b: stroke(
        make_rect(0.1, 0.1, 0.8, 0.6, 0.1), x, y, width=0.1, feather=0.05, backend=b
    ),
    "Fill(Ellipse(0.5, 0.5, 0.4, 0.2), feather=0.05)": lambda x, y, b: fill(
        EllipseGeom(0.5, 0.5, 0.4, 0.2), x, y, feather=0.05, backend=b
    ),
    "Fill(Path(0.5, 0.9, LineTo(0.2649, 0.1764), LineTo(0.8804, 0.6236), LineTo(0.1196, 0.6236), "
    "LineTo(0.7351, 0.1764)))": lambda x, y, b: fill(STAR, x, y, backend=b),
    "Fill(Path(0.5, 0.9, LineTo(0.2649, 0.1764), LineTo(0.8804, 0.6236), LineTo(0.1196, 0.6236), "
    'LineTo(0.7351, 0.1764)), mode="EvenOdd")': lambda x, y, b: fill(
        STAR, x, y, mode="EvenOdd", backend=b
    ),
    "Stroke(Path(0, 0, LineTo(1, 1), CubicTo(1.2, 1.5, -0.5, 2.5, -0.3, 2.7)), 0.2)": (
        lambda x, y, b: stroke(HOOK, x, y, width=0.2, backend=b)
    ),
}


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("dtype", [np.float64, F32], ids=["f64_axes", "f32_axes"])
@pytest.mark.parametrize("expr", sorted(SHAPE_EXPRESSIONS))
def test_fixture_expression(expr: str, dtype: type, backend: str) -> None:
    entry = EXPRESSIONS[expr]
    key = "points_f32_axes" if dtype is F32 and "points_f32_axes" in entry else "points"
    for px, py, want in entry[key]:
        x, y = np.full((1, 1), px, dtype), np.full((1, 1), py, dtype)
        got = SHAPE_EXPRESSIONS[expr](x, y, backend)
        assert got.shape == (1, 1) and got.dtype == np.float64
        assert got[0, 0] == float(want), f"{expr} at ({px}, {py})"


# --- whole-grid checks against fixture programs -------------------------------------------------

GRID_SIZES = [(64, 64), (48, 32)]


def grid_axes(view: tuple[float, float, float, float], width: int, height: int):
    """float32 X (1, W) and Y (H, 1) texel-centre axes, built as the reference does."""
    x1, y1, x2, y2 = view
    x = (np.arange(width, dtype=F32) + 0.5) * F32((x2 - x1) / width) + F32(x1)
    y = (np.arange(height, dtype=F32) + 0.5) * F32((y1 - y2) / height) + F32(y2)
    return x[None, :], y[:, None]


def fixture_height(name: str, size: tuple[int, int]) -> np.ndarray:
    """The reference's composited float32 height map."""
    with np.load(PARITY / f"{name}_{size[0]}x{size[1]}.npz") as data:
        return data["height"]


def composite_height(layers: list[tuple[np.ndarray, np.ndarray | float]]) -> np.ndarray:
    """Max layer height over layers whose float32 alpha is > 0, over a base of height 0."""
    shape = np.broadcast_shapes(*(np.shape(a) for a, _ in layers))
    best = np.zeros(shape, dtype=F32)
    for alpha, height in layers:
        present = np.clip(np.asarray(alpha).astype(F32), 0, 1) > 0
        level = np.broadcast_to(np.asarray(height, dtype=np.float64).astype(F32), shape)
        best = np.where(present, np.maximum(best, level), best)
    return best


def _star_nonzero(x: np.ndarray, y: np.ndarray, backend: str) -> np.ndarray:
    star = fill(STAR, x, y, backend=backend)
    return composite_height([(star, star * 0.02)])


def _star_evenodd(x: np.ndarray, y: np.ndarray, backend: str) -> np.ndarray:
    star = fill(STAR, x, y, mode="EvenOdd", feather=0.01, backend=backend)
    outline = stroke(STAR, x, y, width=0.02, backend=backend)
    return composite_height([(star, 0.01), (outline, 0.015)])


def _rivets_ellipse(x: np.ndarray, y: np.ndarray, backend: str) -> np.ndarray:
    def rivet(dx: float) -> np.ndarray:  # Translate(rivet, dx, 0) samples at (x - dx, y - 0)
        return fill(EllipseGeom(0.25, 0.5, 0.12, 0.12), x - dx, y - 0.0, feather=0.02)

    row = np.maximum(np.maximum(rivet(0.0), rivet(0.5)), np.maximum(rivet(1.0), rivet(1.5)))
    ring = stroke(EllipseGeom(1, 0.5, 0.9, 0.35), x, y, width=0.04, feather=0.01)
    return composite_height([(ring, 0.0), (row, row * 0.03)])


def _rounded_panels(x: np.ndarray, y: np.ndarray, backend: str) -> np.ndarray:
    panel = fill(make_rect(0.5, 0.5, 3, 3, 0.4), x, y, feather=0.05)
    frames = np.maximum(
        stroke(make_rect(1, 1, 2, 2, 0.25), x, y, width=0.08),
        stroke(make_rect(0.25, 0.25, 3.5, 3.5), x, y, width=0.05),
    )
    badge = fill(make_rect(1.5, 1.5, 1, 1, 5), x, y)  # radius clamped to 0.5: a circle
    strip = fill(make_rect(0.8, 3.1, 0.9, 0.2), x, y)
    return composite_height([(panel, 0.05), (frames, 0.03), (badge, 0.06), (strip, 0.055)])


def _leaf_cubic(x: np.ndarray, y: np.ndarray, backend: str) -> np.ndarray:
    leaf_path = PathGeom(
        0.5,
        0.05,
        (CubicSeg(0.95, 0.3, 0.85, 0.8, 0.5, 0.95), CubicSeg(0.15, 0.8, 0.05, 0.3, 0.5, 0.05)),
    )
    vein_path = PathGeom(0.5, 0.08, (CubicSeg(0.52, 0.4, 0.48, 0.6, 0.5, 0.9), LineSeg(0.5, 0.92)))
    leaf = fill(leaf_path, x, y, feather=0.01, backend=backend)
    vein = stroke(vein_path, x, y, width=0.015, feather=0.005, backend=backend)
    return composite_height([(leaf, 0.004), (vein * leaf, 0.006)])


SHAPE_PROGRAMS = {
    "star_nonzero": ((0, 0, 1, 1), _star_nonzero),
    "star_evenodd": ((-0.1, -0.1, 1.1, 1.1), _star_evenodd),
    "rivets_ellipse": ((0, 0, 2, 1), _rivets_ellipse),
    "rounded_panels": ((0, 0, 4, 4), _rounded_panels),
    "leaf_cubic": ((0, 0, 1, 1), _leaf_cubic),
}


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("name", sorted(SHAPE_PROGRAMS))
def test_shape_program_height(name: str, size: tuple[int, int], backend: str) -> None:
    view, build = SHAPE_PROGRAMS[name]
    got = build(*grid_axes(view, *size), backend)
    np.testing.assert_array_equal(got, fixture_height(name, size))


# --- rule checks (spec §2.8) --------------------------------------------------------------------


@pytest.mark.parametrize("backend", BACKENDS)
def test_feather_gives_half_exactly_on_the_outline(backend: str) -> None:
    x, y = np.array([[1.0, 0.5, 0.9]]), np.array([[0.5]])
    rect = fill(make_rect(0, 0, 1, 1), x[:, :1], y, feather=0.5)
    circle = fill(EllipseGeom(0.0, 0.5, 0.5, 0.5), x[:, 1:2], y, feather=0.5)
    vertex = fill(STAR, np.array([[0.5]]), np.array([[0.9]]), feather=0.5, backend=backend)
    line = stroke(
        HOOK,
        np.array([[0.5]]),
        np.array([[0.5 - 0.1 * 2**0.5]]),
        width=0.2,
        feather=0.5,
        backend=backend,
    )
    assert rect[0, 0] == 0.5 and circle[0, 0] == 0.5 and vertex[0, 0] == 0.5
    assert line[0, 0] == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize("backend", BACKENDS)
def test_pentagram_centre_depends_on_the_fill_rule(backend: str) -> None:
    """The star's inner pentagon is wound twice: inside for NonZero, outside for EvenOdd."""
    x, y = np.array([[0.5, 0.5, 0.05]]), np.array([[0.45, 0.75, 0.5]])  # centre, a tip, outside
    assert list(fill(STAR, x, y, backend=backend)[0]) == [1.0, 1.0, 0.0]
    assert list(fill(STAR, x, y, mode="EvenOdd", backend=backend)[0]) == [0.0, 1.0, 0.0]


def test_cubic_flattening_has_sixteen_points_ending_exactly_on_the_end_point() -> None:
    points = flatten_path(HOOK)
    assert points.shape == (1 + 1 + sh.CUBIC_STEPS, 2) and points.dtype == np.float64
    assert tuple(points[-1]) == (-0.3, 2.7) and tuple(points[1]) == (1.0, 1.0)
    straight = flatten_path(PathGeom(0, 0, (CubicSeg(1, 1, 2, 2, 3, 3),)))
    np.testing.assert_allclose(straight[1:, 0], np.arange(1, 17) * 3 / 16, rtol=1e-15)


def test_rect_radius_is_clamped_and_circle_sdf_is_exact() -> None:
    assert make_rect(0, 0, 1, 3, radius=5).radius == 0.5
    assert sh.ellipse_sdf(EllipseGeom(0, 0, 2, 2), np.array(3.0), np.array(4.0)) == 3.0
    with np.errstate(all="raise"):
        centre = sh.ellipse_sdf(EllipseGeom(1, 1, 0.3, 0.7), np.array([1.0]), np.array([1.0]))
    assert centre[0] == -0.3


@pytest.mark.parametrize("backend", BACKENDS)
def test_degenerate_path_is_a_point(backend: str) -> None:
    dot = PathGeom(0.5, 0.5, (LineSeg(0.5, 0.5),))
    x, y = np.array([[0.5, 0.6]]), np.array([[0.5]])
    np.testing.assert_array_equal(fill(dot, x, y, backend=backend), [[1.0, 0.0]])
    np.testing.assert_array_equal(stroke(dot, x, y, width=0.25, backend=backend), [[1.0, 1.0]])


@pytest.mark.parametrize("backend", BACKENDS)
def test_empty_grids(backend: str) -> None:
    for x, y in ((np.zeros((1, 0)), np.zeros((3, 1))), (np.zeros((1, 4)), np.zeros((0, 1)))):
        shape = np.broadcast_shapes(x.shape, y.shape)
        assert fill(STAR, x, y, backend=backend).shape == shape
        assert stroke(HOOK, x, y, width=0.1, backend=backend).shape == shape


def test_invalid_arguments_raise() -> None:
    x, y = np.zeros((1, 2)), np.zeros((2, 1))
    with pytest.raises(ValueError):
        fill(STAR, x, y, mode="Winding")
    with pytest.raises(ValueError):
        fill(STAR, x, y, backend="cuda")
    with pytest.raises(ValueError):
        stroke(make_rect(0, 0, 1, 1), x, y, width=0.1, backend="cuda")
    with pytest.raises(TypeError):
        fill("Rect", x, y)


@pytest.mark.parametrize("backend", BACKENDS)
def test_output_is_a_fresh_full_float64_grid(backend: str) -> None:
    x, y = np.linspace(0, 1, 7, dtype=F32)[None, :], np.linspace(0, 1, 5, dtype=F32)[:, None]
    for out in (fill(STAR, x, y, backend=backend), stroke(make_rect(0, 0, 1, 1), x, y, width=0.1)):
        assert out.shape == (5, 7) and out.dtype == np.float64 and out.flags.writeable


# --- backends and culling -----------------------------------------------------------------------


def random_path(rng: np.random.Generator, n_segments: int) -> PathGeom:
    """A random path mixing lines and cubics (repeated points included)."""
    segments: list[LineSeg | CubicSeg] = []
    for _ in range(n_segments):
        if rng.random() < 0.4:
            segments.append(CubicSeg(*rng.uniform(-1, 2, 6)))
        elif rng.random() < 0.1 and segments:
            segments.append(LineSeg(segments[-1].x, segments[-1].y))  # zero-length edge
        else:
            segments.append(LineSeg(*np.round(rng.uniform(-1, 2, 2), 2)))
    return PathGeom(*np.round(rng.uniform(-1, 2, 2), 2), tuple(segments))


def random_grids(rng: np.random.Generator) -> list[tuple[np.ndarray, np.ndarray]]:
    """Separable float32 axes (hitting vertices on a 0.01 lattice), a rotated full grid,
    a float64 grid with NaN/inf samples, one rotated row and column, and mirrored axes."""
    ax = (np.arange(-120, 220, 3, dtype=F32) * F32(0.01))[None, :]
    ay = (np.arange(230, -130, -4, dtype=F32) * F32(0.01))[:, None]
    c, s = np.cos(0.7), np.sin(0.7)
    rx, ry = c * ax + s * ay, -s * ax + c * ay
    wild_x = rng.uniform(-1.5, 2.5, (23, 31))
    wild_y = rng.uniform(-1.5, 2.5, (23, 31))
    wild_x[3, 4], wild_y[5, 6], wild_x[7, 8] = np.nan, np.inf, -np.inf
    one_row, one_col = (rx[:1], ry[:1]), (rx[:, :1], ry[:, :1])  # both coordinates vary
    mirrored = (ax[:, ::-1], ay[::-1])  # a reversed View: x falls along each row
    return [(ax, ay), (rx, ry), (wild_x, wild_y), one_row, one_col, mirrored]


@pytest.mark.parametrize("seed", range(5))
def test_numba_matches_numpy_on_random_paths_and_grids(seed: int) -> None:
    from matloom.engine.kernels import shapes_numba

    rng = np.random.default_rng(seed)
    points = flatten_path(random_path(rng, int(rng.integers(1, 9))))
    for x, y in random_grids(rng):
        for mode in (None, "NonZero", "EvenOdd"):
            for cutoff in (np.inf, 0.0, 0.05):
                d_np, in_np = sh.path_distance_inside(points, x, y, mode, cutoff)
                d_nb, in_nb = shapes_numba.path_distance_inside(points, x, y, mode, cutoff)
                np.testing.assert_array_equal(d_np, d_nb)
                np.testing.assert_array_equal(in_np, in_nb)


@pytest.mark.parametrize("seed", range(3))
def test_culled_coverage_equals_the_uncut_computation(seed: int) -> None:
    """fill/stroke skip far edges (cutoff); coverage must equal the exact-distance formula."""
    rng = np.random.default_rng(100 + seed)
    path = random_path(rng, int(rng.integers(2, 7)))
    for x, y in random_grids(rng)[:2]:
        for feather in (0.0, 0.02, 0.3):
            for mode in ("NonZero", "EvenOdd"):
                exact = -sh.signed_distance(path, x, y, mode=mode)
                want = smooth_coverage(exact, feather)
                for backend in BACKENDS:
                    got = fill(path, x, y, mode=mode, feather=feather, backend=backend)
                    np.testing.assert_array_equal(got, want)
            distance, _ = sh.path_distance_inside(flatten_path(path), x, y, None)
            want = smooth_coverage(0.05 - distance, feather)
            for backend in BACKENDS:
                got = stroke(path, x, y, width=0.1, feather=feather, backend=backend)
                np.testing.assert_array_equal(got, want)


def test_cutoff_keeps_values_up_to_it_and_sends_the_rest_to_inf() -> None:
    x, y = np.linspace(-1, 2, 61)[None, :], np.linspace(-1, 2, 45)[:, None]
    points = flatten_path(STAR)
    exact, _ = sh.path_distance_inside(points, x, y, "NonZero")
    cut, _ = sh.path_distance_inside(points, x, y, "NonZero", cutoff=0.1)
    near = exact <= 0.1
    np.testing.assert_array_equal(cut[near], exact[near])
    assert np.all(np.isinf(cut[~near])) and near.any() and (~near).any()


@pytest.mark.parametrize("backend", BACKENDS)
def test_non_finite_and_huge_coordinates_raise_no_warnings(backend: str) -> None:
    import warnings

    x = np.array([[np.nan, np.inf, -np.inf, 3e38, 0.5]], dtype=F32)
    y = np.array([[0.5], [np.nan], [-3e38]], dtype=F32)
    shapes = (make_rect(0, 0, 1, 1, 0.2), EllipseGeom(0.5, 0.5, 0.3, 0.3), STAR, HOOK)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for shape in shapes:
            for feather in (0.0, 0.1):
                assert fill(shape, x, y, feather=feather, backend=backend).shape == (3, 5)
                out = stroke(shape, x, y, width=0.1, feather=feather, backend=backend)
                assert out.shape == (3, 5)
