"""Typed, frozen AST of a MatLoom program. The AST is data; evaluation lives in ``matloom.engine``.

Every node carries a source :class:`Span` that is excluded from equality, so two programs that
differ only in layout compare equal.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from matloom.lang.diagnostics import NO_SPAN, Span


def _span() -> Span:
    return field(default=NO_SPAN, compare=False, repr=False)  # type: ignore[return-value]


def _comments() -> tuple[Comment, ...]:
    return field(default=(), compare=False, repr=False)  # type: ignore[return-value]


@dataclass(frozen=True)
class Comment:
    """A ``#`` comment kept for ``matloom fmt``; ``text`` starts with ``#`` (trailing blanks cut).

    ``slot`` places it relative to the node that owns it: ``"leading"`` (own lines before the
    node) or ``"trailing"`` (after the node's last line, two spaces before ``#``). A
    :class:`Program` also uses ``"open"`` (after ``Material(``), ``"footer"`` (own lines before
    Material's closing ``)``), ``"close"`` (after that ``)``) and ``"end"`` (end of the file).
    Comments are excluded from equality, like spans. See :mod:`matloom.lang.comments`.
    """

    text: str
    slot: str = "leading"
    span: Span = _span()


@dataclass(frozen=True)
class Num:
    """A non-negative numeric literal (negatives are :class:`Neg`). ``int`` stays ``int``."""

    value: int | float
    span: Span = _span()


@dataclass(frozen=True)
class Str:
    """A string literal (enum values such as ``"euclidean"``)."""

    value: str
    span: Span = _span()


@dataclass(frozen=True)
class Lit:
    """``True``/``False``/``None`` (and the lowercase spellings)."""

    value: bool | None
    span: Span = _span()


@dataclass(frozen=True)
class Const:
    """A named constant: ``pi`` or ``e``."""

    name: str
    span: Span = _span()


@dataclass(frozen=True)
class Ref:
    """A reference to an earlier ``Define`` by name."""

    name: str
    span: Span = _span()


@dataclass(frozen=True)
class Neg:
    """Unary minus (the reference's ``Mul(-1, operand)``)."""

    operand: Node
    span: Span = _span()


@dataclass(frozen=True)
class BinOp:
    """Infix ``+ - * / **`` (functional forms ``Add(...)`` etc. parse to this too)."""

    op: str
    left: Node
    right: Node
    span: Span = _span()


@dataclass(frozen=True)
class Arg:
    """One bound argument of a call: the registry parameter it binds to and its value."""

    param: str
    value: Node
    keyword: bool = field(default=True, compare=False)
    span: Span = _span()


@dataclass(frozen=True)
class Call:
    """A call of a registry function. ``args`` are in parameter order; ``extra`` holds Path segments."""

    func: str
    args: tuple[Arg, ...] = ()
    extra: tuple[Node, ...] = ()
    span: Span = _span()

    def arg(self, name: str) -> Node | None:
        for a in self.args:
            if a.param == name:
                return a.value
        return None

    def written(self) -> frozenset[str]:
        return frozenset(a.param for a in self.args)


Node = Num | Str | Lit | Const | Ref | Neg | BinOp | Call
"""Any expression node."""


@dataclass(frozen=True)
class ViewDecl:
    """``View(x1, y1, x2, y2[, tileable=True][, unit_m=M])``: bottom-left and top-right corners
    of the sampling window; ``tileable``: the output repeats seamlessly with the window's size;
    ``unit_m``: metres per coordinate unit (the physical size exports record)."""

    x1: float
    y1: float
    x2: float
    y2: float
    span: Span = _span()
    comments: tuple[Comment, ...] = _comments()
    tileable: bool = False
    unit_m: float | None = None

    def as_tuple(self) -> tuple[float, float, float, float]:
        return (self.x1, self.y1, self.x2, self.y2)


@dataclass(frozen=True)
class Define:
    """``Define(name, expr)``: a named field usable by later Defines and layers."""

    name: str
    expr: Node
    span: Span = _span()
    name_span: Span = _span()
    comments: tuple[Comment, ...] = _comments()
    #: Language 3: ``Define(name(a, b), expr)``, a parameterised Define, used as ``name(x, y)``
    #: (a :class:`Call` whose ``func`` is the Define's name and whose args bind the parameters
    #: by name); ``expr`` refers to a parameter as a :class:`Ref`. Empty for a plain Define.
    #: :mod:`matloom.lang.macros` expands the uses before checking and evaluation.
    params: tuple[str, ...] = ()


@dataclass(frozen=True)
class ChannelSet:
    """One effective channel assignment of a layer, e.g. ``.basecolor(r, g, b)``."""

    name: str
    args: tuple[Node, ...]
    span: Span = _span()
    comments: tuple[Comment, ...] = _comments()


@dataclass(frozen=True)
class Layer:
    """A layer: optional alpha (coverage) and its channels in canonical order (last write wins)."""

    alpha: Node | None = None
    channels: tuple[ChannelSet, ...] = ()
    span: Span = _span()
    comments: tuple[Comment, ...] = _comments()

    def channel(self, name: str) -> ChannelSet | None:
        for c in self.channels:
            if c.name == name:
                return c
        return None


@dataclass(frozen=True)
class Program:
    """A whole program: optional View, Defines in source order, and the layers bottom first."""

    view: ViewDecl | None
    defines: tuple[Define, ...]
    layers: tuple[Layer, ...]
    span: Span = _span()
    comments: tuple[Comment, ...] = _comments()

    def define(self, name: str) -> Define | None:
        for d in self.defines:
            if d.name == name:
                return d
        return None

    @property
    def view_tuple(self) -> tuple[float, float, float, float]:
        return self.view.as_tuple() if self.view else (0.0, 0.0, 1.0, 1.0)

    @property
    def tileable(self) -> bool:
        """The program asks for tileable output (``View(..., tileable=True)``)."""
        return self.view is not None and self.view.tileable

    @property
    def unit_m(self) -> float | None:
        """Metres per coordinate unit from ``View(..., unit_m=...)``, else None."""
        return self.view.unit_m if self.view is not None else None


Commented = ViewDecl | Define | ChannelSet | Layer | Program
"""The nodes that carry ``comments``."""


def children(node: Node) -> tuple[Node, ...]:
    """Direct sub-expressions of a node, in evaluation (post-order, left to right) order."""
    if isinstance(node, Neg):
        return (node.operand,)
    if isinstance(node, BinOp):
        return (node.left, node.right)
    if isinstance(node, Call):
        return tuple(a.value for a in node.args) + node.extra
    return ()


def walk(node: Node):
    """Yield every node of an expression tree in post-order (children first)."""
    stack: list[tuple[Node, bool]] = [(node, False)]
    while stack:
        cur, done = stack.pop()
        if done:
            yield cur
            continue
        stack.append((cur, True))
        for child in reversed(children(cur)):
            stack.append((child, False))


def program_expressions(program: Program):
    """Yield (owner, expr) for every top-level expression in reference evaluation order.

    Owner is ``("define", name)`` or ``("layer", index, channel, arg_index)``. The order is the
    reference's construction order: Defines first, then each layer in fixed channel order.
    """
    for d in program.defines:
        yield ("define", d.name), d.expr
    for i, layer in enumerate(program.layers):
        if layer.alpha is not None:
            yield ("layer", i, "alpha", 0), layer.alpha
        for ch in layer.channels:
            for k, a in enumerate(ch.args):
                yield ("layer", i, ch.name, k), a
