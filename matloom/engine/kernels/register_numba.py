"""numba register machine for the deferred channel arithmetic of the fused evaluation path.

A compiled program (see :func:`matloom.engine.schedules.banded.compile_layers`) is a table of rows
(op, dst, a, b, round_to_f32, const_mask) over a register file of float64 rows, one row per
register, evaluated one image row at a time. Leaves (primitive fields) are loaded with
broadcasting from (S|1, H|1, W|1) arrays; constants are read directly by the operations.

Every operation is an IEEE operation with numpy's semantics (safe division gives 0 where the
divisor is 0; min/max propagate NaN like ``np.minimum``/``np.maximum``); a float32 result is the
float64 result rounded once to float32, which equals the float32 operation for + - * / and
sqrt. The language-2 opcodes (atan2, fract, mod, exp; :func:`_language2`) always give float64
and run the scalar functions of :mod:`matloom.engine.kernels.mathops_numba`, which repeat the
float64 operations of their numpy versions. So the register values equal the numpy evaluator's
values bit for bit.

The opcodes and the meaning of their operands come from the table of
:mod:`matloom.engine.kernels.register_ops` (``REGISTER_OPS``): :func:`run_code` decodes a row
by the opcode's arity and parameter block, never by the opcode's number.

numba's on-disk cache of a kernel is keyed on the file that defines it, not on the files of the
functions it calls; :mod:`matloom.engine.kernels.jit` adds a hash of the kernel's import closure
(:mod:`matloom.engine.kernels.abi`) to that key, so the compositing kernels that call this
module are recompiled after it is edited.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from matloom.engine.kernels import mathops_numba as M
from matloom.engine.kernels.jit import jit
from matloom.engine.kernels.register_ops import ARITY, REGISTER_OPS

#: Register-program opcodes (rows of ``code``: op, dst, a, b, round_to_f32, const_mask), from
#: the table (numba freezes these module constants into the kernels).
OP_LOAD64 = REGISTER_OPS["load64"].code
OP_LOAD32 = REGISTER_OPS["load32"].code
OP_ADD = REGISTER_OPS["add"].code
OP_SUB = REGISTER_OPS["sub"].code
OP_MUL = REGISTER_OPS["mul"].code
OP_DIV = REGISTER_OPS["div"].code
OP_MIN = REGISTER_OPS["min"].code
OP_MAX = REGISTER_OPS["max"].code
OP_ABS = REGISTER_OPS["abs"].code
OP_FLOOR = REGISTER_OPS["floor"].code
OP_CEIL = REGISTER_OPS["ceil"].code
OP_SQRT = REGISTER_OPS["sqrt"].code
#: Threshold (grid-path rules of ``kernels.threshold``); ``b`` = first of its 6 constants
#: (below_at, below_to, above_at, above_to, transition_width, 1 * has_above + 2 * has_below).
OP_THRESHOLD = REGISTER_OPS["threshold"].code
#: ``r[a] * c1 + c2`` (two roundings, as the separate * and + give); ``b`` = index of c1, c2.
OP_AXPB = REGISTER_OPS["axpb"].code
#: Language 2 (float64; the scalar functions of ``kernels.mathops_numba``).
OP_ATAN2 = REGISTER_OPS["atan2"].code
OP_FRACT = REGISTER_OPS["fract"].code
OP_MOD = REGISTER_OPS["mod"].code
OP_EXP = REGISTER_OPS["exp"].code

_OPTIONS: dict[str, Any] = {"nogil": True, "error_model": "numpy", "fastmath": False}


def _jit(parallel: bool = False, inline: bool = False) -> Any:
    """:func:`matloom.engine.kernels.jit.jit` with the register machine's options."""
    return jit(parallel=parallel, inline=inline, **_OPTIONS)


@_jit(inline=True)
def _load(dst: int, leaf: np.ndarray, cand: int, i: int, regs: np.ndarray) -> None:
    """regs[dst] = row i of a (S|1, H|1, W|1) leaf for candidate ``cand``, broadcast."""
    s = cand if leaf.shape[0] > 1 else 0
    ii = i if leaf.shape[1] > 1 else 0
    width = regs.shape[1]
    if leaf.shape[2] > 1:
        for j in range(width):
            regs[dst, j] = leaf[s, ii, j]
    else:
        value = np.float64(leaf[s, ii, 0])
        for j in range(width):
            regs[dst, j] = value


# The element loops index the 2-D register file directly (no per-op array views: creating
# views costs more than the arithmetic on short rows).


@_jit(inline=True)
def _binary(op: int, r: np.ndarray, d: int, a: int, b: int) -> None:
    """r[d] = r[a] (op) r[b]; safe division gives 0 where the divisor is 0; min/max keep NaN."""
    n = r.shape[1]
    if op == OP_ADD:
        for j in range(n):
            r[d, j] = r[a, j] + r[b, j]
    elif op == OP_SUB:
        for j in range(n):
            r[d, j] = r[a, j] - r[b, j]
    elif op == OP_MUL:
        for j in range(n):
            r[d, j] = r[a, j] * r[b, j]
    elif op == OP_DIV:
        for j in range(n):
            r[d, j] = 0.0 if r[b, j] == 0.0 else r[a, j] / r[b, j]
    elif op == OP_MIN:
        for j in range(n):
            x, y = r[a, j], r[b, j]
            r[d, j] = x if (x < y or x != x) else y
    else:
        for j in range(n):
            x, y = r[a, j], r[b, j]
            r[d, j] = x if (x > y or x != x) else y


@_jit(inline=True)
def _binary_right_const(op: int, r: np.ndarray, d: int, a: int, y: float) -> None:
    """r[d] = r[a] (op) y for a constant right operand (same semantics as :func:`_binary`)."""
    n = r.shape[1]
    if op == OP_ADD:
        for j in range(n):
            r[d, j] = r[a, j] + y
    elif op == OP_SUB:
        for j in range(n):
            r[d, j] = r[a, j] - y
    elif op == OP_MUL:
        for j in range(n):
            r[d, j] = r[a, j] * y
    elif op == OP_DIV:
        for j in range(n):
            r[d, j] = 0.0 if y == 0.0 else r[a, j] / y
    elif op == OP_MIN:
        for j in range(n):
            x = r[a, j]
            r[d, j] = x if (x < y or x != x) else y
    else:
        for j in range(n):
            x = r[a, j]
            r[d, j] = x if (x > y or x != x) else y


@_jit(inline=True)
def _binary_left_const(op: int, r: np.ndarray, d: int, x: float, b: int) -> None:
    """r[d] = x (op) r[b] for a constant left operand (same semantics as :func:`_binary`)."""
    n = r.shape[1]
    if op == OP_ADD:
        for j in range(n):
            r[d, j] = x + r[b, j]
    elif op == OP_SUB:
        for j in range(n):
            r[d, j] = x - r[b, j]
    elif op == OP_MUL:
        for j in range(n):
            r[d, j] = x * r[b, j]
    elif op == OP_DIV:
        for j in range(n):
            r[d, j] = 0.0 if r[b, j] == 0.0 else x / r[b, j]
    elif op == OP_MIN:
        for j in range(n):
            y = r[b, j]
            r[d, j] = x if (x < y or x != x) else y
    else:
        for j in range(n):
            y = r[b, j]
            r[d, j] = x if (x > y or x != x) else y


@_jit(inline=True)
def _axpb(r: np.ndarray, d: int, a: int, c1: float, c2: float) -> None:
    """r[d] = r[a] * c1 + c2, rounded after the product and after the sum (no FMA: fastmath is
    off), so it equals the ``*`` then ``+`` rows it replaces bit for bit."""
    for j in range(r.shape[1]):
        r[d, j] = r[a, j] * c1 + c2


@_jit(inline=True)
def _unary(op: int, r: np.ndarray, d: int, a: int) -> None:
    """r[d] = abs/floor/ceil/sqrt(r[a]) (sqrt of a negative number is NaN)."""
    n = r.shape[1]
    if op == OP_ABS:
        for j in range(n):
            r[d, j] = abs(r[a, j])
    elif op == OP_FLOOR:
        for j in range(n):
            r[d, j] = np.floor(r[a, j])
    elif op == OP_CEIL:
        for j in range(n):
            r[d, j] = np.ceil(r[a, j])
    else:
        for j in range(n):
            r[d, j] = np.sqrt(r[a, j])


@_jit()
def _language2(op, r, d, a, b, mask, consts):  # type: ignore[no-untyped-def]
    """r[d] = fract/exp(r[a]) or atan2/mod(a, b), an operand being ``consts[a]`` / ``consts[b]``
    where bit 0 / bit 1 of ``mask`` is set. Not inlined: the functions are compiled once, not
    into each operand variant of :func:`run_code` (cold-start compile time)."""
    n = r.shape[1]
    if op == OP_FRACT:
        for j in range(n):
            r[d, j] = M.fract(r[a, j])
    elif op == OP_EXP:
        for j in range(n):
            r[d, j] = M.exp(r[a, j])
    elif op == OP_ATAN2:
        for j in range(n):
            x = consts[a] if mask & 1 else r[a, j]
            y = consts[b] if mask & 2 else r[b, j]
            r[d, j] = M.atan2(x, y)
    else:
        for j in range(n):
            x = consts[a] if mask & 1 else r[a, j]
            y = consts[b] if mask & 2 else r[b, j]
            r[d, j] = M.mod(x, y)


@_jit()
def load_leaves(loads, regs, leaves64, leaves32, cand, i):  # type: ignore[no-untyped-def]
    """Copy row ``i`` of every leaf into its register (``loads`` rows: op, dst, slot).

    Kept apart from :func:`run_code`: a loop that touches the leaf tuples pays a large fixed
    cost per iteration, which would otherwise be paid by every arithmetic op.
    """
    for k in range(loads.shape[0]):
        if loads[k, 0] == OP_LOAD64:
            _load(loads[k, 1], leaves64[loads[k, 2]], cand, i, regs)
        else:
            _load(loads[k, 1], leaves32[loads[k, 2]], cand, i, regs)


@_jit(inline=True)
def _smooth(t: float) -> float:
    return t * t * (3.0 - 2.0 * t)


@_jit(inline=True)
def _threshold(r: np.ndarray, d: int, a: int, p: np.ndarray, base: int) -> None:
    """r[d] = Threshold(r[a]) with the float64 operations of ``kernels.threshold.threshold``
    in the same order (NaN passes: every comparison with it is false)."""
    below_at, below_to, above_at, above_to = p[base], p[base + 1], p[base + 2], p[base + 3]
    width, flags = p[base + 4], int(p[base + 5])
    has_above, has_below = (flags & 1) != 0, (flags & 2) != 0
    start = above_at - width
    for j in range(r.shape[1]):
        v = r[a, j]
        res = v
        if has_above:
            if width == 0.0:
                res = above_to if v >= above_at else res
            else:
                t = (v - start) / width
                s = _smooth(t)
                res = (1.0 - s) * v + s * above_to if (t > 0.0 and t < 1.0) else res
                res = above_to if t >= 1.0 else res
        if has_below:
            if width == 0.0:
                res = below_to if v <= below_at else res
            else:
                t = (v - below_at) / width
                s = _smooth(t)
                res = (1.0 - s) * below_to + s * v if (t > 0.0 and t < 1.0) else res
                res = below_to if t <= 0.0 else res
        r[d, j] = res


@_jit()
def run_code(code, consts, regs):  # type: ignore[no-untyped-def]
    """Execute the arithmetic register program on the current row.

    ``code`` rows are (op, dst, a, b, round_to_f32, const_mask); operands are registers, or
    ``consts`` indices where bit 0 (a) / bit 1 (b) of the mask is set.
    """
    for k in range(code.shape[0]):
        op, dst, a, b = code[k, 0], code[k, 1], code[k, 2], code[k, 3]
        mask = code[k, 5]
        if op == OP_THRESHOLD:
            _threshold(regs, dst, a, consts, b)
        elif op == OP_AXPB:
            _axpb(regs, dst, a, consts[b], consts[b + 1])
        elif op == OP_ATAN2 or op == OP_FRACT or op == OP_MOD or op == OP_EXP:
            _language2(op, regs, dst, a, b, mask, consts)
        elif ARITY[op] == 1:
            _unary(op, regs, dst, a)
        elif mask == 2:
            _binary_right_const(op, regs, dst, a, consts[b])
        elif mask == 1:
            _binary_left_const(op, regs, dst, consts[a], b)
        else:
            _binary(op, regs, dst, a, b)
        if code[k, 4]:
            for j in range(regs.shape[1]):
                regs[dst, j] = np.float64(np.float32(regs[dst, j]))
