"""The ``View(x1, y1, x2, y2[, tileable=True][, unit_m=M])`` statement (called by the parser)."""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.codes import Code
from matloom.lang.lexer import as_float
from matloom.lang.parse_base import Bail, node_span
from matloom.lang.parse_expr import ExpressionParser
from matloom.lang.static import is_static, static_number
from matloom.vocab import LITERALS

#: View's keyword arguments after the four corners.
VIEW_KEYWORDS = ("tileable", "unit_m")


def parse_view(p: ExpressionParser) -> A.ViewDecl:
    """Parse a View statement at ``p``'s current token (the ``View`` name); raises
    :class:`~matloom.lang.parse_base.Bail` after reporting a malformed one."""
    kw = p.next()
    p.expect("(", "after View")
    values: list[float] = []
    bad = False
    for k in range(4):
        if k:
            p.expect(",", "between View arguments")
        tok = p.peek()
        node = p.parse_expr()
        v = static_number(node) if is_static(node) else None  # X()/Y() are not numbers here
        if v is None:
            p.diag(
                Code.BAD_VIEW,
                "View arguments must be numbers",
                node_span(node, tok.span),
                expected="View(x1, y1, x2, y2) with numeric corners",
            )
            bad, v = True, 0.0
        values.append(as_float(v))  # beyond the float range: inf, E061
    tileable = False
    unit_m: float | None = None
    seen: set[str] = set()
    while p.at(",") and p.peek(1).text in VIEW_KEYWORDS and p.at("=", 2):
        p.next()
        key = p.next().text
        p.next()
        tok = p.peek()
        if key in seen:
            raise p.fail(Code.ARGUMENT_COUNT, f"View's {key} is given twice", tok.span)
        seen.add(key)
        if key == "tileable":
            value = LITERALS.get(tok.text, 0) if tok.kind == "IDENT" else 0
            if not isinstance(value, bool):
                raise p.fail(
                    Code.BAD_VIEW,
                    "View's tileable must be True or False",
                    tok.span,
                    expected="View(x1, y1, x2, y2, tileable=True)",
                )
            p.next()
            tileable = value
        else:
            node = p.parse_expr()
            number = static_number(node) if is_static(node) else None
            metres = as_float(number) if isinstance(number, int | float) else None
            if metres is None or not 0 < metres < float("inf"):
                raise p.fail(
                    Code.BAD_VIEW,
                    "View's unit_m must be a number of metres > 0",
                    node_span(node, tok.span),
                    expected="View(x1, y1, x2, y2, unit_m=0.5)",
                )
            unit_m = metres
    if p.at(","):
        raise p.fail(
            Code.ARGUMENT_COUNT,
            "View takes exactly 4 arguments",
            p.peek().span,
            expected="View(x1, y1, x2, y2) or View(x1, y1, x2, y2, tileable=True, unit_m=0.5)",
        )
    p.expect(")", "to close View(...)")
    if bad:  # drop the View, so its placeholder corners cause no follow-on errors
        raise Bail()
    return A.ViewDecl(*values, span=p.span_from(kw.span), tileable=tileable, unit_m=unit_m)
