"""Parameterised Defines (language 3): ``Define(name(a, b), expr)`` used as ``name(x, y)``.

The parser keeps them as written (a :class:`~matloom.lang.ast.Define` with ``params``; a use is
a :class:`~matloom.lang.ast.Call` whose ``func`` is the Define's name and whose args bind the
parameters), so the canonical printer writes them back. Everything that computes with a
program reads it expanded (:func:`expand_program`): each use is replaced by the Define's body
with its parameters replaced by the use's arguments (themselves expanded first), and the
parameterised Defines are dropped. The checker checks the expanded program, the cost model
counts each use as its expansion, the engine evaluates it, and ``fmt --inline`` and the
reference-compatible export write it (language-1 text: no parameterised Define remains).

A body may use earlier Defines (plain or parameterised) but not itself (no recursion: the
parser's E060). Arguments are shared, not copied, so the expanded program is a DAG of the size
of the text; its *tree* size (what an evaluation visits) can still grow exponentially with
nested uses, so :func:`expanded_size` measures it (memoised per node) and the checker refuses a
program past :data:`MAX_EXPANDED_TREE` (E070) before anything walks the tree.
"""

from __future__ import annotations

from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.rewrite import map_expr

__all__ = [
    "MAX_EXPANDED_TREE",
    "ExpansionTooLarge",
    "expand_program",
    "expanded_size",
    "has_macros",
]

#: Most nodes one expression may have once parameterised Defines are expanded.
MAX_EXPANDED_TREE = 200_000


class ExpansionTooLarge(ValueError):
    """Expanding the uses would make more than :data:`MAX_EXPANDED_TREE` nodes (nested uses
    copy bodies: ``f(f(a))`` holds two copies of f's body, so nesting grows exponentially)."""


def has_macros(program: A.Program) -> bool:
    """The program has a parameterised Define."""
    return any(d.params for d in program.defines)


def expand_program(program: A.Program) -> A.Program:
    """``program`` with every use of a parameterised Define expanded and those Defines dropped
    (the program itself when it has none). Uses with bad arguments (reported by the parser)
    get the parameter 0 for a missing argument."""
    if not has_macros(program):
        return program
    macros: dict[str, A.Define] = {}
    budget = [MAX_EXPANDED_TREE]

    def expand(node: A.Node) -> A.Node:
        return map_expr(node, _use)

    def _use(node: A.Node) -> A.Node:
        if not isinstance(node, A.Call) or node.func not in macros:
            return node
        d = macros[node.func]
        values = {a.param: a.value for a in node.args}
        try:
            return _substitute(d.expr, {p: values.get(p, A.Num(0)) for p in d.params}, budget)
        except RecursionError:
            raise ExpansionTooLarge("parameterised Defines nest too deeply") from None

    defines = []
    for d in program.defines:
        body = expand(d.expr)
        if d.params:
            macros[d.name] = replace(d, expr=body)
        else:
            defines.append(replace(d, expr=body))
    layers = []
    for layer in program.layers:
        alpha = None if layer.alpha is None else expand(layer.alpha)
        channels = tuple(replace(c, args=tuple(expand(a) for a in c.args)) for c in layer.channels)
        layers.append(replace(layer, alpha=alpha, channels=channels))
    # the dropped Defines' comments lead the program's (printed before ``Material(``), as
    # the inliner keeps removed Defines' comments
    moved = tuple(replace(c, slot="leading") for d in macros.values() for c in d.comments)
    return replace(
        program,
        defines=tuple(defines),
        layers=tuple(layers),
        comments=moved + program.comments,
    )


def _substitute(body: A.Node, values: dict[str, A.Node], budget: list[int]) -> A.Node:
    """``body`` with each parameter reference replaced by its value (shared, not copied).
    Memoised per node object, so a body that is a DAG (earlier uses' shared arguments) is
    rebuilt in its own size, not its tree's; unchanged sub-trees stay the same objects."""
    memo: dict[int, A.Node] = {}

    def go(node: A.Node) -> A.Node:
        hit = memo.get(id(node))
        if hit is not None:
            return hit
        out: A.Node = node
        if isinstance(node, A.Ref):
            out = values.get(node.name, node)
        elif isinstance(node, A.Neg):
            operand = go(node.operand)
            out = node if operand is node.operand else replace(node, operand=operand)
        elif isinstance(node, A.BinOp):
            left, right = go(node.left), go(node.right)
            if left is not node.left or right is not node.right:
                out = replace(node, left=left, right=right)
        elif isinstance(node, A.Call):
            args = tuple(replace(a, value=go(a.value)) for a in node.args)
            extra = tuple(go(e) for e in node.extra)
            changed = any(a.value is not b.value for a, b in zip(args, node.args, strict=True))
            if changed or any(a is not b for a, b in zip(extra, node.extra, strict=True)):
                out = replace(node, args=args, extra=extra)
        if out is not node:
            budget[0] -= 1
            if budget[0] < 0:
                raise ExpansionTooLarge(
                    f"parameterised Defines expand to more than {MAX_EXPANDED_TREE:,} nodes"
                )
        memo[id(node)] = out
        return out

    return go(body)


def expanded_size(program: A.Program) -> int:
    """The tree size (nodes) of the program's expressions, Define bodies included, memoised
    per node object (so a DAG of shared arguments is measured without walking the tree)."""
    sizes: dict[int, int] = {}

    def size(node: A.Node) -> int:
        # iterative post-order with memo (deep trees must not hit the recursion limit)
        stack: list[tuple[A.Node, bool]] = [(node, False)]
        while stack:
            cur, done = stack.pop()
            if id(cur) in sizes:
                continue
            kids = A.children(cur)
            if done:
                sizes[id(cur)] = min(1 + sum(sizes[id(k)] for k in kids), 1 << 62)
                continue
            stack.append((cur, True))
            stack.extend((k, False) for k in kids if id(k) not in sizes)
        return sizes[id(node)]

    return sum(size(e) for _, e in A.program_expressions(program))
