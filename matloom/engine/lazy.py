"""Deferred channel arithmetic: an :class:`Evaluator` whose element-wise math stays symbolic.

:class:`LazyEvaluator` evaluates every primitive field (noise, patterns, shapes, Threshold, the
transcendental functions) exactly like :class:`~matloom.engine.evaluate.Evaluator`, but returns
a :class:`Lazy` node instead of a full array for ``+ - * /``, unary minus, ``Min``/``Max`` and
``Abs``/``Floor``/``Ceil``/``Sqrt`` over arrays. The fused numba path compiles these nodes into
a register program that runs per row inside the compositing kernel, so the full-size float64
temporaries of the arithmetic are never created.

A :class:`Lazy` records the numpy result dtype (float32 only when every operand is float32, as
numpy's promotion gives for the evaluator's operands) and the broadcast shape. :func:`materialise`
evaluates it with the very numpy operations the evaluator uses, so both give identical values.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from matloom.engine.evaluate import _UNARY, Coords, Evaluator, Field
from matloom.engine.kernels import mathops, threshold
from matloom.engine.kernels.opensimplex import octave_schedule
from matloom.lang import ast as A

#: dtypes the fused kernel can hold exactly in its float64 registers.
FUSABLE_DTYPES = (np.dtype(np.float32), np.dtype(np.float64))
_LAZY_UNARY = {"Abs": "abs", "Floor": "floor", "Ceil": "ceil", "Sqrt": "sqrt"}


@dataclass(eq=False)
class Lazy:
    """A deferred element-wise operation on arrays, scalars or other :class:`Lazy` nodes."""

    op: str  # '+', '-', '*', '/', 'min', 'max', 'abs', 'floor', 'ceil', 'sqrt', 'threshold'
    #: operands; for 'threshold': (value, ((parameter, value), ...))
    args: tuple[Any, ...]
    dtype: np.dtype
    shape: tuple[int, ...]


#: Value of a deferred fBm field where no layer needs it (inside both fBm ranges, [0, 1] and
#: [-1, 1]; see :mod:`matloom.engine.cull`).
PLACEHOLDER = 0.0


@dataclass(eq=False)
class DeferredField:
    """An fBm field (see :mod:`matloom.engine.cull`) of one band whose evaluation waits for the coverage masks.

    ``compute(mask)`` evaluates it (``mask=None``: everywhere). Once resolved, ``array`` holds
    what the compositing kernel reads; ``np.asarray(field)`` resolves it in full if needed.
    """

    compute: Callable[[np.ndarray | None], np.ndarray]
    shape: tuple[int, ...]
    lo: float
    hi: float
    finite_coords: bool
    dtype: np.dtype = field(default_factory=lambda: np.dtype(np.float64))
    array: np.ndarray | None = None
    #: Needed share above which the field is computed everywhere (None: ``cull.FULL_SHARE``).
    full_share: float | None = None

    def full(self) -> np.ndarray:
        if self.array is None:
            self.array = self.compute(None)
        return self.array

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        array = self.full()
        return array if dtype is None else array.astype(dtype)


def is_scalar(value: Any) -> bool:
    """True for Python/numpy scalars and 0-d arrays (values the evaluator keeps unexpanded)."""
    return not isinstance(value, Lazy | DeferredField) and np.ndim(value) == 0


def _numpy_op(op: str, args: list[Any]) -> Any:
    """The evaluator's numpy operation for ``op`` (identical rounding and special cases)."""
    with np.errstate(all="ignore"):
        if op == "+":
            return args[0] + args[1]
        if op == "-":
            return args[0] - args[1]
        if op == "*":
            return args[0] * args[1]
        if op == "/":
            return mathops.safe_div(args[0], args[1])
        if op == "min":
            return np.minimum(args[0], args[1])
        if op == "max":
            return np.maximum(args[0], args[1])
        if op == "threshold":
            return threshold.threshold(np.asarray(args[0]), **dict(args[1]))
        return {"abs": np.abs, "floor": np.floor, "ceil": np.ceil, "sqrt": np.sqrt}[op](args[0])


def materialise(value: Any, cache: dict[int, tuple[Any, Any]] | None = None) -> Any:
    """Evaluate a :class:`Lazy` tree with numpy (other values are returned unchanged; a
    :class:`~matloom.engine.cull.DeferredField` becomes its array, computed in full if needed)."""
    if isinstance(value, DeferredField):
        return np.asarray(value)
    if not isinstance(value, Lazy):
        return value
    cache = {} if cache is None else cache
    key = id(value)
    if key not in cache:  # the entry keeps ``value`` alive so that its id stays unique
        cache[key] = (value, _numpy_op(value.op, [materialise(a, cache) for a in value.args]))
    return cache[key][1]


def gather(
    value: Any, rows: np.ndarray, cols: np.ndarray, shape: tuple[int, int], cache: dict[int, Any]
) -> Any:
    """Value of a field (Lazy, array or scalar) at texels (rows[k], cols[k]) as shape (1, k).

    Leaves are indexed with broadcasting and the Lazy operations re-run with numpy on the
    gathered values, which yields exactly the full-array values at those texels.
    """
    key = id(value)
    if key in cache:
        return cache[key]
    if isinstance(value, Lazy) and value.op == "threshold":
        out = _numpy_op(value.op, [gather(value.args[0], rows, cols, shape, cache), value.args[1]])
    elif isinstance(value, Lazy):
        out = _numpy_op(value.op, [gather(a, rows, cols, shape, cache) for a in value.args])
    elif is_scalar(value):
        out = value
    else:
        out = np.broadcast_to(value, shape)[rows, cols][None, :]
    cache[key] = out
    return out


def shape_of(value: Any) -> tuple[int, ...]:
    """Shape of a field value (array, scalar, Lazy or deferred) without computing it."""
    return value.shape if isinstance(value, Lazy | DeferredField) else np.shape(value)


def _dtype(value: Any) -> np.dtype:
    return value.dtype if isinstance(value, Lazy | DeferredField) else np.asarray(value).dtype


def fusable(*values: Any) -> bool:
    """True when an operation on ``values`` can be deferred: some operand is an array or Lazy
    and every operand is float32/float64 (so the kernel reproduces numpy's promotion)."""
    if all(is_scalar(v) for v in values):
        return False
    return all(_dtype(v) in FUSABLE_DTYPES for v in values)


def make_lazy(op: str, *args: Any) -> Lazy:
    """A :class:`Lazy` with numpy's result dtype and broadcast shape for ``args``."""
    dtypes = {_dtype(a) for a in args}
    dtype = np.dtype(np.float32) if dtypes == {np.dtype(np.float32)} else np.dtype(np.float64)
    shape = np.broadcast_shapes(*(shape_of(a) for a in args))
    return Lazy(op, args, dtype, shape)


def finite_noise_coords(x: Any, y: Any, kw: dict[str, Any]) -> bool:
    """True when every octave's scaled coordinates are finite, so that the fBm is finite (it
    is clamped to its range) everywhere: the condition for culling it (engine.cull)."""
    sched = octave_schedule(kw["octaves"], kw["lacunarity"], kw["gain"], kw["freq_x"], kw["freq_y"])
    top = max(map(abs, (*sched.freqs_x, *sched.freqs_y, 1.0)))
    extent = max(float(np.max(np.abs(x), initial=0.0)), float(np.max(np.abs(y), initial=0.0)))
    return math.isfinite(extent) and extent * top < 1e300


def defer_fbm(
    compute: Callable[[np.ndarray | None], np.ndarray],
    x: Any,
    y: Any,
    kw: dict[str, Any],
    seeds: int | None = None,
    full_share: float | None = None,
) -> DeferredField:
    """A :class:`DeferredField` for the fBm with kernel keywords ``kw`` on coordinates x, y
    (``seeds``: the leading seed axis of a seed batch): its shape, clamped range and whether
    its coordinates allow culling."""
    shape = np.broadcast_shapes(np.shape(x), np.shape(y))
    if seeds is not None:
        shape = (seeds, *shape)
    low = 0.0 if kw["to_01"] else -1.0
    finite = finite_noise_coords(x, y, kw)
    return DeferredField(compute, shape, low, 1.0, finite, full_share=full_share)


class LazyEvaluator(Evaluator):
    """An :class:`Evaluator` that defers element-wise arithmetic (see the module docstring)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.materialised: dict[int, tuple[Any, Any]] = {}
        #: Count zero divisors only when they vary per row (set by band-wise callers).
        self.count_row_invariant_zero_divisions = True
        #: Return fBm fields as :class:`DeferredField` (coverage culling, engine.cull); the
        #: caller must then :func:`~matloom.engine.cull.resolve` the layers.
        self.defer_noise = False

    def concrete(self, value: Any) -> Any:
        """The numpy value of ``value`` (materialises a Lazy once)."""
        return materialise(value, self.materialised)

    def noise(self, call: A.Call, c: Coords) -> Field:
        masked = self.backend.fbm_masked
        if not (self.defer_noise and call.func == "fBm" and masked is not None):
            return super().noise(call, c)
        kw = self.noise_args(call)
        x, y = c
        dense = self.backend.fbm  # no reference to self: the field must not form a cycle

        def compute(mask: np.ndarray | None) -> np.ndarray:
            if mask is None:
                return dense(x, y, **kw)
            return masked(x, y, mask, fill=PLACEHOLDER, **kw)

        return defer_fbm(compute, x, y, kw)

    def eval(self, node: A.Node, c: Coords) -> Field:
        if isinstance(node, A.Neg):
            return self.lazy_binop("*", np.float64(-1.0), self.eval(node.operand, c))
        if isinstance(node, A.BinOp):
            return self.lazy_binop(node.op, self.eval(node.left, c), self.eval(node.right, c))
        return super().eval(node, c)

    def lazy_binop(self, op: str, a: Any, b: Any) -> Any:
        if op == "**":
            with np.errstate(all="ignore"):
                return mathops.pow_(self.concrete(a), self.concrete(b))
        if op == "/":
            b = self.concrete(b)
            row_varying = np.ndim(b) == 2 and np.shape(b)[0] > 1
            if row_varying or self.count_row_invariant_zero_divisions:
                self.stats.zero_divisions += int(np.count_nonzero(np.asarray(b) == 0))
        if fusable(a, b):
            return make_lazy(op, a, b)
        return _numpy_op(op, [self.concrete(a), self.concrete(b)])

    def call(self, call: A.Call, c: Coords) -> Field:
        f = call.func
        if f in _LAZY_UNARY:
            value = self.eval(call.arg("expr"), c)  # type: ignore[arg-type]
            if fusable(value):
                return make_lazy(_LAZY_UNARY[f], value)
            return _numpy_op(_LAZY_UNARY[f], [value])
        if f in ("Min", "Max"):
            a = self.eval(call.arg("expr1"), c)  # type: ignore[arg-type]
            b = self.eval(call.arg("expr2"), c)  # type: ignore[arg-type]
            op = f.lower()
            return (
                make_lazy(op, a, b)
                if fusable(a, b)
                else _numpy_op(op, [self.concrete(a), self.concrete(b)])
            )
        if f in _UNARY:  # Sin, Cos: numpy's own SIMD results are the reference
            with np.errstate(all="ignore"):
                return _UNARY[f](self.concrete(self.eval(call.arg("expr"), c)))  # type: ignore[arg-type]
        if f == "Log":
            value = self.concrete(self.eval(call.arg("expr"), c))  # type: ignore[arg-type]
            return mathops.log(value, self.num(call, "base"))
        if f == "Threshold":
            value = self.eval(call.arg("expr"), c)  # type: ignore[arg-type]
            kw = {
                p: self.num(call, p)
                for p in ("below_at", "below_to", "above_at", "above_to", "transition_width")
            }
            if fusable(value) and self.backend.threshold is threshold.threshold:
                if float(kw["transition_width"]) < 0:  # the numpy kernel raises the error
                    threshold.threshold(np.zeros(1), **kw)
                lazy = make_lazy("threshold", value)
                return Lazy(
                    "threshold", (value, tuple(kw.items())), np.dtype(np.float64), lazy.shape
                )
            return self.backend.threshold(np.asarray(self.concrete(value)), **kw)
        return super().call(call, c)
