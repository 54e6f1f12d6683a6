"""The opcode table of the register machine (:mod:`register_numba`), as plain data.

A register program is a table of rows ``(op, dst, a, b, round_to_f32, const_mask)``. What an
opcode's operands mean is read from its :class:`RegisterOp` entry, never from its number:

* ``arity`` register operands: 0 (a leaf load: ``a`` is the leaf slot), 1 (``a``) or 2 (``a``,
  ``b``). Bit 0 / bit 1 of ``const_mask`` make ``a`` / ``b`` an index into the constants.
* ``consts`` > 0: the op reads that many consecutive constants starting at index ``b`` (its
  parameter block), so ``b`` is not an operand.

Opcode numbers are the positions in :data:`_TABLE`: add a new opcode at the end (the numbers of
the others never change; tests/engine/test_register_ops.py pins them) and give it a body in
``register_numba`` (its loop in ``_unary``/``_binary*``, or its own branch for a parameter block).
The compiler (:mod:`matloom.engine.schedules.banded`) and the op table name opcodes through
:data:`REGISTER_OPS` or :data:`OP_BY_SYMBOL`. Importing this module imports neither numba nor
the kernels.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class RegisterOp:
    """One opcode: ``name``, its number ``code``, ``arity`` register operands, ``consts``
    constants read from the block at ``b``, and the ``symbol`` of the lazy-expression op it
    computes (None for loads and fused forms)."""

    name: str
    code: int
    arity: int
    consts: int = 0
    symbol: str | None = None
    #: What it computes, for readers and generated docs.
    doc: str = ""


#: (name, arity, consts, symbol, doc) in opcode order: append only.
_TABLE: tuple[tuple[str, int, int, str | None, str], ...] = (
    ("load64", 0, 0, None, "regs[dst] = row i of float64 leaf a (broadcast)"),
    ("load32", 0, 0, None, "regs[dst] = row i of float32 leaf a, widened (broadcast)"),
    ("add", 2, 0, "+", "a + b"),
    ("sub", 2, 0, "-", "a - b"),
    ("mul", 2, 0, "*", "a * b"),
    ("div", 2, 0, "/", "a / b, 0 where b == 0 (safe division)"),
    ("min", 2, 0, "min", "np.minimum(a, b) (NaN propagates)"),
    ("max", 2, 0, "max", "np.maximum(a, b) (NaN propagates)"),
    ("abs", 1, 0, "abs", "|a|"),
    ("floor", 1, 0, "floor", "floor(a)"),
    ("ceil", 1, 0, "ceil", "ceil(a)"),
    ("sqrt", 1, 0, "sqrt", "sqrt(a) (NaN below 0)"),
    (
        "threshold",
        1,
        6,
        "threshold",
        "Threshold(a); block: below_at, below_to, above_at, above_to, width, flags",
    ),
    ("axpb", 1, 2, None, "a * c1 + c2 with two roundings (block: c1, c2)"),
    # language 2 (float64 results, the operations of kernels.mathops; see kernels.mathops_numba)
    ("atan2", 2, 0, "atan2", "Atan2(a, b): angle of (b, a) in (-pi, pi]"),
    ("fract", 1, 0, "fract", "a - floor(a), at most 1 - 2**-53"),
    ("mod", 2, 0, "mod", "a - b * floor(a / b), 0 where b == 0"),
    ("exp", 1, 0, "exp", "e ** a"),
)

#: Every opcode by name.
REGISTER_OPS: dict[str, RegisterOp] = {
    name: RegisterOp(name, code, arity, consts, symbol, doc)
    for code, (name, arity, consts, symbol, doc) in enumerate(_TABLE)
}
#: The opcode computing each lazy-expression op (``"+"``, ``"abs"``, ...).
OP_BY_SYMBOL: dict[str, int] = {
    op.symbol: op.code for op in REGISTER_OPS.values() if op.symbol is not None
}
#: Register operands of each opcode, indexed by opcode (the kernels' decoding reads this).
ARITY: np.ndarray = np.array([op.arity for op in REGISTER_OPS.values()], dtype=np.int64)
#: Constants in each opcode's parameter block at ``b`` (0: ``b`` is an operand or unused).
CONSTS: np.ndarray = np.array([op.consts for op in REGISTER_OPS.values()], dtype=np.int64)
ARITY.setflags(write=False)
CONSTS.setflags(write=False)


def operands(op: int, a: int, b: int) -> tuple[int, ...]:
    """The register operands ``(a,)``, ``(a, b)`` or ``()`` of a row with opcode ``op``."""
    return (a, b)[: ARITY[op]]


def is_load(op: int) -> bool:
    """True for the leaf loads (arity 0)."""
    return bool(ARITY[op] == 0)
