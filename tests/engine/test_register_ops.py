"""The register machine's opcode table (matloom.engine.kernels.register_ops) and its decoding in
the numba kernel (register_numba.run_code), op by op against numpy's semantics."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from matloom.engine.kernels import mathops
from matloom.engine.kernels.register_ops import (
    ARITY,
    CONSTS,
    OP_BY_SYMBOL,
    REGISTER_OPS,
    is_load,
    operands,
)

#: The numbers compiled programs and cached kernels hold: new opcodes are appended, these stay.
PINNED = {
    "load64": 0,
    "load32": 1,
    "add": 2,
    "sub": 3,
    "mul": 4,
    "div": 5,
    "min": 6,
    "max": 7,
    "abs": 8,
    "floor": 9,
    "ceil": 10,
    "sqrt": 11,
    "threshold": 12,
    "axpb": 13,
    "atan2": 14,
    "fract": 15,
    "mod": 16,
    "exp": 17,
}


def test_opcode_numbers_never_change() -> None:
    assert {name: REGISTER_OPS[name].code for name in PINNED} == PINNED
    codes = [op.code for op in REGISTER_OPS.values()]
    assert codes == list(range(len(codes)))  # dense: the kernels index ARITY by opcode


def test_operand_decoding_comes_from_the_table() -> None:
    assert ARITY.shape == CONSTS.shape == (len(REGISTER_OPS),)
    for op in REGISTER_OPS.values():
        assert ARITY[op.code] == op.arity and CONSTS[op.code] == op.consts
        assert operands(op.code, 7, 9) == (7, 9)[: op.arity]
        assert is_load(op.code) == (op.arity == 0)
    assert REGISTER_OPS["threshold"].consts == 6 and REGISTER_OPS["axpb"].consts == 2
    emitted = {"+", "-", "*", "/", "min", "max", "abs", "floor", "ceil", "sqrt", "threshold"}
    emitted |= {"atan2", "fract", "mod", "exp"}  # language 2
    assert set(OP_BY_SYMBOL) == emitted
    assert all(REGISTER_OPS[name].code == code for name, code in _numba_constants().items())


def _numba_constants() -> dict[str, int]:
    """The module constants of register_numba (what the kernels freeze), by opcode name."""
    pytest.importorskip("numba")
    from matloom.engine.kernels import register_numba as R

    return {name: getattr(R, f"OP_{name.upper()}") for name in PINNED}


X = np.array([1.5, -2.25, 0.0, 3.0, np.nan, -7.5, 1e300, 0.1])
Y = np.array([0.5, 4.0, 2.0, 0.0, 1.0, -0.5, 1e-300, np.nan])
C = 2.75


def _div(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    with np.errstate(all="ignore"):
        return np.where(y == 0.0, 0.0, x / np.where(y == 0.0, 1.0, y))


NUMPY: dict[str, Callable[..., np.ndarray]] = {
    "add": np.add,
    "sub": np.subtract,
    "mul": np.multiply,
    "div": _div,
    "min": np.minimum,
    "max": np.maximum,
    "abs": np.abs,
    "floor": np.floor,
    "ceil": np.ceil,
    "sqrt": np.sqrt,
    # language 2: their numpy versions (float64, bit-identical on every CPU)
    "atan2": mathops.atan2,
    "fract": mathops.fract,
    "mod": mathops.mod,
    "exp": mathops.exp_,
}


def _bits(a: np.ndarray) -> np.ndarray:
    return np.where(np.isnan(a), np.nan, a).view(np.uint64)


def _run(row: tuple[int, ...]) -> np.ndarray:
    from matloom.engine.kernels.register_numba import run_code

    regs = np.zeros((5, X.size))
    regs[2], regs[3] = X, Y
    consts = np.array([C, -1.25, 0.5])
    run_code(np.array([row], dtype=np.int64), consts, regs)
    return regs[4]


@pytest.mark.numba
@pytest.mark.parametrize("name", sorted(NUMPY))
def test_each_opcode_runs_with_numpy_semantics(name: str) -> None:
    pytest.importorskip("numba")
    op, ref = REGISTER_OPS[name], NUMPY[name]
    with np.errstate(all="ignore"):
        if op.arity == 1:
            cases = [((op.code, 4, 2, 0, 0, 0), ref(X))]
        else:
            cases = [
                ((op.code, 4, 2, 3, 0, 0), ref(X, Y)),
                ((op.code, 4, 2, 0, 0, 2), ref(X, np.full_like(X, C))),  # constant right
                ((op.code, 4, 0, 3, 0, 1), ref(np.full_like(Y, C), Y)),  # constant left
            ]
        for row, expected in cases:
            assert np.array_equal(_bits(_run(row)), _bits(expected)), (name, row)
            rounded = _run((*row[:4], 1, row[5]))  # round_to_f32
            assert np.array_equal(_bits(rounded), _bits(expected.astype(np.float32).astype(float)))


@pytest.mark.numba
def test_axpb_reads_its_constant_block() -> None:
    pytest.importorskip("numba")
    got = _run((REGISTER_OPS["axpb"].code, 4, 2, 1, 0, 0))  # c1, c2 = consts[1], consts[2]
    with np.errstate(all="ignore"):
        assert np.array_equal(_bits(got), _bits(X * -1.25 + 0.5))
