"""Keep the user's layout through an edit: the edited program written as the original text with
only the statements that changed replaced (and the added ones inserted), so a diff shows the
edit and nothing else.

An edit (``matloom edit``, ``matloom set``, the studio's panel) produces canonical text
(:func:`matloom.lang.printer.format_program`); a program written by hand or by the library is
rarely canonical (default arguments written out, positional arguments, ``0.0``), so printing it
whole would rewrite untouched lines. :func:`keep_layout` splices instead, and falls back to the
canonical text whenever the splice would not be the same program (statements removed or
reordered, a parse error): the result always prints to the same canonical program as
``after``.
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.printer import format_expr, format_layer, format_program


def _view_text(v: A.ViewDecl | None) -> str | None:
    return None if v is None else repr((v.as_tuple(), v.tileable, v.unit_m))


def keep_layout(before: str, after: str) -> str:
    """``after`` (an edit of ``before``, as text) with ``before``'s layout wherever a statement
    did not change; ``after`` itself when that cannot be done exactly."""
    try:
        old, new = parse(before), parse(after)
    except ValueError:
        return after
    old_defs = {d.name: d for d in old.defines}
    kept = [d.name for d in new.defines if d.name in old_defs]
    if kept != [d.name for d in old.defines] or len(new.layers) < len(old.layers):
        return after  # a statement removed or moved: the canonical text says it best
    if (old.view is None) != (new.view is None):
        return after
    if len(new.defines) > len(old.defines) and not old.defines:
        return after
    edits: list[tuple[int, int, str]] = []  # (start, end, text) in ``before``

    def piece(node: A.Define | A.Layer | A.ViewDecl) -> str:
        return after[node.span.start : node.span.end]

    if old.view is not None and new.view is not None:
        if _view_text(old.view) != _view_text(new.view):
            edits.append((old.view.span.start, old.view.span.end, piece(new.view)))
    anchor: int | None = None  # the end of the last kept Define, None before the first
    for d in new.defines:
        was = old_defs.get(d.name)
        if was is None:  # added: after the Define it follows in the new text
            if anchor is None:
                first = old.defines[0].span.start
                edits.append((first, first, piece(d) + "\n"))
            else:
                edits.append((anchor, anchor, "\n" + piece(d)))
            continue
        anchor = was.span.end
        if format_expr(was.expr) != format_expr(d.expr) or was.params != d.params:
            numbers = _numbers(was.expr, d.expr) if was.params == d.params else None
            edits += numbers if numbers is not None else [(was.span.start, was.span.end, piece(d))]
    for i, layer in enumerate(new.layers):
        if i < len(old.layers):
            was_layer = old.layers[i]
            if format_layer(was_layer) != format_layer(layer):
                numbers = _layer_numbers(was_layer, layer)
                edits += (
                    numbers
                    if numbers is not None
                    else [(was_layer.span.start, was_layer.span.end, piece(layer))]
                )
        elif old.layers:
            end = old.layers[-1].span.end
            edits.append((end, end, ",\n  " + piece(layer)))
        else:
            return after
    if not edits:
        return _ending(before, after) if format_program(old) == format_program(new) else after
    # from the end, so earlier offsets stay valid; the texts inserted at one point in order
    grouped: dict[tuple[int, int], str] = {}
    for start, end, piece_text in edits:
        grouped[(start, end)] = grouped.get((start, end), "") + piece_text
    text = before
    for (start, end), piece_text in sorted(grouped.items(), reverse=True):
        text = text[:start] + piece_text + text[end:]
    try:
        same = format_program(parse(text)) == format_program(new)
    except ValueError:
        return after
    return _ending(text, after) if same else after


def _ending(text: str, like: str) -> str:
    """``text`` ending as ``like`` does (the callers add the file's final newline)."""
    return text.rstrip("\n") + like[len(like.rstrip("\n")) :]


Edit = tuple[int, int, str]


def _numeric(node: A.Node) -> bool:
    return isinstance(node, A.Num) or (isinstance(node, A.Neg) and isinstance(node.operand, A.Num))


def _numbers(old: A.Node, new: A.Node) -> list[Edit] | None:
    """The edits that turn ``old`` into ``new`` by rewriting number literals in place, or None
    when the two differ in anything else. A keyword ``old`` writes and ``new`` lacks is taken
    as a default the printer leaves out (the caller checks the result prints as ``new``)."""
    if _numeric(old) and _numeric(new):
        if format_expr(old) == format_expr(new):
            return []
        return [(old.span.start, old.span.end, format_expr(new))]
    if type(old) is not type(new):
        return None
    if isinstance(old, A.Neg) and isinstance(new, A.Neg):
        return _numbers(old.operand, new.operand)
    if isinstance(old, A.BinOp) and isinstance(new, A.BinOp):
        if old.op != new.op:
            return None
        return _all_numbers([(old.left, new.left), (old.right, new.right)])
    if isinstance(old, A.Call) and isinstance(new, A.Call):
        if old.func != new.func or len(old.extra) != len(new.extra):
            return None
        olds = {a.param: a.value for a in old.args}
        if any(a.param not in olds for a in new.args):
            return None  # a keyword written now that was not: no place to put it
        pairs = [(olds[a.param], a.value) for a in new.args]
        return _all_numbers(pairs + list(zip(old.extra, new.extra, strict=True)))
    return [] if old == new else None


def _layer_numbers(old: A.Layer, new: A.Layer) -> list[Edit] | None:
    """:func:`_numbers` over a layer's coverage and channels (the same channels in order)."""
    if (old.alpha is None) != (new.alpha is None) or len(old.channels) != len(new.channels):
        return None
    pairs: list[tuple[A.Node, A.Node]] = []
    if old.alpha is not None and new.alpha is not None:
        pairs.append((old.alpha, new.alpha))
    for a, b in zip(old.channels, new.channels, strict=True):
        if a.name != b.name or len(a.args) != len(b.args):
            return None
        pairs += zip(a.args, b.args, strict=True)
    return _all_numbers(pairs)


def _all_numbers(pairs: list[tuple[A.Node, A.Node]]) -> list[Edit] | None:
    """:func:`_numbers` over each (old, new) pair, joined; None when any pair is None."""
    out: list[Edit] = []
    for old, new in pairs:
        sub = _numbers(old, new)
        if sub is None:
            return None
        out += sub
    return out


__all__ = ["keep_layout"]
