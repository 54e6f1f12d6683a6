"""The engine's rules of the op table (:mod:`matloom.ops`): what needs arrays, kernels or the AST.

The op table names these by :class:`~matloom.ops.Ref` (``"module:function"``, imported on first
use), so that the table itself stays free of the engine:

* :mod:`.fields`: the field rules of the primitives (noise, patterns, shapes, Tile, transforms,
  coordinates) and the geometry builders, ``rule(interpreter, call, coords)``;
* :mod:`.fields_math`: the field rules of the language-2 functions that are not one element-wise
  op (Clamp, Mix, Smoothstep composed of element-wise ops; Hash);
* :mod:`.support`: where a field can be non-zero (coverage culling of Tile motifs).
"""
