"""Transform rules: what a coordinate transform does to the coordinates (``Op.transform``).

A transform (Translate, Scale, Rotate) evaluates its operand at ``coords(x, y, a, b)``, two
numbers (a, b) made from its parameters:

* ``values(param)``: (a, b) of static parameters, as Python floats (the numbers the frames are
  composed and keyed from, :mod:`matloom.lang.cost`): Translate's (dx, dy), Scale's (sx, sy),
  Rotate's (cos, sin) of its angle, with the portable cos and sin (the C library's pick their
  last bit by CPU);
* ``warp(values)``: (a, b) of a domain warp from its field parameters' values (arrays or floats,
  registry order), computed as the interpreter computes fields;
* ``matrix(a, b)``: the same map as the affine matrix ``(x', y') = M (x, y, 1)``, the six
  coefficients (a, b, c, d, e, f) of ``x' = a x + b y + c``, ``y' = d x + e y + f`` that the
  frames compose;
* ``back(u, v, a, b)``: a point of the operand's frame mapped back to the transform's frame
  (the support boxes of :mod:`matloom.engine.rules.support`).

What the transform does to a tileable View's periods is its period rule (:mod:`.period`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["Transform", "pair", "params", "turn"]

Param = Callable[[str], Any]
#: (a, b, c, d, e, f): x' = a x + b y + c, y' = d x + e y + f.
Affine = tuple[float, float, float, float, float, float]


@dataclass(frozen=True)
class Transform:
    """One coordinate transform's rules (see the module docstring)."""

    values: Callable[[Param], tuple[float, float]]
    coords: Callable[[Any, Any, Any, Any], tuple[Any, Any]]
    matrix: Callable[[float, float], Affine]
    warp: Callable[[list[Any]], tuple[Any, Any]]
    back: Callable[[float, float, float, float], tuple[float, float]]
    #: The map is affine (``matrix`` gives it). False (Quantize's cell centres): its frames
    #: equal no affine frame, and the interpreter gives them the periods of the op's period
    #: rule (:mod:`.period`) instead of reading them off a matrix.
    affine: bool = True


def pair(values: list[Any]) -> tuple[Any, Any]:
    """A warp's two field parameters' values, as they are."""
    return values[0], values[1]


def params(a: str, b: str) -> Callable[[Param], tuple[float, float]]:
    """(a, b): the values of the static parameters ``a`` and ``b``."""

    def rule(param: Param) -> tuple[float, float]:
        return param(a), param(b)

    return rule


def turn(angle: str) -> Callable[[Param], tuple[float, float]]:
    """(cos, sin) of the static angle ``angle`` in degrees, with the portable cos and sin."""

    def rule(param: Param) -> tuple[float, float]:
        from matloom.ops import portable_math as pm

        rad = math.radians(param(angle))
        return pm.scalar(pm.cos, rad), pm.scalar(pm.sin, rad)

    return rule
