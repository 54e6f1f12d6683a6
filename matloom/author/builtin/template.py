"""Slot substitution for recipe templates.

Templates are MatLoom program text with ``{...}`` slots. MatLoom itself never uses braces, so a
slot is unambiguous. The slot forms are:

* ``{view}``: the side of the square View window (after scale words and sizes are applied);
* ``{name}``, ``{name*k}``, ``{name+k}``: a scalar slot (``rough``, ``wear``, ``gap`` ...),
  optionally scaled or offset by a literal; a slot may also hold a short expression text
  (e.g. the stripe axis ``X()`` or ``Y()``), substituted as is;
* ``{mf:40}``: a frequency giving 40 features across the View whatever its size (fine grain
  that must stay above pixel size and below the pattern scale);
* ``{h:0.02}``: a height in coordinate units, multiplied by the relief slot (finish words such
  as "rough" or "smooth" change it); use it for features sized in coordinate units;
* ``{hv:0.02}``: the same, also multiplied by View / default View: for ``{mf:...}`` features,
  whose coordinate size grows with the View, so their slopes (what the preview shows) stay put;
* ``{rgb:role}``: the three components ``r, g, b`` of a colour role;
* ``{mix:a,b,field}``: three channel expressions blending colour ``a`` (field = 0) to ``b``
  (field = 1);
* colour references may be shaded: ``role~0.3`` lightens by 30 %, ``role~-0.3`` darkens;
* ``{seed:name}``: an explicit seed derived from (prompt, user seed, recipe, name);
* ``{micro:part}`` and ``{mcol:role}``: the parts of the chosen micro-texture (see ``micro``).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from matloom.author.builtin import colours as C

_SLOT_RE = re.compile(r"\{([^{}:]+)(?::([^{}]*))?\}")
_OP_RE = re.compile(r"^([a-z_][a-z_0-9]*)([*+])(-?[0-9.]+)$")


class TemplateError(ValueError):
    """A template references a slot that does not exist (a bug in a recipe)."""


def fmt(value: float) -> str:
    """Compact number text: integers without a point, others with at most 4 decimals."""
    if abs(value - round(value)) < 1e-9:
        return str(int(round(value)))
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    if text in {"0", "-0"}:
        text = f"{value:.6f}".rstrip("0").rstrip(".")
    return text


@dataclass
class SlotValues:
    """Everything a template can reference, already resolved."""

    colours: Mapping[str, C.RGB]
    scalars: Mapping[str, float | str]
    view: float
    relief_scale: float
    view_ratio: float
    seed_for: Callable[[str], int]
    micro_parts: Mapping[str, str] = field(default_factory=dict)
    micro_colour: Callable[[str, C.RGB], str] | None = None


def colour_ref(ref: str, values: SlotValues) -> C.RGB:
    """Resolve ``role`` or ``role~amount`` to a colour."""
    name, _, amount = ref.strip().partition("~")
    if name not in values.colours:
        raise TemplateError(f"unknown colour role {name!r}")
    rgb = values.colours[name]
    return C.shade(rgb, float(amount)) if amount else rgb


def mix_expr(a: C.RGB, b: C.RGB, field_name: str) -> str:
    """Three channel expressions blending ``a`` to ``b`` by ``field_name``."""
    parts = []
    for ca, cb in zip(a, b, strict=True):
        delta = cb - ca
        parts.append(str(ca) if delta == 0 else f"({ca} + ({field_name} * {delta}))")
    return ", ".join(parts)


def _scalar(head: str, values: SlotValues) -> str:
    if head == "view":
        return fmt(values.view)
    if head in values.scalars:
        value = values.scalars[head]
        return value if isinstance(value, str) else fmt(value)
    m = _OP_RE.match(head)
    if m and (m.group(1) in values.scalars or m.group(1) == "view"):
        base = values.view if m.group(1) == "view" else values.scalars[m.group(1)]
        k = float(m.group(3))
        return fmt(base * k if m.group(2) == "*" else base + k)
    raise TemplateError(f"unknown slot {head!r}")


def _expand(match: re.Match[str], values: SlotValues) -> str:
    head, arg = match.group(1).strip(), match.group(2)
    if arg is None:
        return _scalar(head, values)
    if head == "rgb":
        return ", ".join(str(c) for c in colour_ref(arg, values))
    if head == "mix":
        a, b, field_name = (p.strip() for p in arg.split(",", 2))
        return mix_expr(colour_ref(a, values), colour_ref(b, values), field_name)
    if head == "h":
        return fmt(float(arg) * values.relief_scale)
    if head == "hv":
        return fmt(float(arg) * values.relief_scale * values.view_ratio)
    if head == "mf":
        return fmt(float(arg) / values.view)
    if head == "seed":
        return str(values.seed_for(arg.strip()))
    if head == "micro":
        if arg not in values.micro_parts:
            raise TemplateError(f"unknown micro part {arg!r}")
        return values.micro_parts[arg]
    if head == "mcol":
        if values.micro_colour is None:
            raise TemplateError("template uses {mcol:...} but no micro-texture is selected")
        return values.micro_colour(arg.strip(), colour_ref(arg, values))
    raise TemplateError(f"unknown slot form {head!r}")


def render(template: str, values: SlotValues) -> str:
    """Substitute every slot of ``template``; raises :class:`TemplateError` on unknown slots.

    Micro parts may themselves contain slots (``{seed:...}``, ``{h:...}``), so substitution runs
    until no slot is left (at most three passes).
    """
    text = template
    for _ in range(3):
        new = _SLOT_RE.sub(lambda m: _expand(m, values), text)
        if new == text:
            break
        text = new
    if _SLOT_RE.search(text):
        raise TemplateError(f"unresolved slot in {_SLOT_RE.search(text).group(0)!r}")  # type: ignore[union-attr]
    return text
