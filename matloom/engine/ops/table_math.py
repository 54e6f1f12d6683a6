"""Op entries of the language-2 math functions (see :mod:`matloom.vocab.functions_math`);
:data:`matloom.engine.ops.table.OPS` includes them."""

from __future__ import annotations

from matloom.engine.ops.op import Op

MATH_V2_ENTRIES: tuple[Op, ...] = ()
