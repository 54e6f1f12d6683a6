"""What one function of the language means to the engine: the :class:`Op` record.

An op states every rule once (see :mod:`matloom.ops.table` for the entries):

* ``numpy``: how it is computed. For an element-wise op, the array function
  ``numpy(*operands, **params)`` (operands: the function's expression parameters in registry
  order; params: its static parameters). For a field primitive (noise, patterns, shapes,
  transforms, coordinates) the field rule ``numpy(interpreter, call, coords)``; for a geometry
  node (Rect, Path, LineTo, ...) the builder ``numpy(interpreter, call)``.
* ``static``: the constant-folding rule ``static(values, strict)`` over Python numbers (values of
  the call's arguments as written); None when the call is not a constant.
* ``bounds``: the interval rule ``bounds(*operand_intervals, **params)`` used by coverage culling
  (:mod:`matloom.engine.cull`); None where NaN/inf or an unbounded value can arise.
* ``fast``: the fast path: the name of the register-machine opcode that computes it
  (:mod:`matloom.engine.kernels.register_ops`), or :data:`NUMPY` (computed with numpy; the result
  is a leaf of the compiled program).
* ``period``: how it keeps, wraps, scales or breaks the View's periods of a tileable output
  (:mod:`matloom.ops.period`), read by the checker's tileable analysis and the interpreter.

Importing this module (and the table) imports neither numpy nor any kernel: implementations are
:class:`Ref` s resolved on first use (the engine's rules in :mod:`matloom.engine.rules` and
kernels), so :mod:`matloom.lang` can read the static, work and period rules.
"""

from __future__ import annotations

import enum
import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from matloom.ops.period import KEEP, Period
from matloom.ops.transform import Transform

Interval = tuple[float, float]
Bounds = Interval | None
StaticRule = Callable[[list[Any], bool], Any]
BoundsRule = Callable[..., Bounds]

#: ``fast`` of an op computed with numpy (its result is a leaf of the register program).
NUMPY = None


class Kind(enum.Enum):
    """How the interpreter evaluates a call of the op."""

    ELEMENTWISE = "elementwise"  # operands evaluated, then ``numpy``/the fast path
    FIELD = "field"  # ``numpy(interpreter, call, coords)`` gives the field
    GEOMETRY = "geometry"  # ``numpy(interpreter, call)`` gives a shape or path segment


class Ref:
    """A function named ``"module:attribute"``, imported on first call."""

    __slots__ = ("path", "_fn")

    def __init__(self, path: str) -> None:
        self.path = path
        self._fn: Callable[..., Any] | None = None

    def resolve(self) -> Callable[..., Any]:
        if self._fn is None:
            module, _, name = self.path.partition(":")
            self._fn = getattr(importlib.import_module(module), name)
        return self._fn

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        fn = self._fn if self._fn is not None else self.resolve()
        return fn(*args, **kwargs)

    def __repr__(self) -> str:
        return f"Ref({self.path!r})"


@dataclass(frozen=True)
class Op:
    """The engine's rules for one registry function (see the module docstring)."""

    name: str
    kind: Kind
    numpy: Callable[..., Any]
    static: StaticRule
    bounds: BoundsRule
    fast: str | None
    #: Zeros of this operand are counted as divisions by zero (EvalStats.zero_divisions).
    divisor: int | None = None
    #: Result dtype: None for numpy's promotion of the operands, else this dtype name.
    dtype: str | None = None
    #: For an opcode with a parameter block: the block's constants from the static params.
    block: Callable[..., list[float]] | None = None
    #: Raise on invalid static params before the op is deferred to the fast path.
    check: Callable[..., None] | None = None
    #: For a coordinate transform: its coordinates, values, frame matrix (:mod:`.transform`).
    transform: Transform | None = None
    #: Field-sized arrays one evaluation of the op allocates, its intermediates included (the
    #: memory estimate of ``matloom.engine.limits`` counts this many per evaluation).
    arrays: int = 1
    #: Where the field can be non-zero: ``support(context, node, operands)`` -> a box or None
    #: (see :mod:`matloom.engine.rules.support`); None: anywhere (no rule).
    support: Callable[..., Any] | None = None
    #: Work of one evaluation in node evaluations (the cost model's unit, see
    #: :mod:`matloom.ops.work`): a number, or a rule ``work(param)`` over the call's
    #: static parameters that bounds every loop the op's kernels run.
    work: float | Callable[[Callable[[str], Any]], float] = 1
    #: How the op keeps, wraps, scales or breaks the View's periods (tileable output).
    period: Period = KEEP

    @property
    def materialised(self) -> bool:
        """What the sweep's memory budget needs: an element-wise op without an opcode makes a
        full float64 array per seed-batched candidate (not fused)."""
        return self.kind is Kind.ELEMENTWISE and self.fast is NUMPY


# ------------------------------------------------------------------ shared rules
def not_constant(values: list[Any], strict: bool) -> None:
    """Static rule of a field or geometry: never a constant."""
    del values, strict


def unbounded(*intervals: Interval, **params: Any) -> Bounds:
    """Bounds rule of an op that culling does not analyse (treated as unbounded)."""
    del intervals, params
