"""Deferred channel arithmetic: the interpreter over lazy expressions.

:class:`LazyEvaluator` is the :class:`~matloom.engine.interpret.Evaluator` with another kind of
value: an element-wise op whose fast path is an opcode of the register machine (``OPS[name].fast``,
e.g. ``+ - * /``, unary minus, Min/Max, Abs, Threshold) returns a :class:`Lazy` node instead of
a full array when an operand is an array; every other op (noise, patterns, shapes, the ops
computed with numpy) is evaluated exactly like the dense interpreter. The fused numba path
compiles these nodes into a register program that runs per row inside the compositing kernel,
so the full-size float64 temporaries of the arithmetic are never created.

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

from matloom.engine.interpret import Coords, Evaluator, Field
from matloom.engine.kernels.mathops import count_zero
from matloom.engine.kernels.register_ops import REGISTER_OPS
from matloom.lang import ast as A
from matloom.ops import OPS, Op
from matloom.ops.octaves import octave_schedule

#: dtypes the fused kernel can hold exactly in its float64 registers.
FUSABLE_DTYPES = (np.dtype(np.float32), np.dtype(np.float64))
#: The lazy-expression symbol of each op with an opcode (its opcode's symbol: "+", "abs", ...).
SYMBOL_OF: dict[str, str] = {
    op.name: REGISTER_OPS[op.fast].symbol  # type: ignore[misc]
    for op in OPS.values()
    if op.fast is not None
}
#: The op of each lazy-expression symbol.
OP_OF: dict[str, Op] = {symbol: OPS[name] for name, symbol in SYMBOL_OF.items()}


@dataclass(eq=False)
class Lazy:
    """A deferred element-wise operation on arrays, scalars or other :class:`Lazy` nodes."""

    op: str  # the symbol of an op's opcode: '+', '-', '*', '/', 'min', 'abs', 'threshold', ...
    #: operands (arrays, scalars, Lazy nodes)
    args: tuple[Any, ...]
    dtype: np.dtype
    shape: tuple[int, ...]
    #: the op's static parameters ((name, value), ...), e.g. Threshold's
    params: tuple[tuple[str, Any], ...] = ()


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
    #: Its octaves: what culling can save (``cull.resolve`` weighs it against the masks' cost).
    octaves: int = 1

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


def numpy_value(value: Lazy, operands: list[Any]) -> Any:
    """The numpy value of ``value``'s op on (numpy) ``operands``: the op's numpy implementation,
    the very operation the dense evaluator runs (identical rounding and special cases)."""
    with np.errstate(all="ignore"):
        return OP_OF[value.op].numpy(*operands, **dict(value.params))


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
        cache[key] = (value, numpy_value(value, [materialise(a, cache) for a in value.args]))
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
    if isinstance(value, Lazy):
        out = numpy_value(value, [gather(a, rows, cols, shape, cache) for a in value.args])
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


def make_lazy(
    op: str, *args: Any, params: tuple[tuple[str, Any], ...] = (), dtype: str | None = None
) -> Lazy:
    """A :class:`Lazy` with numpy's result dtype (or ``dtype``) and broadcast shape for ``args``."""
    if dtype is None:
        dtypes = {_dtype(a) for a in args}
        f32 = dtypes == {np.dtype(np.float32)}
        result = np.dtype(np.float32) if f32 else np.dtype(np.float64)
    else:
        result = np.dtype(dtype)
    shape = np.broadcast_shapes(*(shape_of(a) for a in args))
    return Lazy(op, args, result, shape, params)


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
    octaves = max(1, int(kw.get("octaves", 1) or 1))
    return DeferredField(compute, shape, low, 1.0, finite, full_share=full_share, octaves=octaves)


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

    def instance_value(self, node: A.Node, frame: Coords) -> Any:
        """:meth:`Evaluator.instance_value`, also dropping the arrays materialised for it."""
        cached = set(self.materialised)
        try:
            return super().instance_value(node, frame)
        finally:
            for key in [k for k in self.materialised if k not in cached]:
                del self.materialised[key]

    def fbm(self, call: A.Call, c: Coords) -> Field:
        masked = self.backend.fbm_masked
        if not (self.defer_noise and masked is not None):
            return super().fbm(call, c)
        kw = self.noise_args(call, c)
        x, y = c
        dense = self.backend.fbm  # no reference to self: the field must not form a cycle

        def compute(mask: np.ndarray | None) -> np.ndarray:
            if mask is None:
                return dense(x, y, **kw)
            return masked(x, y, mask, fill=PLACEHOLDER, **kw)

        return defer_fbm(compute, x, y, kw)

    def operate(self, op: Op, args: list[Field], params: dict[str, Any]) -> Field:
        if op.divisor is not None:  # a divisor is a materialised leaf (its zeros are counted)
            args = list(args)
            b = args[op.divisor] = self.concrete(args[op.divisor])
            row_varying = np.ndim(b) == 2 and np.shape(b)[0] > 1
            if row_varying or self.count_row_invariant_zero_divisions:
                self.stats.zero_divisions += count_zero(b)
        return self.apply(op, args, params)

    def apply(self, op: Op, args: list[Field], params: dict[str, Any]) -> Field:
        """An op with an opcode on fusable values stays a :class:`Lazy` expression; any other
        is computed with numpy on the concrete values."""
        symbol = SYMBOL_OF.get(op.name)
        if symbol is not None and fusable(*args):
            if op.check is not None:  # the numpy kernel's errors, before deferring
                op.check(**params)
            return make_lazy(symbol, *args, params=tuple(params.items()), dtype=op.dtype)
        with np.errstate(all="ignore"):
            return op.numpy(*[self.concrete(a) for a in args], **params)
