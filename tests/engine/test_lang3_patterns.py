"""Language 3 of Bricks and Weave: brick row/column indices (and the documented row-shift
direction), Weave's separate weft width and per-thread random values, on every backend against
direct formulas; the backends agree bit for bit; tileable output repeats; canonical text of
programs without the new keywords is unchanged."""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import prepare
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import Evaluator
from matloom.engine.kernels.noise_numpy import worley_hash
from matloom.engine.kernels.opensimplex import worley_seed_term
from matloom.engine.kernels.patterns import WARP_SALT, WEFT_SALT
from matloom.engine.maps import View
from matloom.lang.seeds import canonicalize_seeds

BACKENDS = [b for b in ("numpy", "numba") if b in available_backends()]
_BRICK = dict(brick_width=0.5, brick_height=0.25, mortar=0.02, feather=0.0)
_WEAVE = dict(over=2, under=1, shift=1, freq_x=4.0, freq_y=4.0, warp_width=0.8, feather=0.0)


def _grid(n: int = 64, lo: float = -1.3, hi: float = 1.7, dtype: type = np.float32) -> tuple:
    axis = np.linspace(lo, hi, n, dtype=dtype)
    return axis[None, :], axis[::-1, None].copy()


def _full(v: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    return np.broadcast_to(v, np.broadcast_shapes(x.shape, y.shape))


# ---------------------------------------------------------------------------- Bricks
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("axis", ["row", "column"])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_brick_indices_match_the_formula(backend: str, axis: str, dtype: type) -> None:
    x, y = _grid(dtype=dtype)
    xf, yf = (np.broadcast_to(a, (64, 64)).astype(np.float64) for a in (x, y))
    bw, bh, off = 0.5, 0.25, 0.3
    kernel = get_backend(backend).bricks
    kw = dict(_BRICK, offset=off, axis=axis)
    row = kernel(x, y, output="row", **kw)
    col = kernel(x, y, output="column", **kw)
    if axis == "row":
        want_row = np.floor(yf / bh)
        want_col = np.floor((xf - want_row * off * bw) / bw)
    else:
        want_col = np.floor(xf / bw)
        want_row = np.floor((yf - want_col * off * bh) / bh)
    # float32 coordinates: compare away from the cell borders
    inner = kernel(x, y, output="edge", **{**kw, "mortar": 0.0}) > 1e-4
    assert row.dtype == np.float64 and (row == np.floor(row)).all()
    np.testing.assert_array_equal(row[inner], want_row[inner])
    np.testing.assert_array_equal(col[inner], want_col[inner])
    # constant over each brick: the cell value changes exactly where an index does
    value = kernel(x, y, output="cell_value", seed=4, **kw)
    same = (np.diff(row, axis=1) == 0) & (np.diff(col, axis=1) == 0)
    assert (np.diff(value, axis=1)[same] == 0).all()


@pytest.mark.parametrize("backend", BACKENDS)
def test_offset_shifts_the_next_course_right(backend: str) -> None:
    """axis="row": the course one brick_height up is shifted by +offset * brick_width (to the
    right); axis="column": the column one brick_width right is shifted up."""
    kernel = get_backend(backend).bricks
    kw = dict(brick_width=1.0, brick_height=1.0, offset=0.25, mortar=0.0, feather=0.0)
    xs = np.array([[0.2, 0.3]])
    # row 1 (y = 1.5): the brick border is at x = 0.25
    col = kernel(xs, np.array([[1.5]]), output="column", axis="row", **kw)
    assert col.tolist() == [[-1.0, 0.0]]
    assert kernel(xs, np.array([[0.5]]), output="column", axis="row", **kw).tolist() == [[0, 0]]
    # column 1 (x = 1.5): the border between rows is at y = 0.25
    ys = np.array([[0.2], [0.3]])
    row = kernel(np.array([[1.5]]), ys, output="row", axis="column", **kw)
    assert row.tolist() == [[-1.0], [0.0]]


# ---------------------------------------------------------------------------- Weave
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_weft_width_sets_the_horizontal_threads(backend: str, dtype: type) -> None:
    x, y = _grid(128, 0.0, 2.0, dtype)
    weave = get_backend(backend).weave
    mask = weave(x, y, **_WEAVE, weft_width=0.3)
    u, v = (np.broadcast_to(a, mask.shape).astype(np.float64) * 4.0 for a in (x, y))
    col, row = np.floor(u), np.floor(v)
    warp = np.mod(col - row, 3) < 2
    want = np.where(warp, np.abs(u - col - 0.5) <= 0.4, np.abs(v - row - 0.5) <= 0.15)
    edge = np.minimum(np.abs(np.abs(u - col - 0.5) - 0.4), np.abs(np.abs(v - row - 0.5) - 0.15))
    far = edge > 1e-4  # away from the thread borders (float32 coordinates)
    np.testing.assert_array_equal(mask[far], want[far].astype(np.float64))
    across = weave(x, y, **{**_WEAVE, "warp_width": 0.5}, weft_width=0.25, output="across")
    want_a = np.where(warp, (u - col - 0.25) / 0.5, (v - row - 0.375) / 0.25).clip(0, 1)
    np.testing.assert_allclose(across, want_a, atol=1e-4)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("output", ["mask", "warp", "weft", "across", "along"])
def test_weft_width_default_is_the_warp_width(backend: str, output: str) -> None:
    x, y = _grid()
    weave = get_backend(backend).weave
    kw = dict(_WEAVE, feather=0.05, output=output)
    base = weave(x, y, **kw)
    assert np.array_equal(base, weave(x, y, **kw, weft_width=None), equal_nan=True)
    assert np.array_equal(base, weave(x, y, **kw, weft_width=0.8), equal_nan=True)


@pytest.mark.parametrize("backend", BACKENDS)
def test_thread_value_is_the_thread_hash(backend: str) -> None:
    x, y = _grid(96, -2.0, 2.0)
    value = get_backend(backend).weave(x, y, **_WEAVE, output="thread_value", seed=11)
    u, v = (np.broadcast_to(a, value.shape).astype(np.float64) * 4.0 for a in (x, y))
    col, row = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
    warp = np.mod(col - row, 3) < 2
    term = worley_seed_term(11)
    zero = np.zeros_like(col)
    want = np.where(
        warp, worley_hash(col, zero, term, WARP_SALT), worley_hash(zero, row, term, WEFT_SALT)
    )
    np.testing.assert_array_equal(value, want)
    assert ((value >= 0) & (value < 1)).all()
    # constant along each warp thread where it is on top
    for c in np.unique(col[warp]):
        assert np.unique(value[warp & (col == c)]).size == 1


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
@pytest.mark.parametrize(
    "kw",
    [
        dict(output="thread_value", seed=3),
        dict(output="thread_value", seed=3, wrap=(8, 0)),
        dict(output="across", weft_width=0.35),
        dict(output="mask", weft_width=0.35, feather=0.1),
        dict(output="weft", weft_width=0.35, feather=0.1),
    ],
)
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_weave_backends_agree(kw: dict, dtype: type) -> None:
    x, y = _grid(80, -3.0, 5.0, dtype)
    x = np.concatenate([x, np.array([[np.nan, np.inf]], dtype=dtype)], axis=1)
    args = {**_WEAVE, **kw}
    a = get_backend("numpy").weave(x, y, **args)
    b = get_backend("numba").weave(x, y, **args)
    assert np.array_equal(a, b, equal_nan=True)


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
@pytest.mark.parametrize("output", ["row", "column"])
@pytest.mark.parametrize("axis", ["row", "column"])
def test_brick_backends_agree(output: str, axis: str) -> None:
    x, y = _grid(80, -30.0, 50.0)
    x = np.concatenate([x, np.array([[np.nan, np.inf]], dtype=np.float32)], axis=1)
    kw = dict(_BRICK, offset=0.37, axis=axis, output=output)
    a = get_backend("numpy").bricks(x, y, **kw)
    b = get_backend("numba").bricks(x, y, **kw)
    assert np.array_equal(a, b, equal_nan=True)


# ---------------------------------------------------------------------------- programs
def _doubled(expr: str, backend: str, n: int = 48) -> np.ndarray:
    """``expr`` on twice the View (0.25, -0.5)-(1.25, 0.5) with the View's periods."""
    program = prepare(f"View(0.25, -0.5, 1.25, 0.5)\nMaterial(Layer(1).height({expr}))")
    node = program.layers[0].channel("height").args[0]
    x, y = sample_axes(View(0.25, -0.5, 2.25, 1.5), 2 * n, 2 * n)
    ev = Evaluator(program, x, y, get_backend(backend), periods=(1.0, 1.0))
    return np.broadcast_to(np.asarray(ev.field(node), dtype=np.float64), (2 * n, 2 * n))


TILEABLE = {
    "rows": 'Bricks(brick_width=0.25, brick_height=0.125, offset=0.5, output="row")',
    "columns": 'Bricks(brick_width=0.25, brick_height=0.125, offset=0.25, output="column")',
    "column axis": 'Bricks(brick_width=0.25, brick_height=0.5, axis="column", output="row")',
    "threads": 'Weave(over=2, under=1, base_freq=6, output="thread_value", seed=5)',
}


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name", list(TILEABLE))
def test_indices_and_threads_repeat_with_the_view(name: str, backend: str) -> None:
    v = _doubled(TILEABLE[name], backend)
    n = v.shape[0] // 2
    assert np.isfinite(v).all() and np.std(v) > 1e-3
    np.testing.assert_array_equal(v[:, n:], v[:, :n])
    np.testing.assert_array_equal(v[n:], v[:n])
    if name != "threads":
        assert v.min() >= 0 and v.max() <= 8  # wrapped to the counts per period


def test_canonical_text_keeps_defaults_out() -> None:
    plain = matloom.format("Material(Layer(1).height(Weave(over=2, base_freq=9) * Bricks()))")
    assert ".height((Weave(over=2, base_freq=9) * Bricks()))" in plain
    wide = matloom.format("Material(Layer(1).height(Weave(base_freq=9, weft_width=0.3)))")
    assert ".height(Weave(base_freq=9, weft_width=0.3))" in wide
    program = canonicalize_seeds(
        matloom.parse(
            'Material(Layer(1).height(Weave(output="thread_value") + Bricks(output="row")))'
        )
    )
    text = matloom.format(program)
    assert 'thread_value", seed=' in text and 'Bricks(output="row")' in text
