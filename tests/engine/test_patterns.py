"""Bricks and Weave kernels: parity with the reference's fixtures, plus rule checks.

Point samples come from tests/data/parity/expressions.json; whole-grid checks rebuild the
``height`` (and ``alpha``) maps of fixture programs whose layers are a single pattern, so the
reference's arrays pin the kernels texel by texel (feathered values included).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.kernels.patterns import bricks, smooth_coverage, weave

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
EXPRESSIONS = {e["expr"]: e for e in json.loads((PARITY / "expressions.json").read_text())}
F32 = np.float32
Kernel = Callable[[np.ndarray, np.ndarray], np.ndarray]

BRICKS_DEFAULTS = dict(
    brick_width=1.0, brick_height=0.5, offset=0.5, mortar=0.05, axis="row", feather=0.0
)
WEAVE_DEFAULTS = dict(over=1, under=1, shift=1, freq_x=8.0, freq_y=8.0, warp_width=0.5, feather=0.0)


def bricks_with(**kw: float | str) -> Kernel:
    """Bricks(...) with the registry defaults for the parameters not given."""
    return lambda x, y: bricks(x, y, **{**BRICKS_DEFAULTS, **kw})


def weave_with(**kw: float) -> Kernel:
    """Weave(...) with the registry defaults (base_freq 8 for both axes)."""
    return lambda x, y: weave(x, y, **{**WEAVE_DEFAULTS, **kw})


PATTERN_EXPRESSIONS: dict[str, Kernel] = {
    "Bricks()": bricks_with(),
    "Bricks(brick_width=0.3, brick_height=0.2, offset=0.25, mortar=0.04, feather=0.02)": (
        bricks_with(brick_width=0.3, brick_height=0.2, offset=0.25, mortar=0.04, feather=0.02)
    ),
    "Weave()": weave_with(),
    "Weave(over=2, under=1, shift=1, base_freq_x=6, base_freq_y=4, warp_width=0.7, feather=0.1)": (
        weave_with(over=2, under=1, shift=1, freq_x=6.0, freq_y=4.0, warp_width=0.7, feather=0.1)
    ),
}


@pytest.mark.parametrize("dtype", [np.float64, F32], ids=["f64_axes", "f32_axes"])
@pytest.mark.parametrize("expr", sorted(PATTERN_EXPRESSIONS))
def test_fixture_expression(expr: str, dtype: type) -> None:
    entry = EXPRESSIONS[expr]
    key = "points_f32_axes" if dtype is F32 and "points_f32_axes" in entry else "points"
    for px, py, want in entry[key]:
        got = PATTERN_EXPRESSIONS[expr](np.full((1, 1), px, dtype), np.full((1, 1), py, dtype))
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


def fixture_map(name: str, size: tuple[int, int], key: str) -> np.ndarray:
    """One of the reference's composited float32 maps."""
    with np.load(PARITY / f"{name}_{size[0]}x{size[1]}.npz") as data:
        return data[key]


def masked_height(coverage: np.ndarray, scale: float) -> np.ndarray:
    """Height of a pattern layer ``coverage * scale`` over a flat opaque base of height 0:
    the layer counts where its float32 alpha is > 0 (the max with 0 is then its height)."""
    alpha = np.clip(coverage.astype(F32), 0, 1)
    layer = (coverage * np.float64(scale)).astype(F32)
    return np.where(alpha > 0, np.maximum(layer, F32(0)), F32(0))


PATTERN_PROGRAMS: dict[str, tuple[tuple[float, ...], Kernel, float]] = {
    "bricks": ((0, 0, 10, 10), bricks_with(), 0.5),
    "bricks_column": (
        (0, 0, 3, 3),
        bricks_with(
            brick_width=0.25,
            brick_height=0.9,
            offset=0.33,
            mortar=0.03,
            axis="column",
            feather=0.02,
        ),
        0.02,
    ),
    "denim_twill": (
        (0, 0, 1, 1),
        weave_with(over=2, under=1, shift=1, freq_x=24.0, freq_y=20.0, warp_width=0.9, feather=0.1),
        0.003,
    ),
    "satin_weave": (
        (0, 0, 0.5, 0.5),
        weave_with(over=4, under=1, shift=2, freq_x=30.0, freq_y=30.0, warp_width=0.95),
        0.001,
    ),
}


@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("name", sorted(PATTERN_PROGRAMS))
def test_pattern_program_height(name: str, size: tuple[int, int]) -> None:
    view, kernel, scale = PATTERN_PROGRAMS[name]
    coverage = kernel(*grid_axes(view, *size))
    assert coverage.shape == (size[1], size[0]) and coverage.dtype == np.float64
    np.testing.assert_array_equal(masked_height(coverage, scale), fixture_map(name, size, "height"))


@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
def test_satin_weave_alpha_includes_feathered_back_layer(size: tuple[int, int]) -> None:
    """Total coverage of two weave layers (negative shift, feather 0.2 on the back one)."""
    x, y = grid_axes((0, 0, 0.5, 0.5), *size)
    satin = weave_with(over=4, under=1, shift=2, freq_x=30.0, freq_y=30.0, warp_width=0.95)(x, y)
    back = weave_with(
        over=1, under=3, shift=-1, freq_x=30.0, freq_y=30.0, warp_width=0.7, feather=0.2
    )(x, y)
    running = (F32(1) - satin.astype(F32)) * (F32(1) - back.astype(F32))
    np.testing.assert_allclose(
        F32(1) - running, fixture_map("satin_weave", size, "alpha"), rtol=0, atol=2e-7
    )


@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
def test_carved_grooves_height(size: tuple[int, int]) -> None:
    """Height -0.02 - (1 - Bricks(offset=0, feather 0.03)) * 0.03 (float64 via Constants)."""
    x, y = grid_axes((0, 0, 2, 2), *size)
    mask = bricks_with(brick_width=0.5, brick_height=0.5, offset=0.0, mortar=0.06, feather=0.03)(
        x, y
    )
    height = (-0.02 - (1.0 - mask) * 0.03).astype(F32)
    np.testing.assert_array_equal(height, fixture_map("carved_grooves", size, "height"))


@pytest.mark.parametrize("size", GRID_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
def test_parquet_transforms_plank_support(size: tuple[int, int]) -> None:
    """Translate(Rotate(Scale(Bricks(1, 0.2, 0.37, 0.01), 1.5, 0.8), 30), 0.25, -0.1) on full
    rotated float32 grids. The plank layer's height (plank * 0.01 + positive noise) is the
    only non-zero height, so the fixture's height != 0 exactly where the plank covers."""
    x, y = grid_axes((0, 0, 2, 2), *size)
    tx, ty = x - 0.25, y - (-0.1)  # Translate samples at (x - dx, y - dy)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    rx, ry = c * tx + s * ty, -s * tx + c * ty  # Rotate
    plank = bricks_with(brick_width=1.0, brick_height=0.2, offset=0.37, mortar=0.01)(
        rx / 1.5,
        ry / 0.8,  # Scale
    )
    np.testing.assert_array_equal(plank > 0, fixture_map("parquet_transforms", size, "height") != 0)


# --- rule checks (spec §2.5, §2.6) --------------------------------------------------------------


def test_smooth_coverage_is_half_on_the_edge_and_hard_without_feather() -> None:
    s = np.array([-1.0, -0.25, 0.0, 0.25, 1.0])
    np.testing.assert_array_equal(smooth_coverage(s, 0.0), [0, 0, 1, 1, 1])
    np.testing.assert_array_equal(smooth_coverage(s, 0.5), [0, 0, 0.5, 1, 1])
    np.testing.assert_allclose(smooth_coverage(np.array([-0.125, 0.125]), 0.5), [0.15625, 0.84375])


def test_bricks_feather_gives_half_on_the_mortar_edge() -> None:
    """Row 0 of Bricks(): the left brick edge sits at x = mortar/2 = 0.025 (in float64)."""
    x = np.array([[0.025, 0.0125, 0.0375, 0.5]])
    y = np.array([[0.25]])
    got = bricks_with(feather=0.5)(x, y)
    assert got[0, 0] == 0.5
    assert 0 < got[0, 1] < 0.5 < got[0, 2] < got[0, 3] <= 1.0


def test_bricks_negative_offset_shifts_rows_left() -> None:
    """Row k is shifted by k * offset * width; offset -0.25 equals offset 0.75 (period 1)."""
    x = np.linspace(-3, 3, 241)[None, :] + 0.0123  # keep samples off the mortar edges
    y = np.linspace(-2, 2, 161)[:, None] + 0.0071
    np.testing.assert_array_equal(bricks_with(offset=-0.25)(x, y), bricks_with(offset=0.75)(x, y))
    shifted = bricks_with(offset=-0.25)(x, y)
    # In row 1 (0.5 <= y < 1) the mortar line sits at x = -0.25 (+ k).
    row1 = bricks_with(offset=-0.25)(np.array([[-0.25, 0.25, 0.75]]), np.array([[0.75]]))
    np.testing.assert_array_equal(row1, [[0, 1, 0]])
    assert shifted.shape == (161, 241)


def test_weave_negative_shift_mirrors_the_twill() -> None:
    """shift=-1 reverses the diagonal: the warp is on top where (col + row) mod 3 < 2.

    Samples sit at the cell centre in x (on the warp band) and 0.1 into the cell in y (off
    the weft band, half width 0.25), so the value is 1 exactly where the warp is on top."""
    cells = np.arange(-4, 4, dtype=np.float64)
    got = weave_with(over=2, under=1, shift=-1, freq_x=1.0, freq_y=1.0, warp_width=0.5)(
        (cells + 0.5)[None, :], (cells + 0.1)[:, None]
    )
    warp_on_top = np.mod(cells[None, :] + cells[:, None], 3) < 2
    np.testing.assert_array_equal(got, np.where(warp_on_top, 1.0, 0.0))


def test_weave_full_width_covers_everything() -> None:
    x = np.linspace(-1, 1, 33)[None, :]
    y = np.linspace(-1, 1, 17)[:, None]
    np.testing.assert_array_equal(weave_with(warp_width=1.0)(x, y), np.ones((17, 33)))


def test_full_coordinate_grids_match_separable_axes() -> None:
    """Rotated subtrees pass full (H, W) grids; the result must not depend on the layout."""
    x, y = grid_axes((-1.3, -0.7, 2.1, 1.9), 40, 24)
    xf, yf = np.broadcast_arrays(x, y)
    for kernel in (
        bricks_with(feather=0.05, axis="column", offset=-0.3),
        weave_with(over=3, under=2, shift=-2, feather=0.1),
    ):
        np.testing.assert_array_equal(kernel(xf.copy(), yf.copy()), kernel(x, y))


@pytest.mark.parametrize("feather", [0.0, 0.1])
def test_non_finite_and_huge_coordinates_raise_no_warnings(feather: float) -> None:
    import warnings

    x = np.array([[np.nan, np.inf, -np.inf, 3e38, 0.3]], dtype=F32)
    y = np.array([[0.2], [np.nan], [-3e38]], dtype=F32)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for axis in ("row", "column"):
            out = bricks_with(axis=axis, feather=feather)(x, y)
            assert out.shape == (3, 5) and out[0, 4] == 1.0
        out = weave_with(feather=feather)(x, y)
        assert out.shape == (3, 5)
