"""``/api/vocab``: the vocabulary registry (:mod:`matloom.vocab`) as the editor reads it --
highlighting, completion, signature help and hover docs all come from here, so the editor never
writes the language down a second time."""

from __future__ import annotations

import math
from typing import Any

from matloom.lang.parse_expr import KEYWORDS
from matloom.vocab import CHANNELS, CONSTANTS, FUNCTIONS, LITERALS, FunctionSpec, ParamSpec
from matloom.vocab.spec import LANGUAGE_VERSION, format_default


def _number(v: float | None) -> float | None:
    return None if v is None or not math.isfinite(v) else v


def _default(p: ParamSpec) -> Any:
    if p.required:
        return None
    v = p.default
    if isinstance(v, float) and not math.isfinite(v):
        return format_default(v)
    return v


def _param(p: ParamSpec) -> dict[str, Any]:
    return {
        "name": p.name,
        "type": "enum" if p.choices else p.kind.value,
        "default": _default(p),
        "default_text": None if p.required else format_default(p.default),
        "doc": p.doc,
        "low": _number(p.lo),
        "high": _number(p.hi),
        "low_open": p.lo_open,
        "high_open": p.hi_open,
        "constraint": p.constraint_text(),
        "required": p.required,
        "choices": list(p.choices),
        "seed": p.is_seed,
        "field": p.field,
    }


def _function(f: FunctionSpec) -> dict[str, Any]:
    summary = f.doc.split("; ")[0].split(". ")[0]
    out: dict[str, Any] = {
        "name": f.name,
        "kind": f.family,
        "summary": summary,
        "doc": f.doc,
        "example": f.example,
        "signature": f.signature(),
        "params": [_param(p) for p in f.params],
        "returns": f.returns.value,
        "operator": f.operator,
    }
    if f.variadic is not None:
        out["variadic"] = _param(f.variadic)
    return out


#: The statements (grammar, not registry): name, signature and what each holds.
STATEMENTS: tuple[tuple[str, str, str], ...] = (
    ("View", "View(x1, y1, x2, y2, tileable=False, unit_m=None)",
     "the sampling window: bottom-left and top-right corners in coordinate units; tileable: "
     "the maps repeat with the window's size; unit_m: metres per coordinate unit"),
    ("Define", "Define(name, expr)", "a named field usable by later Defines and layers"),
    ("Material", "Material(Layer(...), ...)", "the layers, bottom first"),
    ("Layer", "Layer(alpha)", "a layer with its coverage (1 = everywhere); channels follow as "
     "methods, e.g. .basecolor(r, g, b)"),
)  # fmt: skip


def vocab_json() -> dict[str, Any]:
    """The registry for the editor (docs/studio-api.md)."""
    channels = []
    for c in CHANNELS.values():
        channels.append(
            {
                "name": c.name,
                "method": f".{c.name}",
                "args": list(c.arg_names),
                "defaults": list(c.defaults),
                "low": _number(c.clamp_lo),
                "high": _number(c.clamp_hi),
                "units": c.units,
                "doc": c.doc,
                "example": c.example,
                "colour": bool(c.colour_args),
            }
        )
    return {
        "language": LANGUAGE_VERSION,
        "functions": [_function(f) for f in FUNCTIONS.values()],
        "constants": [{"name": n, "value": v} for n, v in CONSTANTS.items()],
        "literals": list(LITERALS),
        "keywords": list(KEYWORDS),
        "statements": [{"name": n, "signature": s, "doc": d} for n, s, d in STATEMENTS],
        "channels": channels,
        "layer_methods": [f".{c.name}" for c in CHANNELS.values()],
        "comment": "#",
    }
