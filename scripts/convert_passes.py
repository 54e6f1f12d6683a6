"""AST passes of the one-off recipe conversion (scripts/convert_recipes.py): the Sin-hash idiom
as ``Hash``, cell-local coordinates as ``Fract``, unused Defines dropped, and the View sized and
placed so that the converted program tiles."""

from __future__ import annotations

import math
from dataclasses import replace

from matloom.author.builtin.compose import derive_seed
from matloom.lang import ast as A
from matloom.lang.rewrite import map_expr
from matloom.lang.tileable import make_tileable, tileable_warnings


def _sin_hash_args(node: A.Node, defines: dict[str, A.Node]) -> tuple[A.Node, A.Node] | None:
    """(a, b) when ``node`` is ``Sin((a * 12.9898) + (b * 78.233)) * 43758.5453``."""
    while isinstance(node, A.Ref) and node.name in defines:
        node = defines[node.name]
    if not (isinstance(node, A.BinOp) and node.op == "*" and isinstance(node.right, A.Num)):
        return None
    if abs(node.right.value - 43758.5453) > 1e-6 or not isinstance(node.left, A.Call):
        return None
    if node.left.func != "Sin":
        return None
    inner = node.left.args[0].value
    terms = [(inner, 12.9898)]
    if isinstance(inner, A.BinOp) and inner.op == "+":
        terms = [(inner.left, 12.9898), (inner.right, 78.233)]
    parts: list[A.Node] = []
    for term, k in terms:
        if not (isinstance(term, A.BinOp) and term.op == "*" and isinstance(term.right, A.Num)):
            return None
        if abs(term.right.value - k) > 1e-6:
            return None
        parts.append(term.left)
    if len(parts) == 1:
        parts.append(A.Num(0))
    return parts[0], parts[1]


def _unfloor(node: A.Node) -> A.Node:
    """``Floor(e)`` -> ``e`` (Hash floors its operands itself)."""
    if isinstance(node, A.Call) and node.func == "Floor":
        return node.args[0].value
    return node


def hash_cells(program: A.Program, recipe: str) -> A.Program:
    """Rewrite ``h - Floor(h)`` of a Sin hash ``h`` into ``Hash(a, b, seed=...)``."""
    defines = {d.name: d.expr for d in program.defines}
    count = [0]

    def fn(node: A.Node) -> A.Node:
        if not (isinstance(node, A.BinOp) and node.op == "-"):
            return node
        right = node.right
        if not (isinstance(right, A.Call) and right.func == "Floor"):
            return node
        if right.args[0].value != node.left:
            return node
        args = _sin_hash_args(node.left, defines)
        if args is None:
            return node
        count[0] += 1
        seed = derive_seed("", 0, recipe, f"hash{count[0]}")
        return A.Call(
            "Hash",
            (
                A.Arg("x", _unfloor(args[0]), keyword=False),
                A.Arg("y", _unfloor(args[1]), keyword=False),
                A.Arg("seed", A.Num(seed)),
            ),
        )

    new = []
    for d in program.defines:
        expr = map_expr(d.expr, fn)
        new.append(replace(d, expr=expr))
        defines[d.name] = expr
    return drop_unused(replace(program, defines=tuple(new)))


def _fract_fn(node: A.Node) -> A.Node:
    """``e - Floor(e)`` -> ``Fract(e)``; ``e - Floor(e + c)`` -> ``Fract(e + c) - c``."""
    if not (isinstance(node, A.BinOp) and node.op == "-"):
        return node
    right = node.right
    if not (isinstance(right, A.Call) and right.func == "Floor"):
        return node
    inner = right.args[0].value
    if inner == node.left:
        return A.Call("Fract", (A.Arg("x", inner, keyword=False),))
    if (
        isinstance(inner, A.BinOp)
        and inner.op == "+"
        and inner.left == node.left
        and isinstance(inner.right, A.Num)
    ):
        fract = A.Call("Fract", (A.Arg("x", inner, keyword=False),))
        return A.BinOp("-", fract, inner.right)
    return node


def fract_cells(program: A.Program) -> A.Program:
    """Write cell-local coordinates with Fract, which the tileable check knows is periodic."""
    return replace(
        program,
        defines=tuple(replace(d, expr=map_expr(d.expr, _fract_fn)) for d in program.defines),
    )


def _refs(node: A.Node) -> set[str]:
    return {n.name for n in A.walk(node) if isinstance(n, A.Ref)}


def drop_unused(program: A.Program) -> A.Program:
    """Remove Defines nothing (transitively) used by the layers refers to."""
    live: set[str] = set()
    todo: list[str] = []
    for layer in program.layers:
        exprs = ([layer.alpha] if layer.alpha is not None else []) + [
            a for c in layer.channels for a in c.args
        ]
        for e in exprs:
            todo += list(_refs(e))
    by_name = {d.name: d for d in program.defines}
    while todo:
        name = todo.pop()
        if name in live or name not in by_name:
            continue
        live.add(name)
        todo += list(_refs(by_name[name].expr))
    return replace(program, defines=tuple(d for d in program.defines if d.name in live))


def with_view(program: A.Program, side: float) -> A.Program:
    view = program.view or A.ViewDecl(0.0, 0.0, 1.0, 1.0)
    x1, y1 = view.x1, view.y1
    if x1 < 0:  # centred windows stay centred
        return replace(
            program, view=replace(view, x1=-side / 2, y1=-side / 2, x2=side / 2, y2=side / 2)
        )
    return replace(program, view=replace(view, x2=x1 + side, y2=y1 + side))


def tileable_view(program: A.Program, view0: float) -> float | None:
    """The View side closest to ``view0`` (within x0.75..x1.5) at which the program tiles."""
    candidates = {view0}
    for num in range(1, 25):
        for den in range(1, 9):
            v = round(view0 * num / den / 4, 6)
            if 0.75 * view0 <= v <= 1.5 * view0:
                candidates.add(v)
    for v in sorted(candidates, key=lambda v: (abs(math.log(v / view0)), v)):
        if not tileable_warnings(make_tileable(with_view(program, v))):
            return v
    return None


ORIGINS = (0.0, 0.13, 0.29, 0.41, 0.07, 0.21, 0.37, 0.47)


def seam_safe(program: A.Program) -> tuple[A.Program, float | None]:
    """``program`` with its View moved so that no pattern boundary runs along the wrap edge
    (the seam ratio counts one as a seam): the first origin offset whose seam ratios stay
    within the limit at 64 and 128 pixels, else (program, None)."""
    from matloom.library.checks import evaluate_problems

    view = program.view
    assert view is not None
    side = view.x2 - view.x1
    for frac in ORIGINS:
        off = round(frac * side / max(1, round(side)), 4)
        moved = replace(
            program,
            view=replace(
                view, x1=view.x1 + off, x2=view.x2 + off, y1=view.y1 + off, y2=view.y2 + off
            ),
        )
        if all(not evaluate_problems(moved, size, True)[0] for size in (64, 128)):
            return moved, off
    return program, None
