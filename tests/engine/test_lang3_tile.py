"""Language 3 of Tile and Choose: per-instance values (random value, row / column index,
rotation angle, motif-local u / v) against direct formulas (splitmix64 written out in Python
integers), on every backend with the same bits; tileable output repeats; ``Choose`` picks
``floor(index * n)`` clamped, and composes with Tile for a per-instance motif."""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import prepare
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import Evaluator
from matloom.engine.maps import View
from matloom.engine.rules.instancing import pick

BACKENDS = [b for b in ("numpy", "numba") if b in available_backends()]
MASK = (1 << 64) - 1
DISC = "Fill(Ellipse(0, 0, 0.3, 0.3))"


def _mix(z: int) -> int:
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    return z ^ (z >> 31)


def _uniform(seed: int, stream: int, row: int, col: int) -> float:
    key = (seed * 0x9E3779B97F4A7C15 + stream) & MASK
    z = _mix((key + 0x9E3779B97F4A7C15) & MASK)
    z = _mix((z + (row & MASK)) & MASK)
    z = _mix((z + (col & MASK)) & MASK)
    return (z >> 11) / 2.0**53


def _field(expr: str, backend: str, n: int = 64, view: tuple = (-1.0, -1.0, 3.0, 3.0)) -> tuple:
    """``expr`` on an n x n grid of the View (float64), with the sample coordinates."""
    program = prepare(f"View{view}\nMaterial(Layer(1).height({expr}))")
    node = program.layers[0].channel("height").args[0]
    x, y = sample_axes(View(*view), n, n)
    value = Evaluator(program, x, y, get_backend(backend)).field(node)
    xx, yy = (np.broadcast_to(a, (n, n)).astype(np.float64) for a in (x, y))
    return np.broadcast_to(np.asarray(value, np.float64), (n, n)), xx, yy


def _tile(output: str, **kw: object) -> str:
    extra = "".join(f", {k}={v}" for k, v in kw.items())
    return f'Tile({DISC}, 1, 1{extra}, seed=7, output="{output}")'


@pytest.mark.parametrize("backend", BACKENDS)
def test_outputs_of_separate_instances(backend: str) -> None:
    """Discs of radius 0.3 centred in unit cells: each sample in a disc sees its cell's
    instance; elsewhere every output is 0."""
    out = {o: _field(_tile(o, rotate=50), backend)[0] for o in ("instance_value", "row")}
    out |= {o: _field(_tile(o, rotate=50), backend)[0] for o in ("column", "angle", "u", "v")}
    _, x, y = _field(_tile("u"), backend)
    row, col = np.floor(y), np.floor(x)
    du, dv = x - (col + 0.5), y - (row + 0.5)
    inside = du * du + dv * dv < 0.29**2
    outside = du * du + dv * dv > 0.31**2
    for name, v in out.items():
        assert (v[outside] == 0).all(), name
    want_value = [_uniform(7, 5, int(r), int(c)) for r, c in zip(row[inside], col[inside])]
    np.testing.assert_array_equal(out["instance_value"][inside], want_value)
    want_angle = [
        (2 * _uniform(7, 2, int(r), int(c)) - 1) * 50 for r, c in zip(row[inside], col[inside])
    ]
    np.testing.assert_allclose(out["angle"][inside], want_angle, rtol=1e-15)
    assert np.abs(out["angle"]).max() <= 50 and np.unique(out["angle"][inside]).size > 4
    np.testing.assert_array_equal(out["row"][inside], row[inside])
    np.testing.assert_array_equal(out["column"][inside], col[inside])
    # u, v: the offset from the centre rotated by -angle (the disc looks the same rotated)
    theta = np.radians(out["angle"][inside])
    want_u = np.cos(theta) * du[inside] + np.sin(theta) * dv[inside]
    want_v = np.cos(theta) * dv[inside] - np.sin(theta) * du[inside]
    np.testing.assert_allclose(out["u"][inside], want_u, atol=1e-6)
    np.testing.assert_allclose(out["v"][inside], want_v, atol=1e-6)


@pytest.mark.parametrize("backend", BACKENDS)
def test_the_largest_motif_wins(backend: str) -> None:
    """A cone wider than its cell: the instance on top is the nearest centre (ties aside)."""
    cone = "Max(0, 1 - Sqrt(X() * X() + Y() * Y()))"
    expr = f'Tile({cone}, 0.5, 0.5, offset=0.5, seed=3, output="{{}}")'
    u, x, y = _field(expr.format("u"), backend, 48, (0.0, 0.0, 2.0, 2.0))
    v = _field(expr.format("v"), backend, 48, (0.0, 0.0, 2.0, 2.0))[0]
    row = _field(expr.format("row"), backend, 48, (0.0, 0.0, 2.0, 2.0))[0]
    # every neighbour centre: (c + 0.5) * 0.5 + r * 0.25, (r + 0.5) * 0.5
    r0 = np.floor(y / 0.5)
    best = np.full(x.shape, np.inf)
    want_u, want_v, want_r = (np.zeros(x.shape) for _ in range(3))
    for dr in (-1, 0, 1):
        r = r0 + dr
        c0 = np.floor((x - r * 0.25) / 0.5)
        for dc in (-1, 0, 1):
            cx, cy = (c0 + dc + 0.5) * 0.5 + r * 0.25, (r + 0.5) * 0.5
            d = np.hypot(x - cx, y - cy)
            closer = d < best - 1e-9
            best = np.where(closer, d, best)
            want_u, want_v = np.where(closer, x - cx, want_u), np.where(closer, y - cy, want_v)
            want_r = np.where(closer, r, want_r)
    np.testing.assert_allclose(u, want_u, atol=1e-6)
    np.testing.assert_allclose(v, want_v, atol=1e-6)
    np.testing.assert_array_equal(row, want_r)


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
@pytest.mark.parametrize("output", ["instance_value", "row", "column", "angle", "u", "v"])
def test_backends_agree(output: str) -> None:
    expr = (
        f"Tile(Fill(Rect(-0.3, -0.2, 0.6, 0.4)) * fBm(octaves=2, to_01=True, seed=1), 0.45, "
        f"0.35, jitter=0.3, rotate=70, scale_min=0.6, scale_max=1.3, probability=0.8, "
        f'offset=0.3, seed=9, output="{output}")'
    )
    a = _field(expr, "numpy", 80)[0]
    b = _field(expr, "numba", 80)[0]
    assert np.array_equal(a, b, equal_nan=True)
    assert np.unique(a).size > 3


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("output", ["instance_value", "row", "column", "angle", "u"])
def test_instances_repeat_with_the_view(backend: str, output: str) -> None:
    expr = (
        "Tile(Fill(Ellipse(0, 0, 0.12, 0.1)), 0.37, 0.29, jitter=0.2, rotate=40, offset=0.45, "
        f'seed=9, output="{output}")'
    )
    program = prepare(f"View(0, 0, 1, 1)\nMaterial(Layer(1).height({expr}))")
    node = program.layers[0].channel("height").args[0]
    x, y = sample_axes(View(0, 0, 2, 2), 96, 96)
    ev = Evaluator(program, x, y, get_backend(backend), periods=(1.0, 1.0))
    v = np.broadcast_to(np.asarray(ev.field(node), np.float64), (96, 96))
    assert np.std(v) > 1e-3
    np.testing.assert_allclose(v[:, 48:], v[:, :48], atol=2e-4)
    np.testing.assert_allclose(v[48:], v[:48], atol=2e-4)
    if output in ("row", "column"):
        assert v.min() >= 0 and v.max() <= 3  # 3 rows / 3 columns per period


# ---------------------------------------------------------------------------- Choose
def test_pick_is_floor_of_index_times_n_clamped() -> None:
    index = np.array([-0.5, 0.0, 0.33, 0.34, 0.66, 0.67, 0.999, 1.0, 7.0, np.nan])
    got = pick(index, [10.0, 20.0, np.full(index.shape, 30.0)])
    want = [10, 10, 10, 20, 20, 30, 30, 30, 30]
    assert got[:-1].tolist() == want and np.isnan(got[-1])


@pytest.mark.parametrize("backend", BACKENDS)
def test_choose_in_a_program(backend: str) -> None:
    expr = "Choose(Hash(X() * 4, Y() * 4, seed=2), X(), 0.5, Y() * 2, -1)"
    got, x, y = _field(expr, backend)
    index = _field("Hash(X() * 4, Y() * 4, seed=2)", backend)[0]
    k = np.clip(np.floor(index * 4), 0, 3)
    want = np.select([k == 0, k == 1, k == 2, k == 3], [x, 0.5, (y * 2), -1.0])
    np.testing.assert_allclose(got, want, atol=1e-6)
    assert {0, 1, 2, 3} <= set(np.unique(k).astype(int).tolist())
    program = prepare(f"Material(Layer(1).height({expr}))")
    assert "Choose(Hash(" in matloom.format(program)
    assert matloom.parse("Material(Layer(1).roughness(Choose(0.6, 0.1, 0.2, 0.3)))")
    (rough,) = (
        matloom.parse("Material(Layer(1).roughness(Choose(0.6, 0.1, 0.2, 0.3)))").layers[0].channels
    )
    from matloom.lang.static import static_number

    assert static_number(rough.args[0]) == 0.2


@pytest.mark.parametrize("backend", BACKENDS)
def test_choose_picks_a_motif_per_instance(backend: str) -> None:
    """The documented composition: the option Tiles share the grid and seed, and the
    instance value of a covering motif picks one per instance."""
    disc, square = "Fill(Ellipse(0, 0, 0.3, 0.3))", "Fill(Rect(-0.25, -0.25, 0.5, 0.5))"
    same = "1, 1, jitter=0.1, seed=4"
    expr = (
        f'Choose(Tile(Max({disc}, {square}), {same}, output="instance_value"), '
        f"Tile({disc}, {same}), Tile({square}, {same}))"
    )
    got, x, y = _field(expr, backend)
    value = _field(f'Tile(Max({disc}, {square}), {same}, output="instance_value")', backend)[0]
    a = _field(f"Tile({disc}, {same})", backend)[0]
    b = _field(f"Tile({square}, {same})", backend)[0]
    np.testing.assert_array_equal(got, np.where(value < 0.5, a, b))
    # whole instances: per cell, the result is entirely one motif
    cells = np.floor(x) + 10 * np.floor(y)
    shown = [
        (
            np.array_equal(got[cells == k], a[cells == k]),
            np.array_equal(got[cells == k], b[cells == k]),
        )
        for k in np.unique(cells)
    ]
    assert all(is_a or is_b for is_a, is_b in shown)
    assert any(is_a and not is_b for is_a, is_b in shown)
    assert any(is_b and not is_a for is_a, is_b in shown)
