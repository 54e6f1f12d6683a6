"""The op table: what every function of the language means to the engine, stated once.

``OPS[name]`` is the :class:`Op` of registry function ``name`` (numpy implementation, static
rule, bounds rule, fast-path opcode or NUMPY; see :mod:`matloom.engine.ops.op`). Importing this
package imports neither numpy nor the kernels (the static evaluation of :mod:`matloom.lang`
reads it).
"""

from __future__ import annotations

from matloom.engine.ops.op import NUMPY, Bounds, Interval, Kind, Op, Ref, not_constant, unbounded
from matloom.engine.ops.table import OPS, operator_ops

__all__ = [
    "NUMPY",
    "OPS",
    "Bounds",
    "Interval",
    "Kind",
    "Op",
    "Ref",
    "not_constant",
    "operator_ops",
    "unbounded",
]
