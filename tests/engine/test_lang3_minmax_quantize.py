"""Language 3: n-ary Min/Max and Quantize. Formulas on both backends, constant folding, bounds
and support rules, canonical text, the cost model and tileable output."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import evaluate, prepare
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import Evaluator
from matloom.engine.maps import View
from matloom.lang.api import check, format, parse
from matloom.lang.cost import expanded_cost
from matloom.lang.static import static_number
from matloom.ops import OPS

BACKENDS = available_backends()
VIEW = (-1.5, -1.25, 1.5, 0.75)
W, H = 40, 28
F = np.float64


def _program(expr: str, view: tuple[float, ...] = VIEW) -> str:
    return f"View{view}\nMaterial(Layer(1).height({expr}))"


def _field(expr: str, backend: str) -> np.ndarray:
    program = prepare(_program(expr))
    x, y = sample_axes(View(*VIEW), W, H)
    ev = Evaluator(program, x, y, get_backend(backend))
    return np.broadcast_to(ev.field(program.layers[0].channels[0].args[0]), (H, W))


def _q(v: np.ndarray, size: float) -> np.ndarray:
    """Cell centres of the coordinates v for cells of ``size`` (float64, back in v's dtype)."""
    return ((np.floor(v.astype(F) / F(size)) + 0.5) * F(size)).astype(v.dtype)


EXACT = {
    "Min(X(), Y(), 0.2)": lambda x, y: np.minimum(np.minimum(x, y), F(0.2)),
    "Max(X(), Y() * 2, -X(), 0.1)": lambda x, y: np.maximum(
        np.maximum(np.maximum(x, y * F(2)), F(-1) * x), F(0.1)
    ),
    "Min(X(), Y())": lambda x, y: np.minimum(x, y),
    "Quantize(X() + Y() * 3, 0.25, 0.5)": lambda x, y: _q(x, 0.25) + _q(y, 0.5) * F(3),
    "Quantize(Translate(X(), 0.1, 0), 0.3, 0.7)": lambda x, y: _q(x, 0.3) - 0.1,
    "Translate(Quantize(Y(), 0.2, 0.2), 0, 0.05)": lambda x, y: _q(y - 0.05, 0.2),
    "Quantize(Min(X(), Y(), 0), 0.125, 0.125)": lambda x, y: np.minimum(
        np.minimum(_q(x, 0.125), _q(y, 0.125)), F(0)
    ),
}


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("expr", sorted(EXACT))
def test_equals_its_formula(expr: str, backend: str) -> None:
    x, y = sample_axes(View(*VIEW), W, H)
    expected = np.broadcast_to(EXACT[expr](x, y), (H, W))
    got = _field(expr, backend)
    assert np.array_equal(got, expected)
    maps = evaluate(_program(expr), W, H, backend=backend)
    assert np.array_equal(maps.height, expected.astype(np.float32))


NOISY = (
    "Quantize(fBm(octaves=4, base_freq=3, seed=4), 0.125, 0.1)",
    "Min(Worley(base_freq=4, seed=2), fBm(base_freq=2, to_01=True, seed=3), 0.6, Y())",
    "Max(Quantize(Worley(base_freq=3, seed=5), 0.2, 0.2), X() * 0.3, Bricks())",
)


@pytest.mark.skipif("numba" not in BACKENDS, reason="numba not installed")
@pytest.mark.parametrize("expr", NOISY)
def test_backends_give_the_same_bits(expr: str) -> None:
    a = evaluate(_program(expr), 33, 17, backend="numpy")
    b = evaluate(_program(expr), 33, 17, backend="numba")
    assert np.array_equal(a.height, b.height)
    assert np.std(a.height) > 0


def test_quantize_is_constant_in_each_cell() -> None:
    v = _field("Quantize(fBm(octaves=3, base_freq=5, seed=1), 0.75, 2)", "numpy")
    x, y = sample_axes(View(*VIEW), W, H)
    cx, cy = np.floor(x[0].astype(F) / 0.75), np.floor(y[:, 0].astype(F) / 2)
    for i in np.unique(cx):
        for k in np.unique(cy):
            assert np.ptp(v[np.ix_(cy == k, cx == i)]) == 0
    assert np.ptp(v) > 0


def test_quantize_of_noise_is_the_noise_at_the_centres() -> None:
    noise = "fBm(octaves=3, base_freq=5, seed=1)"
    got = _field(f"Quantize({noise}, 0.25, 0.5)", "numpy")
    program = prepare(_program(noise))
    x, y = sample_axes(View(*VIEW), W, H)
    ev = Evaluator(program, _q(x, 0.25), _q(y, 0.5), get_backend("numpy"))
    expected = np.broadcast_to(ev.field(program.layers[0].channels[0].args[0]), (H, W))
    assert np.array_equal(got, expected)


# ------------------------------------------------------------------ static, bounds, support
def test_static_folding() -> None:
    program = parse("Define(a, Min(3, 1, 2) + Max(1, 5, 2, 4))\nMaterial(Layer(1).height(a))")
    assert static_number(program.defines[0].expr) == 6
    assert OPS["Min"].static([3, 1, 2], True) == 1
    assert OPS["Max"].static([1.5, -2, 7, 0], True) == 7
    assert OPS["Min"].static([1.0], True) is None
    assert OPS["Quantize"].static([1.0, 1.0, 1.0], True) is None


def test_bounds_rules() -> None:
    assert OPS["Min"].bounds((0.0, 1.0), (-1.0, 0.5), (0.2, 3.0)) == (-1.0, 0.5)
    assert OPS["Max"].bounds((0.0, 1.0), (-1.0, 0.5), (0.2, 3.0)) == (0.2, 3.0)
    assert OPS["Min"].bounds((0.0, 1.0), (2.0, 3.0)) == (0.0, 1.0)  # binary unchanged


def test_support_of_an_nary_min_covers_every_operand() -> None:
    text = (
        "Tile(Max(Fill(Rect(-0.1, -0.1, 0.05, 0.05)), Fill(Rect(0.1, 0.1, 0.05, 0.05)), "
        "Fill(Rect(-0.3, 0.2, 0.05, 0.05))), 1, 1, seed=1)"
    )
    dense = _field(text, "numpy")
    assert dense.max() == 1.0
    program = prepare(_program(text))
    x, y = sample_axes(View(*VIEW), W, H)
    ev = Evaluator(program, x, y, get_backend("numpy"))
    box = ev.motif_support(program.layers[0].channels[0].args[0].arg("expr"))
    assert box is not None and box[0] <= -0.3 and box[3] >= 0.25


# ------------------------------------------------------------------ text, checks and cost
def test_canonical_text() -> None:
    for expr in ("Min(X(), Y())", "Max(X(), 1)", "Min(X(), Y(), 0.5, -X())"):
        text = format(parse(_program(expr)))
        assert f".height({expr})" in text
        assert format(parse(text)) == text
    q = format(parse(_program("Quantize(X(), 0.5, 0.25)")))
    assert ".height(Quantize(X(), 0.5, 0.25))" in q


def test_checks() -> None:
    assert check(_program("Min(X(), Y(), 0.5)")) == []
    bad = check(_program('Min(X(), Y(), "a")'))
    assert bad and "operand 3" in bad[0].message
    assert check(_program("Min(X())"))  # two operands at least
    assert check(_program("Quantize(X(), 0, 1)"))  # width > 0
    assert check(_program("Quantize(X(), fBm(seed=1), 1)"))  # static widths


def test_cost_counts_one_op_per_operand() -> None:
    two = expanded_cost(parse(_program("Min(X(), Y())")))
    four = expanded_cost(parse(_program("Min(X(), Y(), X(), Y())")))
    assert four.nodes == two.nodes + 2 + 2  # two more operands, two more binary Min ops
    base = expanded_cost(parse("Define(d, fBm(seed=1))\nMaterial(Layer(d + Quantize(d, 1, 1)))"))
    assert base.define_evaluations == 2  # the grid's frame and the cells' frame
    same = expanded_cost(
        parse("Define(d, fBm(seed=1))\nMaterial(Layer(Quantize(d, 1, 1) + Quantize(d, 1, 1)))")
    )
    assert same.define_evaluations == 1


# ------------------------------------------------------------------ tileable output
def _doubled(expr: str, backend: str, n: int = 48) -> np.ndarray:
    x1, y1, x2, y2 = (0.25, -0.5, 1.25, 0.5)
    w, h = x2 - x1, y2 - y1
    program = prepare(_program(expr, (x1, y1, x2, y2)))
    x, y = sample_axes(View(x1, y1, x1 + 2 * w, y1 + 2 * h), 2 * n, 2 * n)
    ev = Evaluator(program, x, y, get_backend(backend), periods=(w, h))
    value = ev.field(program.layers[0].channels[0].args[0])
    return np.broadcast_to(np.asarray(value, dtype=F), (2 * n, 2 * n))


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize(
    "expr",
    [
        "Quantize(fBm(octaves=3, base_freq=2.7, seed=3), 0.125, 0.25)",
        "Quantize(Scale(Worley(base_freq=3, seed=5), 0.5, 1), 0.1, 0.2)",
        "Quantize(Fract(X() * 2), 0.25, 0.25)",
    ],
)
def test_quantize_repeats_with_the_view_when_cells_divide_it(expr: str, backend: str) -> None:
    v = _doubled(expr, backend)
    n = v.shape[0] // 2
    assert np.std(v) > 1e-3
    np.testing.assert_allclose(v[:, n:], v[:, :n], atol=2e-4)
    np.testing.assert_allclose(v[n:], v[:n], atol=2e-4)
    assert not [d for d in check(_program(expr, (0, 0, 1, 1)) + "") if d.code.startswith("W")]


def test_quantize_cells_that_do_not_divide_the_view_warn() -> None:
    text = "View(0, 0, 1, 1, tileable=True)\nMaterial(Layer(1).height(Quantize(fBm(seed=3), 0.3, 0.25)))"
    found = [d for d in check(text) if d.code == "W009"]
    assert found and "Quantize cells" in found[0].message
    ok = "View(0, 0, 1, 1, tileable=True)\nMaterial(Layer(1).height(Quantize(fBm(seed=3), 0.2, 0.25)))"
    assert not [d for d in check(ok) if d.code.startswith("W")]
    seam = "View(0, 0, 1, 1, tileable=True)\nMaterial(Layer(1).height(Min(0.5, 1, X())))"
    assert [d for d in check(seam) if d.code == "W010"]
