"""The op table: what every function of the language means, stated once (level 1).

``OPS[name]`` is the :class:`Op` of registry function ``name`` (numpy implementation, static
rule, bounds rule, fast-path opcode or NUMPY, work and period rules; see :mod:`matloom.ops.op`).
The package imports only :mod:`matloom.vocab` (and the standard library; numpy on first use of a
static rule): the engine's implementations are :class:`Ref` s resolved on first call, so the
checker, the cost model and static folding (:mod:`matloom.lang`) read it without the engine.
"""

from __future__ import annotations

from matloom.ops.op import NUMPY, Bounds, Interval, Kind, Op, Ref, not_constant, unbounded
from matloom.ops.period import Period, Repeats
from matloom.ops.table import OPS, operator_ops

__all__ = [
    "NUMPY",
    "OPS",
    "Bounds",
    "Interval",
    "Kind",
    "Op",
    "Period",
    "Ref",
    "Repeats",
    "not_constant",
    "operator_ops",
    "unbounded",
]
