"""Field rules of the language-2 functions that are not one element-wise op (see
:mod:`matloom.ops.table_math`).

* **Clamp, Mix, Smoothstep** have three field operands, one more than a register-machine row
  holds. Their rules evaluate the operands and compose the element-wise ops Min, Max, Add,
  Sub, Mul and Div through the interpreter (``ev.apply``), so each schedule treats the parts as
  it treats those ops: numpy arrays in the dense schedule, deferred :class:`~matloom.engine.lazy.Lazy`
  nodes that the fused numba path compiles onto its existing opcodes, seed-batched values in a
  sweep. The array versions in :mod:`matloom.engine.kernels.mathops` (``clamp``, ``mix``,
  ``smoothstep``) do the same operations (constant folding and tests).
* **Hash** is a primitive field: its operands are evaluated (and materialised), then the
  backend's hash kernel (:mod:`matloom.engine.kernels.hashing` for numpy,
  :mod:`matloom.engine.kernels.hash_numba` for numba; the same bits) gives a float32 leaf. In a
  seed batch (:class:`~matloom.engine.schedules.seed_batch.SweepEvaluator`, which has
  ``batch_seeds``) it gets a leading candidate axis, one seed per candidate.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from matloom.lang import ast as A
from matloom.ops import OPS

_CONSTANTS = {v: np.float64(v) for v in (0.0, 1.0, 2.0, 3.0)}


def _operand(ev: Any, call: A.Call, name: str, c: Any, default: float | None = None) -> Any:
    """The value of operand ``name`` (its default, as a float64 scalar, when not written)."""
    node = call.arg(name)
    if node is None:
        if default is None:
            raise ValueError(f"{call.func}: {name} is missing")
        return np.float64(default)
    return ev.eval(node, c)


def _op(ev: Any, name: str, *args: Any) -> Any:
    """Element-wise op ``name`` on ``args`` as this schedule computes it (no zero-division
    count: these divisions are not written in the program)."""
    return ev.apply(OPS[name], list(args), {})


def clamp(ev: Any, call: A.Call, c: Any) -> Any:
    """``Min(Max(x, lo), hi)`` (as ``mathops.clamp``)."""
    x = _operand(ev, call, "x", c)
    lo = _operand(ev, call, "lo", c, 0.0)
    hi = _operand(ev, call, "hi", c, 1.0)
    return _op(ev, "Min", _op(ev, "Max", x, lo), hi)


def mix(ev: Any, call: A.Call, c: Any) -> Any:
    """``a + (b - a) * t`` (as ``mathops.mix``)."""
    a, b, t = (_operand(ev, call, name, c) for name in ("a", "b", "t"))
    return _op(ev, "Add", a, _op(ev, "Mul", _op(ev, "Sub", b, a), t))


def smoothstep(ev: Any, call: A.Call, c: Any) -> Any:
    """GLSL smoothstep with safe division (as ``mathops.smoothstep``)."""
    e0, e1, x = (_operand(ev, call, name, c) for name in ("edge0", "edge1", "x"))
    k = _CONSTANTS
    ratio = _op(ev, "Div", _op(ev, "Sub", x, e0), _op(ev, "Sub", e1, e0))
    t = _op(ev, "Min", _op(ev, "Max", ratio, k[0.0]), k[1.0])
    return _op(ev, "Mul", _op(ev, "Mul", t, t), _op(ev, "Sub", k[3.0], _op(ev, "Mul", k[2.0], t)))


def _concrete(ev: Any, value: Any) -> Any:
    """The numpy value of a field value of any schedule (a Lazy node is materialised)."""
    concrete = getattr(ev, "concrete", None)
    if concrete is not None:
        return concrete(value)
    from matloom.engine.lazy import materialise

    return materialise(value)


def _hash_kernel(backend: Any) -> Any:
    if getattr(backend, "name", None) == "numba":
        from matloom.engine.kernels.hash_numba import cell_hash
    else:
        from matloom.engine.kernels.hashing import cell_hash
    return cell_hash


def hash_cells(ev: Any, call: A.Call, c: Any) -> Any:
    """Hash of the cells (floor(x), floor(y)) for the call's seed (a float32 leaf)."""
    from matloom.engine.kernels.hashing import seed_key

    seed = ev.num(call, "seed")
    if seed is None:
        raise ValueError("Hash has no seed; canonicalise the program first")
    x = _concrete(ev, _operand(ev, call, "x", c))
    y = _concrete(ev, _operand(ev, call, "y", c, 0.0))
    period = ev.periods_of(c, call.func) if getattr(ev, "periods", None) else None
    if period is not None:
        x, y = _wrap_hash(ev, call, period, x, y)
    batch = getattr(ev, "batch_seeds", None)
    seeds = [seed] if batch is None else batch(call)
    out = _hash_kernel(ev.backend)(x, y, [seed_key(s) for s in seeds])
    if batch is not None:
        return out
    shape = np.broadcast_shapes(np.shape(x), np.shape(y))
    return out[0, 0, 0] if shape == () else out.reshape(shape)


def hash_wrap(call: A.Call, defines: Any, period: tuple[float, float]) -> tuple[float, float]:
    """Cells per period (nx, ny) of Hash's operands for tileable output, 0 for an operand that
    does not wrap. An operand ``a X() + b Y()`` plus terms that repeat with the View advances
    ``|a| Px`` cells over a horizontal period and ``|b| Py`` over a vertical one; when those are
    whole numbers its cells are wrapped modulo their greatest common divisor, so it repeats
    along both axes (``Hash(x=Floor(Y() * 8))`` as well as ``Hash(x=X() * 8, y=Y() * 8)``; see
    :mod:`matloom.lang.affine`); operands without coordinates need no wrap."""
    from math import gcd

    from matloom.lang.affine import coord_coeffs
    from matloom.ops.period import whole

    out = []
    for name in ("x", "y"):
        coeffs = coord_coeffs(call.arg(name), defines, period)
        if coeffs is None or coeffs == (0.0, 0.0):
            out.append(0.0)
            continue
        steps = [whole(abs(k * p)) for k, p in zip(coeffs, period, strict=True) if k != 0.0]
        if any(not n for n in steps):
            out.append(0.0)
            continue
        out.append(float(gcd(*(n for n in steps if n))))
    return out[0], out[1]


def _wrap_hash(
    ev: Any, call: A.Call, period: tuple[float, float], x: Any, y: Any
) -> tuple[Any, Any]:
    """Operands whose cells are wrapped modulo their cells per period: (floor(v) mod n) + 0.5
    (exact for integer cells), so both backends hash the same cells."""
    nx, ny = hash_wrap(call, ev.defines, period)
    with np.errstate(invalid="ignore"):
        if nx:
            cx = np.floor(np.asarray(x, dtype=np.float64))
            x = cx - np.floor(cx / nx) * nx + 0.5
        if ny:
            cy = np.floor(np.asarray(y, dtype=np.float64))
            y = cy - np.floor(cy / ny) * ny + 0.5
    return x, y
