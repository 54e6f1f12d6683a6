"""The structured view of a program and the panel's edits (``/api/check``, ``/api/format``,
``/api/structure``, ``/api/set``, ``/api/layers``).

The structure is the exposed-parameter model of :mod:`matloom.lang.params` (every literal a
parameter with its registry range), grouped the way the panel shows it: the View, the Defines
and the layers (1-based, bottom first), plus the noise seeds (:mod:`matloom.studio.seeds`).
Edits go through the language's own code -- :func:`matloom.lang.params.set_params` for values,
the canonical printer with comments for layer moves -- and come back as text that keeps the
user's comments and names (:func:`matloom.studio.rewrite.program_text`).
"""

from __future__ import annotations

import hashlib
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from matloom.lang import ast as A
from matloom.lang.params import Param, list_params
from matloom.lang.printer import format_expr, format_layer, format_program
from matloom.studio.program import check_json, checked, diagnostics_json, layer_label
from matloom.studio.protocol import ApiError
from matloom.studio.rewrite import program_text
from matloom.studio.seeds import seed_entries

if TYPE_CHECKING:
    from matloom.engine.session import Session

__all__ = [
    "check_json",
    "checked",
    "diagnostics_json",
    "format_text",
    "layer_label",
    "layer_op",
    "set_values",
    "structure_json",
]

LAYER_OPS = ("move", "duplicate", "delete")


def format_text(text: str) -> str:
    """``/api/format``: the canonical text, comments kept (``matloom fmt``)."""
    return format_program(checked(text), comments=True)


# ---------------------------------------------------------------------------- structure
def structure_json(text: str, session: Session | None = None) -> dict[str, Any]:
    """``/api/structure`` (docs/studio-api.md)."""
    program = checked(text, session)
    params = list_params(program)
    v = program.view
    x1, y1, x2, y2 = program.view_tuple
    view = {"x1": x1, "y1": y1, "x2": x2, "y2": y2, "tileable": program.tileable,
            "unit_m": v.unit_m if v is not None else None}  # fmt: skip
    return {
        "params": [p.to_json() for p in params],
        "view": view,
        "defines": [_define_json(d, params) for d in program.defines],
        "layers": [_layer_json(k, layer, params) for k, layer in enumerate(program.layers)],
        "seeds": [s.to_json() for s in seed_entries(program)],
    }


def _owned(prefix: str, params: list[Param]) -> list[str]:
    return [p.address for p in params if p.address == prefix or p.address.startswith(prefix + ".")]


def _define_json(d: A.Define, params: list[Param]) -> dict[str, Any]:
    owned = _owned(f"define:{d.name}", params)
    if d.name.endswith("_r"):  # a colour slot C_r, C_g, C_b is one parameter define:C
        slot = f"define:{d.name[:-2]}"
        owned += [p.address for p in params if p.address == slot and p.kind == "colour"]
    return {
        "name": d.name,
        "line": d.span.line,
        "text": f"Define({d.name}, {format_expr(d.expr)})",
        "params": owned,
    }


def _layer_json(k: int, layer: A.Layer, params: list[Param]) -> dict[str, Any]:
    return {
        "index": k + 1,
        "line": layer.span.line,
        "text": "\n".join(line.strip() for line in format_layer(layer)),
        "label": layer_label(k, layer),
        "params": _owned(f"layer:{k + 1}", params),
    }


# ---------------------------------------------------------------------------- edits
def set_values(text: str, values: dict[str, Any], session: Session | None = None) -> dict[str, Any]:
    """``/api/set``: the text with the parameters set (only the touched literals rewritten
    where possible), and the clamping warnings. 400 for an unknown address or a wrong value.

    With a ``session`` (the studio's), the program's parameter listing is kept per text and the
    new text's analysis is left in the session's cache, so the evaluation, structure and check
    requests that follow a slider step parse nothing again."""
    from matloom.lang.params import edit_program, listing

    before = checked(text, session)
    listed = (
        session.cached("studio-listing", text, lambda: listing(before))
        if session is not None
        else None
    )
    converted = {k: tuple(v) if isinstance(v, list) else v for k, v in values.items()}
    try:
        edited, warnings = edit_program(before, converted, listed)
    except ValueError as err:
        raise ApiError(400, str(err)) from None
    new = program_text(text, before, edited, session)
    return {"text": new, "warnings": warnings, "text_sha": text_sha(new)}


def text_sha(text: str) -> str:
    """The hash ``/api/set`` and a maps request with ``values`` report for a program text
    (sha256 of its UTF-8, the first 16 hex digits), so the page compares two strings."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def layer_op(text: str, op: str, index: int, to: int | None) -> dict[str, Any]:
    """``/api/layers``: move layer ``index`` to position ``to``, duplicate it (the copy goes
    above it) or delete it; 1-based, bottom first. The layer's comments go with it."""
    program = checked(text)
    layers = list(program.layers)
    count = len(layers)
    if op not in LAYER_OPS:
        raise ApiError(400, f"unknown layer operation {op!r}; choose {', '.join(LAYER_OPS)}")
    if not 1 <= index <= count:
        raise ApiError(400, f"layer {index} does not exist (the program has {count})")
    layer = layers[index - 1]
    if op == "move":
        if to is None or not 1 <= to <= count:
            raise ApiError(400, f"'to' must be a layer position in [1, {count}]")
        layers.insert(to - 1, layers.pop(index - 1))
    elif op == "duplicate":
        layers.insert(index, layer)
    else:
        if count == 1:
            raise ApiError(422, "a material needs at least one layer; this is its last")
        layers.pop(index - 1)
    return {"text": format_program(replace(program, layers=tuple(layers)), comments=True)}
