"""Named values in static parameters: the constant Defines of a program and their resolution.

A static parameter (a frequency, size, mortar, octave count, angle, seed, ...: a ``float`` or
``int`` parameter that does not accept fields) takes a number or constant arithmetic. It also
takes a constant expression of *constant Defines*: Defines whose expression, with the earlier
constant Defines it names substituted, is constant arithmetic (no noise, pattern, ``X()`` or
``Y()``)::

    Define(grout, 0.02)
    Define(scale, 2)
    ... Bricks(mortar=grout) ... Perlin(base_freq=(scale * 8)) ...

:func:`resolve_static` writes each such name out as the Define's (substituted) expression, so
the program means exactly what it means with the constant written in: every consumer of static
values (the checker's range checks, the cost model, the tileable analysis, the interpreter)
reads the resolved program and sees constant arithmetic, and the maps are bit-identical to
the program with the literal. A Define that is a field stays a reference (error E045 in a
static parameter). Field parameters (``ParamSpec.field``) are never touched: there a Define
reference is a per-sample field, as before. The canonical printer keeps the names;
:func:`plain_numbers` writes plain numbers instead (``fmt --inline``, text for the reference
engine).
"""

from __future__ import annotations

import math
from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.rewrite import map_expr, map_program
from matloom.lang.static import is_static, static_number
from matloom.vocab import FUNCTIONS, Kind

#: Most nodes a Define's substituted expression may have to be written out as an expression;
#: a larger one (Defines doubling each other) is written as its value, which is the same number.
_MAX_EXPANSION = 256

Constants = dict[str, A.Node]
"""Constant Define name -> its expression with earlier constant Defines substituted."""


def constant_defines(program: A.Program) -> Constants:
    """The program's constant Defines, in source order, each with its references substituted."""
    out: Constants = {}
    sizes: dict[str, int] = {}
    for d in program.defines:
        if any(isinstance(n, A.Ref) and n.name not in out for n in A.walk(d.expr)):
            continue  # names a field Define (or an unknown name)
        expr = substitute(d.expr, out)
        if not is_static(expr):
            continue
        size = sum(sizes.get(n.name, 1) if isinstance(n, A.Ref) else 1 for n in A.walk(d.expr))
        out[d.name] = expr if size <= _MAX_EXPANSION else _value_node(expr)
        sizes[d.name] = size if size <= _MAX_EXPANSION else 2
    return out


def substitute(node: A.Node, consts: Constants) -> A.Node:
    """``node`` with every reference to a constant Define replaced by its expression."""
    if not consts or not _has_ref(node):
        return node

    def sub(n: A.Node) -> A.Node:
        return consts.get(n.name, n) if isinstance(n, A.Ref) else n

    return map_expr(node, sub)


def is_static_param(func: str, name: str) -> bool:
    """Whether ``func``'s parameter ``name`` takes a static number (not a field)."""
    spec = FUNCTIONS.get(func)
    p = spec.param(name) if spec is not None else None
    return p is not None and p.kind in (Kind.FLOAT, Kind.INT) and not p.field


def static_refs(node: A.Node) -> list[str]:
    """Names of the Defines a static parameter's value refers to, in order, each once."""
    names = [n.name for n in A.walk(node) if isinstance(n, A.Ref)]
    return list(dict.fromkeys(names))


def resolve_static(program: A.Program, consts: Constants | None = None) -> A.Program:
    """``program`` with constant Define names in static parameters written out (the same
    object when it has none, so programs without named values are untouched)."""
    if not program.defines:
        return program
    consts = constant_defines(program) if consts is None else consts
    if not consts or not _names_in_static(program, consts):
        return program
    return map_program(program, lambda n: _resolve_call(n, consts))


def plain_numbers(program: A.Program) -> A.Program:
    """``program`` as text for the reference engine: static parameters that name constant
    Defines are written out, so the canonical printer (which folds constant arithmetic in
    static parameters) prints plain numbers. The Defines themselves stay."""
    return resolve_static(program)


def _resolve_call(node: A.Node, consts: Constants) -> A.Node:
    if not isinstance(node, A.Call):
        return node
    args = tuple(
        replace(a, value=substitute(a.value, consts))
        if is_static_param(node.func, a.param) and _names_const(a.value, consts)
        else a
        for a in node.args
    )
    return replace(node, args=args)


def _names_in_static(program: A.Program, consts: Constants) -> bool:
    return any(
        isinstance(n, A.Call)
        and any(is_static_param(n.func, a.param) and _names_const(a.value, consts) for a in n.args)
        for _, e in A.program_expressions(program)
        for n in A.walk(e)
    )


def _names_const(node: A.Node, consts: Constants) -> bool:
    return any(isinstance(n, A.Ref) and n.name in consts for n in A.walk(node))


def _has_ref(node: A.Node) -> bool:
    return any(isinstance(n, A.Ref) for n in A.walk(node))


def _value_node(node: A.Node) -> A.Node:
    """The value of a constant expression as a literal (``Neg`` of one when negative); the
    node itself when it is not constant or its value is not a plain finite number."""
    v = static_number(node)
    if v is None or isinstance(v, bool) or not is_static(node):
        return node
    if isinstance(v, float) and v != v:  # NaN: keep the expression (the checker reports it)
        return node
    try:
        negative = math.copysign(1, v) < 0
    except OverflowError:  # an exact integer past the float range: keep its arithmetic
        return node
    return A.Neg(A.Num(-v)) if negative else A.Num(v)
