"""Binding of call arguments to registry parameters (positional by index, keywords by name).

Keyword arguments may come before positional ones, as in the reference: ``fBm(seed=1, 3)``
binds 3 to ``octaves``. The expression parser calls :func:`bind_call` with itself as the
:class:`~matloom.lang.diagnostics.Reporter` of the problems found.
"""

from __future__ import annotations

from matloom.lang import ast as A
from matloom.lang.codes import Code
from matloom.lang.diagnostics import Reporter, Span, did_you_mean, hint_for
from matloom.lang.lexer import Token
from matloom.vocab import CHANNELS, FUNCTIONS

_BINARY = {"Add": "+", "Sub": "-", "Mul": "*", "Div": "/", "Pow": "**"}
_NOT_FUNCTIONS = {
    "View": "View(...) is a statement and must be the first line",
    "Define": "Define(...) is a statement; reference a Define by its bare name",
    "Material": "Material(...) is the last statement, not an expression",
    "Layer": "Layer(...) only appears inside Material(...)",
    "Ref": "reference a Define by its bare name, without Ref(...)",
}


def bind_call(
    p: Reporter, name_tok: Token, raw: list[tuple[Token | None, A.Node, Span]], span: Span
) -> A.Node:
    """The call ``name_tok(raw...)`` at ``span`` with its arguments (``raw``: keyword token or
    None, value, span) bound to the function's parameters; problems are reported to ``p``.
    Arithmetic functions (``Add`` ...) become their operators."""
    name = name_tok.text
    spec = FUNCTIONS.get(name)
    if spec is None:
        from matloom.lang.aliases import function_alias

        hint = _NOT_FUNCTIONS.get(name) or hint_for(name, FUNCTIONS) or function_alias(name)
        if hint is None and name.lower() in CHANNELS:
            hint = f"'{name}' is a layer channel: chain it as .{name.lower()}(...) on a Layer"
        p.diag(
            Code.UNKNOWN_FUNCTION,
            f"unknown function '{name}'",
            name_tok.span,
            expected="a function of the MatLoom vocabulary",
            hint=hint,
        )
        args = tuple(A.Arg(f"#{k}", v, False, s) for k, (_, v, s) in enumerate(raw))
        return A.Call(name, args, (), span)

    bound: dict[str, A.Arg] = {}
    extra: list[A.Node] = []
    pos = 0
    names = spec.param_names
    for key, value, aspan in raw:
        if key is not None:
            pname = key.text
            if spec.param(pname) is None:
                guess = did_you_mean(pname, names)
                hint = f"did you mean `{guess}=`?" if guess else None
                if spec.variadic is not None and pname == spec.variadic.name:
                    hint = f"pass {spec.variadic.name} as extra positional arguments"
                p.diag(
                    Code.UNKNOWN_PARAMETER,
                    f"unknown parameter '{pname}' for {name}",
                    key.span,
                    expected=_param_list(spec.param_names)
                    if names
                    else f"{name}() takes no arguments",
                    hint=hint,
                )
                continue
            if pname in bound:
                p.diag(
                    Code.DUPLICATE_ARGUMENT,
                    f"duplicate value for parameter '{pname}' in {name}",
                    key.span,
                    expected="each parameter at most once",
                )
                continue
            bound[pname] = A.Arg(pname, value, True, aspan)
            continue
        # positional: the next parameter index (keywords do not advance it, as in the reference)
        if pos < len(names):
            pname = names[pos]
            pos += 1
            if pname in bound:
                p.diag(
                    Code.DUPLICATE_ARGUMENT,
                    f"duplicate value for parameter '{pname}' in {name} "
                    "(given by keyword and by position)",
                    aspan,
                    expected="each parameter at most once",
                )
                continue
            bound[pname] = A.Arg(pname, value, False, aspan)
        elif spec.variadic is not None:
            extra.append(value)
        else:
            p.diag(
                Code.TOO_MANY_ARGUMENTS,
                f"too many positional arguments for {name}: expected at most "
                f"{len(names)}, got {sum(1 for k, _, _ in raw if k is None)}",
                aspan,
                expected=spec.signature(),
            )
    missing = [q.name for q in spec.params if q.required and q.name not in bound]
    if missing:
        p.diag(
            Code.MISSING_ARGUMENT,
            f"{name}() is missing required argument"
            f"{'s' if len(missing) > 1 else ''}: {', '.join(missing)}",
            span,
            expected=spec.signature(),
        )
    if spec.variadic is not None and len(extra) < spec.min_variadic and not missing:
        p.diag(
            Code.BAD_SEGMENTS,
            f"{name} needs at least {spec.min_variadic} segment (LineTo or CubicTo)",
            span,
            expected=spec.signature(),
        )
    if name in _BINARY and not missing:
        left = bound[names[0]].value
        right = bound[names[1]].value
        return A.BinOp(_BINARY[name], left, right, span)
    args = tuple(bound[n] for n in names if n in bound)
    return A.Call(name, args, tuple(extra), span)


def _param_list(names: tuple[str, ...]) -> str:
    return "one of " + ", ".join(f"{n}=" for n in names)
