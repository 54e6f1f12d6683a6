"""Inlined serialisation: replace every Define reference by a copy of its resolved expression."""

from __future__ import annotations

from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.rewrite import map_expr, map_program


def inline_defines(program: A.Program) -> A.Program:
    """Program with no Defines; every reference replaced by the (recursively inlined) expression.

    Explicit noise seeds are kept verbatim, so the inlined program evaluates to the same maps.
    """
    resolved: dict[str, A.Node] = {}

    def sub(node: A.Node) -> A.Node:
        if isinstance(node, A.Ref) and node.name in resolved:
            return resolved[node.name]
        return node

    for d in program.defines:
        resolved[d.name] = map_expr(d.expr, sub)
    inlined = map_program(replace(program, defines=()), sub)
    return inlined
