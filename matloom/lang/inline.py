"""Inlined serialisation: replace every Define reference by a copy of its resolved expression."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.checker import MAX_NODES
from matloom.lang.codes import Code
from matloom.lang.cost import field_params
from matloom.lang.diagnostics import ProgramError
from matloom.lang.macros import ExpansionTooLarge, expand_program, expanded_size, has_macros
from matloom.lang.rewrite import map_expr, map_program
from matloom.lang.seeds import canonicalize_seeds, has_seedless_noise
from matloom.lang.static import static_number


def inline_defines(program: A.Program, program_seed: int = 0) -> A.Program:
    """Program with no Defines; every reference replaced by the (recursively inlined) expression.

    Except: a Define that makes a field parameter a per-sample field of X()/Y() only (e.g.
    ``Define(swirl, X() * 20)`` in ``Rotate(f, swirl)``) stays, since written inline such an
    expression is evaluated once at the origin (see ``ParamSpec.field``).

    Explicit noise seeds are kept verbatim, so the inlined program evaluates to the same maps.
    Omitted seeds are made explicit first (from ``program_seed``, the render default 0), as
    evaluation would: written out, a named noise's copies would each draw a seed of their own
    and the numbering of every later seedless call would shift.
    Comments of the removed Defines move to the program's leading comments (printed just before
    ``Material(``), in source order, so ``fmt --inline`` loses no comment text.
    Raises :class:`ProgramError` (E070) if the result would exceed the node limit: Defines that
    reuse each other can grow exponentially when written out.
    """
    size = 0
    if has_macros(program):  # language 3: parameterised Defines are written out first
        if has_seedless_noise(program):
            program = canonicalize_seeds(program, program_seed)
        try:
            program = expand_program(program)
            size = expanded_size(program)  # bounded before walking the (maybe huge) tree
        except ExpansionTooLarge:
            size = MAX_NODES + 1
    if size <= MAX_NODES:
        size = inlined_size(program)
    if size > MAX_NODES:
        message = f"inlining gives {size} expression nodes, more than the limit of {MAX_NODES}"
        hint = "keep the Defines: the program is valid as written"
        too_big = Code.SIZE_LIMIT.diagnostic(
            message, program.span, expected=f"at most {MAX_NODES} nodes", hint=hint
        )
        raise ProgramError([too_big])
    if program.defines and has_seedless_noise(program):
        program = canonicalize_seeds(program, program_seed)
    resolved: dict[str, A.Node] = {}

    def sub(node: A.Node) -> A.Node:
        if isinstance(node, A.Ref) and node.name in resolved:
            return resolved[node.name]
        return node

    for d in program.defines:
        resolved[d.name] = map_expr(d.expr, sub)
    pinned = _pinned_defines(program, sub)
    if pinned:
        # A pinned Define stays a reference everywhere, in other Defines' bodies too: written
        # out in a field parameter there, its X()/Y() would mean the origin value, not a field.
        resolved.clear()
        for d in program.defines:
            resolved[d.name] = map_expr(
                d.expr, lambda n: n if isinstance(n, A.Ref) and n.name in pinned else sub(n)
            )
    kept_defines = tuple(
        replace(d, expr=resolved[d.name]) for d in program.defines if d.name in pinned
    )
    moved = tuple(
        replace(c, slot="leading")
        for d in program.defines
        if d.name not in pinned
        for c in d.comments
    )
    kept = replace(program, defines=(), comments=moved + program.comments)

    def sub_unpinned(node: A.Node) -> A.Node:
        return node if isinstance(node, A.Ref) and node.name in pinned else sub(node)

    return replace(map_program(kept, sub_unpinned), defines=kept_defines)


def _pinned_defines(program: A.Program, sub: Callable[[A.Node], A.Node]) -> set[str]:
    """Defines that must stay: referenced in a field parameter (Translate's dx, ...) that
    inlining would turn into an expression of X()/Y() and constants only, which means its value
    at the origin there (language 1), not a per-sample field."""
    pinned: set[str] = set()
    for _, expr in A.program_expressions(program):
        for node in A.walk(expr):
            if not isinstance(node, A.Call):
                continue
            for name in field_params(node):
                value = node.arg(name)
                assert value is not None
                if static_number(map_expr(value, sub)) is not None:
                    pinned |= {n.name for n in A.walk(value) if isinstance(n, A.Ref)}
    return pinned


def inlined_size(program: A.Program) -> int:
    """Number of expression nodes of the inlined program, computed without building it."""
    size_of: dict[str, int] = {}
    total = 0
    for owner, expr in A.program_expressions(program):
        size = sum(size_of.get(n.name, 1) if isinstance(n, A.Ref) else 1 for n in A.walk(expr))
        if owner[0] == "define":
            size_of[owner[1]] = size
        else:
            total += size
    return total
