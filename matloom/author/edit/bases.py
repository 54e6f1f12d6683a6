"""Channel bases: the constant term of a layer channel written as ``(c + variation)``.

Many programs write a channel as a base value plus a noise-driven variation
(``.roughness((0.04 + (glazeGrain * 0.05)))``, ``.basecolor((12 + (ripple * 6)), ...)``); the
parameter list (:func:`matloom.lang.params.list_params`) exposes only literals, so the offline
edits add these bases as parameters of their own: ``layer:N.CHANNEL.base`` (a colour when all
three components have one), labelled with the layer's and the variation's names. The constant
is looked for down sums and differences (``((0.86 - lie * 0.16) + grain * 0.06)``) and inside a
``Clamp``. Setting one replaces only that constant, so the variation and its seed stay as they
were.
"""

from __future__ import annotations

import re
from dataclasses import replace

from matloom.lang import ast as A
from matloom.lang.params import Param, words
from matloom.vocab import CHANNELS

SUFFIX = ".base"


#: Calls a channel base is looked for inside (their first argument): a clamp keeps the value.
_WRAPPERS = frozenset({"Clamp"})


def _base_path(node: A.Node) -> tuple[str, ...] | None:
    """Where the constant term of ``node`` is: the constant of ``c + rest`` / ``rest + c`` /
    ``c - rest`` (``rest`` not a constant), looked for down the left of sums and differences
    (``(0.86 - a) + b``) and inside a ``Clamp``; None when there is none."""
    if isinstance(node, A.Call) and node.func in _WRAPPERS and node.args:
        sub = _base_path(node.args[0].value)
        return None if sub is None else ("call", *sub)
    if isinstance(node, A.BinOp) and node.op in ("+", "-"):
        left_num, right_num = isinstance(node.left, A.Num), isinstance(node.right, A.Num)
        if left_num and not right_num:
            return ("left",)
        if node.op == "+" and right_num and not left_num:
            return ("right",)
        for side in ("left", "right") if node.op == "+" else ("left",):
            sub = _base_path(getattr(node, side))
            if sub is not None:
                return (side, *sub)
    return None


def _at(node: A.Node, path: tuple[str, ...]) -> A.Node:
    for step in path:
        node = node.args[0].value if step == "call" else getattr(node, step)  # type: ignore[union-attr]
    return node


def _base(node: A.Node) -> float | None:
    """The constant term of a channel argument (see :func:`_base_path`), else None."""
    path = _base_path(node)
    if path is None:
        return None
    num = _at(node, path)
    return float(num.value) if isinstance(num, A.Num) else None


def _with_base(node: A.Node, value: float) -> A.Node:
    path = _base_path(node)
    assert path is not None
    return _put(node, path, A.Num(int(value) if float(value).is_integer() else float(value)))


def _put(node: A.Node, path: tuple[str, ...], num: A.Node) -> A.Node:
    if not path:
        return num
    step, rest = path[0], path[1:]
    if step == "call":
        assert isinstance(node, A.Call)
        first = replace(node.args[0], value=_put(node.args[0].value, rest, num))
        return replace(node, args=(first, *node.args[1:]))
    return replace(node, **{step: _put(getattr(node, step), rest, num)})


def _refs(node: A.Node) -> list[str]:
    return [n.name for n in A.walk(node) if isinstance(n, A.Ref)]


def base_params(program: A.Program) -> list[Param]:
    """The channel bases of ``program`` as parameters (``layer:N.CHANNEL.base``)."""
    out: list[Param] = []
    for i, layer in enumerate(program.layers):
        owner = words(layer.alpha.name) if isinstance(layer.alpha, A.Ref) else f"layer {i + 1}"
        for ch in layer.channels:
            spec = CHANNELS[ch.name]
            colour = spec.colour_args[:3] if spec.colour_args else ()
            bases = [_base(a) for a in ch.args]
            names = " ".join(dict.fromkeys(words(n) for a in ch.args for n in _refs(a)))
            label = f"{owner} {words(ch.name)} base ({names})" if names else f"{owner} {ch.name}"
            address = f"layer:{i + 1}.{ch.name}{SUFFIX}"
            span = ch.args[0].span
            if colour and all(bases[k] is not None for k in colour):
                value = tuple(float(bases[k]) for k in colour)  # type: ignore[arg-type]
                out.append(
                    Param(
                        address,
                        value,
                        "colour",
                        0.0,
                        255.0,
                        "sRGB 0-255",
                        label,  # type: ignore[arg-type]
                        (ch.name,),
                        span.line,
                        span.col,
                    )  # fmt: skip
                )
            elif not colour and len(ch.args) == 1 and bases[0] is not None:
                lo, hi = spec.clamp_lo, spec.clamp_hi
                out.append(
                    Param(
                        address,
                        bases[0],
                        "scalar",
                        lo,
                        hi,
                        None,
                        label,
                        (ch.name,),
                        span.line,
                        span.col,
                    )  # fmt: skip
                )
    return out


def is_base(address: str) -> bool:
    return address.endswith(SUFFIX) and address.startswith("layer:")


def set_bases(program: A.Program, values: dict[str, float | tuple[float, ...]]) -> A.Program:
    """``program`` with the channel bases ``values`` (address -> value) replaced."""
    layers = list(program.layers)
    for address, value in values.items():
        m = re.fullmatch(r"layer:(\d+)\.(\w+)" + re.escape(SUFFIX), address)
        if m is None or not 0 < int(m.group(1)) <= len(layers):
            raise ValueError(f"unknown channel base {address!r}")
        i, name = int(m.group(1)) - 1, m.group(2)
        vals = list(value) if isinstance(value, tuple) else [value]
        chans = []
        found = False
        for ch in layers[i].channels:
            if ch.name == name:
                found = True
                args = list(ch.args)
                want = 3 if CHANNELS[name].colour_args else 1
                if len(vals) != want:
                    raise ValueError(f"{address} takes {'[r, g, b]' if want == 3 else 'a number'}")
                for k, v in enumerate(vals):
                    if _base(args[k]) is None:
                        raise ValueError(f"{address}: argument {k + 1} has no constant base")
                    args[k] = _with_base(args[k], float(v))
                ch = replace(ch, args=tuple(args))
            chans.append(ch)
        if not found:
            raise ValueError(f"unknown channel base {address!r}")
        layers[i] = replace(layers[i], channels=tuple(chans))
    return replace(program, layers=tuple(layers))


#: Static parameters the edits may write when a call leaves them at their default (a joint
#: width written nowhere is still the width a "wider grout" request means).
IMPLICIT = {"Bricks": ("mortar",)}


def implicit_params(program: A.Program, listed: list[Param]) -> list[Param]:
    """Defaults of the :data:`IMPLICIT` parameters of the first such call in each Define, as
    parameters at the address they would have if written (``define:NAME.Bricks.mortar``)."""
    from matloom.vocab import FUNCTIONS

    known = {p.address: p for p in listed}
    out: list[Param] = []
    for d in program.defines:
        calls = sorted(
            (n for n in A.walk(d.expr) if isinstance(n, A.Call) and n.func in IMPLICIT),
            key=lambda c: c.span.start,
        )
        if not calls:
            continue
        call = calls[0]
        written = {a.param for a in call.args}
        prefix = f"define:{d.name}.{call.func}."
        sibling = next((p for p in listed if p.address.startswith(prefix)), None)
        affects = sibling.affects if sibling is not None else ("alpha",)
        for name in IMPLICIT[call.func]:
            spec = FUNCTIONS[call.func].param(name)
            if name in written or spec is None or f"{prefix}{name}" in known:
                continue
            out.append(
                Param(
                    f"{prefix}{name}",
                    spec.default,
                    "size",
                    spec.lo,
                    spec.hi,
                    "units",  # type: ignore[arg-type]
                    f"{words(d.name)} {name} width",
                    affects,
                    call.span.line,
                    call.span.col,
                )  # fmt: skip
            )
    return out


def set_implicit(program: A.Program, values: dict[str, float]) -> A.Program:
    """``program`` with the implicit parameters ``values`` written into their calls."""
    from matloom.lang.rewrite import map_program

    for address, value in values.items():
        m = re.fullmatch(r"define:(\w+)\.(\w+)\.(\w+)", address)
        d = program.define(m.group(1)) if m else None
        if m is None or d is None:
            raise ValueError(f"unknown parameter {address!r}")
        calls = sorted(
            (n for n in A.walk(d.expr) if isinstance(n, A.Call) and n.func == m.group(2)),
            key=lambda c: c.span.start,
        )
        if not calls:
            raise ValueError(f"unknown parameter {address!r}")
        start, param = calls[0].span.start, m.group(3)
        num = A.Num(int(value) if float(value).is_integer() else float(value))

        def fn(node: A.Node, start: int = start, param: str = param, num: A.Node = num) -> A.Node:
            if isinstance(node, A.Call) and node.span.start == start:
                return replace(node, args=(*node.args, A.Arg(param, num)))
            return node

        program = map_program(program, fn)
    return program


def slot_params(listed: list[Param]) -> list[Param]:
    """Colour slots listed as three scalars (``define:C_r``, ``_g``, ``_b``: the parameter list
    does so when a Define ``C`` of another kind exists) as one colour ``colour:C``."""
    by = {p.address: p for p in listed}
    out: list[Param] = []
    for p in listed:
        m = re.fullmatch(r"define:(\w+)_r", p.address)
        if m is None or p.kind == "colour":
            continue
        parts = [by.get(f"define:{m.group(1)}_{c}") for c in "rgb"]
        if any(q is None or isinstance(q.value, tuple) for q in parts):
            continue
        affects = tuple(sorted({a for q in parts for a in q.affects}))  # type: ignore[union-attr]
        value = tuple(float(q.value) for q in parts)  # type: ignore[union-attr,arg-type]
        out.append(
            Param(
                f"colour:{m.group(1)}",
                value,
                "colour",
                0.0,
                255.0,
                "sRGB 0-255",  # type: ignore[arg-type]
                f"{words(m.group(1))} colour",
                affects,
                p.line,
                p.col,
            )  # fmt: skip
        )
    return out


def expand_slots(assignments: dict[str, object]) -> dict[str, object]:
    """``colour:C`` assignments as the three ``define:C_r/_g/_b`` ones."""
    out: dict[str, object] = {}
    for k, v in assignments.items():
        if k.startswith("colour:") and isinstance(v, tuple | list) and len(v) == 3:
            name = k.removeprefix("colour:")
            out.update({f"define:{name}_{c}": float(x) for c, x in zip("rgb", v, strict=True)})
        else:
            out[k] = v
    return out
