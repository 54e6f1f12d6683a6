"""Generic bottom-up rewriting of expression trees and programs (the AST stays immutable)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from matloom.lang import ast as A

Rewrite = Callable[[A.Node], A.Node]


def map_expr(node: A.Node, fn: Rewrite) -> A.Node:
    """Rebuild ``node`` bottom-up, applying ``fn`` to every node after its children (post-order)."""
    if isinstance(node, A.Neg):
        node = replace(node, operand=map_expr(node.operand, fn))
    elif isinstance(node, A.BinOp):
        node = replace(node, left=map_expr(node.left, fn), right=map_expr(node.right, fn))
    elif isinstance(node, A.Call):
        args = tuple(replace(a, value=map_expr(a.value, fn)) for a in node.args)
        extra = tuple(map_expr(e, fn) for e in node.extra)
        node = replace(node, args=args, extra=extra)
    return fn(node)


def map_program(program: A.Program, fn: Rewrite) -> A.Program:
    """Apply :func:`map_expr` to every expression, in the reference's evaluation order."""
    defines = tuple(replace(d, expr=map_expr(d.expr, fn)) for d in program.defines)
    layers = []
    for layer in program.layers:
        alpha = map_expr(layer.alpha, fn) if layer.alpha is not None else None
        chans = tuple(
            replace(c, args=tuple(map_expr(a, fn) for a in c.args)) for c in layer.channels
        )
        layers.append(replace(layer, alpha=alpha, channels=chans))
    return replace(program, defines=defines, layers=tuple(layers))


def map_seeds(program: A.Program, fn: Callable[[int], int]) -> A.Program:
    """``program`` with every explicit ``seed=`` number replaced by ``fn(seed)``, in the
    reference's evaluation order (so a stateful ``fn`` sees the seeds as they are drawn)."""

    def seeds(node: A.Node) -> A.Node:
        if not isinstance(node, A.Call):
            return node
        args = tuple(
            replace(a, value=A.Num(fn(int(a.value.value))))
            if a.param == "seed" and isinstance(a.value, A.Num)
            else a
            for a in node.args
        )
        return replace(node, args=args)

    return map_program(program, seeds)
