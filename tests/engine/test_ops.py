"""The op table (matloom.ops): one entry per registry function, every rule stated, and a
new element-wise function needs nothing but its registry entry and its op entry."""

from __future__ import annotations

import math

import numpy as np
import pytest

import matloom
from matloom.engine import interpret
from matloom.engine.kernels.register_ops import REGISTER_OPS
from matloom.lang.static import static_number
from matloom.ops import NUMPY, OPS, Kind, Op, Ref, Repeats, operator_ops, unbounded
from matloom.vocab import FUNCTIONS
from matloom.vocab.spec import FunctionSpec, ParamSpec, Returns
from matloom.vocab.spec import Kind as ParamKind


def test_every_registry_function_has_an_op() -> None:
    assert set(OPS) == set(FUNCTIONS)


@pytest.mark.parametrize("name", sorted(OPS))
def test_every_op_states_every_rule(name: str) -> None:
    op = OPS[name]
    assert op.name == name
    assert isinstance(op.kind, Kind)
    assert callable(op.numpy) and callable(op.static) and callable(op.bounds)
    assert op.fast is NUMPY or op.fast in REGISTER_OPS
    assert isinstance(op.materialised, bool)
    if isinstance(op.numpy, Ref):
        op.numpy.resolve()  # the implementation exists
    if op.fast is not None:
        assert op.kind is Kind.ELEMENTWISE
        assert REGISTER_OPS[op.fast].symbol is not None  # a lazy-expression op of the machine
        assert (op.block is not None) == (REGISTER_OPS[op.fast].consts > 0)
    returns = FUNCTIONS[name].returns
    assert (op.kind is Kind.GEOMETRY) == (returns is not Returns.FIELD)
    if name in ("Translate", "Scale", "Rotate"):
        assert op.transform is not None
        if isinstance(op.transform.warp, Ref):
            op.transform.warp.resolve()
    assert (op.transform is not None) == (op.period.repeats is Repeats.FRAME)


def test_operators_are_ops() -> None:
    ops = operator_ops()
    assert {k: v.name for k, v in ops.items()} == {
        "+": "Add",
        "-": "Sub",
        "*": "Mul",
        "/": "Div",
        "**": "Pow",
    }


def test_static_rules() -> None:
    parse = matloom.parse

    def value(expr: str) -> float | int | None:
        program = parse(f"Material(Layer(1).roughness({expr}))")
        return static_number(program.layers[0].channels[0].args[0])

    assert value("Log(100, 10) + Sqrt(4) * 2 ** 3 - Min(1, 2)") == 2.0 + 2.0 * 8.0 - 1
    assert value("Floor(2.5) + Ceil(0.5) + Abs(-3)") == 6.0
    assert math.isnan(value("Sqrt(-1)"))  # type: ignore[arg-type]
    assert value("1 / 0") == 0.0
    assert value("fBm(seed=1)") is None


def test_bounds_rules() -> None:
    assert OPS["Add"].bounds((0.0, 1.0), (2.0, 3.0)) == (2.0, 4.0)
    assert OPS["Div"].bounds((1.0, 1.0), (-1.0, 1.0)) is None
    assert OPS["Abs"].bounds((-2.0, 1.0)) == (0.0, 2.0)
    assert OPS["Sqrt"].bounds((-1.0, 1.0)) is None
    assert OPS["Threshold"].bounds((0.0, 1.0), transition_width=0.0) is None


def test_sweep_materialised_from_the_table() -> None:
    assert {n for n, op in OPS.items() if op.materialised} == {"Sin", "Cos", "Log", "Pow"}


# ------------------------------------------------------------------ a new function, end to end
def _atan2_op() -> Op:
    def static(values: list[float], strict: bool) -> float | None:
        return math.atan2(values[0], values[1]) if len(values) == 2 else None

    return Op(
        "Angle",
        Kind.ELEMENTWISE,
        np.arctan2,
        static,
        lambda a, b: (-math.pi, math.pi),
        NUMPY,
    )


@pytest.fixture
def atan2(monkeypatch: pytest.MonkeyPatch) -> None:
    """``Angle(y, x)`` (an atan2 under a name the language does not have) registered with one
    registry entry and one op entry, nothing else."""
    spec = FunctionSpec(
        "Angle",
        "math",
        "angle of (x, y)",
        "Angle(Y(), X())",
        (ParamSpec("y", ParamKind.EXPR, "y"), ParamSpec("x", ParamKind.EXPR, "x")),
    )
    monkeypatch.setitem(FUNCTIONS, "Angle", spec)
    monkeypatch.setitem(OPS, "Angle", _atan2_op())


PROGRAM = """Material(
  Layer(1)
    .height(Angle(Y() - 0.5, X() - 0.5) * fBm(seed=3, to_01=True))
    .roughness(Angle(1, 1) + 0.1)
)"""


@pytest.mark.usefixtures("atan2")
@pytest.mark.parametrize("backend", ["numpy", "numba"])
def test_new_function_evaluates_everywhere(backend: str) -> None:
    if backend not in matloom_backends():
        pytest.skip(f"{backend} not available")
    assert not [d for d in matloom.check(PROGRAM) if d.severity.name == "ERROR"]
    maps = matloom.evaluate(PROGRAM, 64, 64, backend=backend)
    reference = matloom.evaluate(PROGRAM, 64, 64, backend="numpy")
    assert np.isfinite(maps.height).all()
    assert np.array_equal(maps.height, reference.height)
    assert float(maps.roughness[0, 0]) == pytest.approx(math.atan2(1, 1) + 0.1, abs=1e-6)
    (roughness,) = [
        ch.args[0] for ch in matloom.parse(PROGRAM).layers[0].channels if ch.name == "roughness"
    ]
    assert static_number(roughness) == pytest.approx(math.atan2(1, 1) + 0.1)


@pytest.mark.usefixtures("atan2")
def test_new_function_in_culling() -> None:
    from matloom.engine.cull import channel_bounds
    from matloom.engine.lazy import DeferredField, make_lazy

    x = np.linspace(-1, 1, 8)[None, :]
    dense = interpret.Evaluator(matloom.parse(PROGRAM), x, x.T, _numpy_backend())
    expr = matloom.parse("Material(Layer(1).height(Angle(Y(), X())))").layers[0].channels[0]
    angle = dense.field(expr.args[0])
    deferred = DeferredField(lambda m: np.zeros((8, 8)), (8, 8), 0.0, 1.0, True)
    assert channel_bounds(make_lazy("*", angle, deferred), {}) is not None  # a bounded leaf


def matloom_backends() -> list[str]:
    from matloom.engine.backends import available_backends

    return available_backends()


def _numpy_backend() -> object:
    from matloom.engine.backends import get_backend

    return get_backend("numpy")


def test_unbounded_is_none() -> None:
    assert unbounded((0.0, 1.0)) is None
