"""Attach ``#`` comments to the AST so that ``matloom fmt`` keeps every one of them.

The lexer keeps comments aside (:attr:`Lexer.comments`), so the parser's token stream is the same
with or without them. After parsing, :func:`attach_comments` gives each comment to a node, as an
:class:`~matloom.lang.ast.Comment` in a *slot*:

* a comment on its own line goes to the construct that starts on the next code token: a View, a
  Define, ``Material(`` (Program ``"leading"``), a ``Layer(...)`` or a channel call ``.name(...)``
  — as a ``"leading"`` comment. Before Material's closing ``)`` it is a Program ``"footer"``;
  after the last code token it is a Program ``"end"`` comment.
* a comment after code on its line goes to the construct that ends at the last code token of
  that line (a separating ``,`` is skipped): a View, a Define, a Layer head ``Layer(...)``, a
  channel call, ``Material(`` (Program ``"open"``) or Material's ``)`` (Program ``"close"``) —
  as a ``"trailing"`` comment.
* any other comment (inside an expression, or on a channel call the AST drops, such as a
  ``.alpha(...)`` or an overwritten channel) becomes a ``"leading"`` comment of the innermost
  channel call, layer or statement around it; between layers, of the next layer (or the
  footer). No comment text is ever dropped.

Printing them is the printer's job (``format_program(program, comments=True)``).
"""

from __future__ import annotations

import bisect
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TypeVar

from matloom.lang import ast as A
from matloom.lang.lexer import Token

Key = tuple[object, ...]
"""Names a comment owner: ``("program",)``, ``("view",)``, ``("define", i)``, ``("layer", i)``
or ``("channel", layer_index, channel_index)``."""


@dataclass
class _Anchor:
    """A construct comments can attach to: ``start``/``end`` bound its head (what leading and
    trailing comments refer to), ``outer`` the end of everything it contains."""

    key: Key
    start: int
    end: int
    outer: int
    children: list[_Anchor] = field(default_factory=list)
    starts: list[int] = field(default_factory=list)  # of the children, for bisection


class _Attacher:
    def __init__(self, program: A.Program, toks: Sequence[Token]) -> None:
        self.program = program
        self.toks = toks
        self.starts = [t.span.start for t in toks]
        self.index = {t.span.start: k for k, t in enumerate(toks) if t.kind != "EOF"}
        self.material: _Anchor | None = None
        self.close: Token | None = None
        self.root = _Anchor(("program",), 0, 0, toks[-1].span.end + 1)
        self.root.children = self._statements()
        self.by_start: dict[int, _Anchor] = {}
        self.by_end: dict[int, _Anchor] = {}
        self._register(self.root)
        self.out: dict[Key, list[A.Comment]] = {}
        self.trailed: set[tuple[Key, str]] = set()  # one trailing comment per line of code

    # ------------------------------------------------------------------ anchors
    def _statements(self) -> list[_Anchor]:
        top: list[_Anchor] = []
        p = self.program
        if p.view is not None:
            top.append(_Anchor(("view",), p.view.span.start, p.view.span.end, p.view.span.end))
        for k, d in enumerate(p.defines):
            top.append(_Anchor(("define", k), d.span.start, d.span.end, d.span.end))
        material = self._material()
        if material is not None:
            top.append(material)
        top.sort(key=lambda a: a.start)
        return top

    def _material(self) -> _Anchor | None:
        """Anchor of ``Material(`` ... ``)``; its children are the layers and their channels."""
        first = self.program.layers[0].span.start if self.program.layers else None
        k = self._material_keyword(first)
        if k is None:
            return None
        close = self._matching(k + 1)
        self.close = self.toks[close] if close is not None else None
        outer = self.close.span.end if self.close else self.toks[-1].span.end
        self.material = _Anchor(
            ("program",), self.toks[k].span.start, self.toks[k + 1].span.end, outer
        )
        for i, layer in enumerate(self.program.layers):
            self.material.children.append(self._layer(i, layer))
        return self.material

    def _material_keyword(self, first_layer: int | None) -> int | None:
        """Index of the ``Material`` token: the last one followed by ``(`` before the first layer."""
        found = None
        for k in range(len(self.toks) - 1):
            tok = self.toks[k]
            if first_layer is not None and tok.span.start >= first_layer:
                break
            if tok.kind == "IDENT" and tok.text == "Material" and self.toks[k + 1].text == "(":
                found = k
                if first_layer is None:
                    break
        return found

    def _matching(self, open_index: int) -> int | None:
        """Index of the ``)`` that closes the ``(`` at ``open_index``."""
        depth = 0
        for k in range(open_index, len(self.toks)):
            tok = self.toks[k]
            if tok.kind == "OP" and tok.text == "(":
                depth += 1
            elif tok.kind == "OP" and tok.text == ")":
                depth -= 1
                if depth == 0:
                    return k
        return None

    def _layer(self, i: int, layer: A.Layer) -> _Anchor:
        k = self.index.get(layer.span.start)
        close = self._matching(k + 1) if k is not None else None
        head_end = self.toks[close].span.end if close is not None else layer.span.end
        anchor = _Anchor(("layer", i), layer.span.start, head_end, layer.span.end)
        for j, ch in enumerate(layer.channels):
            name = self.index.get(ch.span.start)
            dot = self.toks[name - 1].span.start if name else ch.span.start
            anchor.children.append(_Anchor(("channel", i, j), dot, ch.span.end, ch.span.end))
        anchor.children.sort(key=lambda a: a.start)
        return anchor

    def _register(self, anchor: _Anchor) -> None:
        anchor.starts = [a.start for a in anchor.children]
        for a in anchor.children:
            self.by_start.setdefault(a.start, a)
            self.by_end.setdefault(a.end, a)
            self._register(a)

    # ------------------------------------------------------------------ placement
    def place(self, comment: Token) -> None:
        pos, line = comment.span.start, comment.span.line
        k = bisect.bisect_left(self.starts, pos)
        nxt = self.toks[k]
        prev = self.toks[k - 1] if k > 0 else None
        if prev is None or prev.span.line < line:
            self._own_line(comment, nxt)
        else:
            self._trailing(comment, k - 1)

    def _own_line(self, comment: Token, nxt: Token) -> None:
        anchor = self.by_start.get(nxt.span.start)
        if anchor is not None:
            self._add(anchor.key, comment, "leading")
        elif self.close is not None and nxt is self.close:
            self._add(("program",), comment, "footer")
        elif nxt.kind == "EOF":
            self._add(("program",), comment, "end")
        else:
            self._fallback(comment)

    def _trailing(self, comment: Token, k: int) -> None:
        while k > 0 and self.toks[k].kind == "OP" and self.toks[k].text == ",":
            k -= 1
        anchor = self.by_end.get(self.toks[k].span.end)
        slot = "open" if anchor is not None and anchor is self.material else "trailing"
        if self.close is not None and self.toks[k] is self.close:
            self._add(("program",), comment, "close")
        elif anchor is not None and (anchor.key, slot) not in self.trailed:
            self.trailed.add((anchor.key, slot))
            self._add(anchor.key, comment, slot)
        else:
            self._fallback(comment)

    def _fallback(self, comment: Token) -> None:
        """Leading comment of the innermost construct around ``comment`` (see module doc)."""
        pos = comment.span.start
        owner = self.root
        while (inner := _containing(owner, pos)) is not None:
            owner = inner
        if owner is self.root or owner is self.material:  # between statements or layers
            following = _following(owner, pos)
            if following is not None:
                self._add(following.key, comment, "leading")
            else:
                self._add(("program",), comment, "end" if owner is self.root else "footer")
        else:
            self._add(owner.key, comment, "leading")

    def _add(self, key: Key, comment: Token, slot: str) -> None:
        self.out.setdefault(key, []).append(A.Comment(comment.text, slot, comment.span))

    # ------------------------------------------------------------------ result
    def result(self) -> A.Program:
        p, out = self.program, self.out
        view = _with(p.view, out.get(("view",))) if p.view is not None else None
        defines = tuple(_with(d, out.get(("define", k))) for k, d in enumerate(p.defines))
        layers = []
        for i, layer in enumerate(p.layers):
            chans = tuple(
                _with(c, out.get(("channel", i, j))) for j, c in enumerate(layer.channels)
            )
            layers.append(_with(replace(layer, channels=chans), out.get(("layer", i))))
        rebuilt = replace(p, view=view, defines=defines, layers=tuple(layers))
        return _with(rebuilt, out.get(("program",)))


_N = TypeVar("_N", A.ViewDecl, A.Define, A.ChannelSet, A.Layer, A.Program)


def _with(node: _N, comments: list[A.Comment] | None) -> _N:
    """``node`` with ``comments`` appended to its own."""
    return replace(node, comments=node.comments + tuple(comments)) if comments else node


def _containing(parent: _Anchor, pos: int) -> _Anchor | None:
    """The child of ``parent`` whose extent contains ``pos``."""
    k = bisect.bisect_right(parent.starts, pos) - 1
    if k >= 0 and parent.children[k].start <= pos < parent.children[k].outer:
        return parent.children[k]
    return None


def _following(parent: _Anchor, pos: int) -> _Anchor | None:
    """The first child of ``parent`` that starts after ``pos``."""
    k = bisect.bisect_right(parent.starts, pos)
    return parent.children[k] if k < len(parent.children) else None


def attach_comments(
    program: A.Program, comments: Sequence[Token], toks: Sequence[Token]
) -> A.Program:
    """``program`` with every comment token attached to a node (see the module doc)."""
    if not comments:
        return program
    attacher = _Attacher(program, toks)
    for comment in comments:
        attacher.place(comment)
    return attacher.result()


def all_comments(program: A.Program) -> list[A.Comment]:
    """Every comment of ``program``, owners in print order (View, Defines, Material, layers)."""
    out: list[A.Comment] = []
    if program.view is not None:
        out += program.view.comments
    for d in program.defines:
        out += d.comments
    out += program.comments
    for layer in program.layers:
        out += layer.comments
        for ch in layer.channels:
            out += ch.comments
    return out
