"""Offline edits: common requests mapped to parameter changes, driven by the parameter list.

A rule reads the request's words, picks parameters by their kind, label, address and the
channels they affect (:func:`matloom.lang.params.list_params`), and returns a :class:`Plan`:
the assignments, the View changes and the channels the edit means to change (the locality
check holds the edit to them). The rules, in the order they are tried:

* **tileable** ("make it tileable", "seamless"): ``View(..., tileable=True)``;
* **physical size** ("1 m wide", "make it 50 cm across"): ``unit_m`` so the View spans it;
* **joints** ("wider grout", "narrower mortar joints"): size parameters of mortar, grout, gaps;
* **overlay amounts** ("more rust", "less moss", "more wear", "less dirt"): the cover amount
  of a library overlay (or a parameter labelled with the condition);
* **roughness** ("rougher", "glossier", "matte", "shinier", "higher roughness");
* **colour** ("blue glaze", "darker grout", "make the tiles dark green"): a named colour from
  the library's colour table, or a tone word applied to the current colour, on the colour
  parameter whose label or address names the noun (the main colour when none does);
* **scale** ("bigger tiles", "smaller", "denser", "sparser"): size, frequency and count
  parameters (those naming the noun, or all of them).

A request no rule maps raises :class:`EditRefused`, listing the parameters that could be
changed: never a silent no-op. So does a rule whose parameters are already at their limit.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from importlib.resources import files
from typing import Any

from matloom.lang import ast as A
from matloom.lang.params import Param
from matloom.library.colour import RGB, apply_tone, clamp_rgb
from matloom.library.data import Words, words

Value = float | tuple[float, float, float]


class EditRefused(ValueError):
    """A request the offline rules cannot map (the message lists what could be changed)."""

    def __init__(self, request: str, reason: str, params: Sequence[Param] = ()) -> None:
        self.request = request
        self.reason = reason
        self.params = list(params)
        listed = ", ".join(f"{p.address} ({p.label or p.kind})" for p in self.params[:40])
        more = f" and {len(self.params) - 40} more" if len(self.params) > 40 else ""
        super().__init__(
            f"cannot edit {request!r} offline: {reason}"
            + (f"; parameters it could change: {listed}{more}" if listed else "")
        )


@dataclass(frozen=True)
class Plan:
    """What a rule decided: parameter assignments, View changes and intended channels."""

    rule: str
    note: str
    assignments: dict[str, Value] = field(default_factory=dict)
    view: dict[str, Any] = field(default_factory=dict)
    intended: tuple[str, ...] = ()

    def to_json(self) -> dict[str, Any]:
        return {
            "rule": self.rule,
            "note": self.note,
            "assignments": {k: _json_value(v) for k, v in self.assignments.items()},
            "view": dict(self.view),
            "intended": list(self.intended),
        }


def _json_value(v: Value) -> Any:
    return list(v) if isinstance(v, tuple) else v


# ---- words ---------------------------------------------------------------------------------

_W = tomllib.loads(files("matloom.author.edit").joinpath("words.toml").read_text("utf-8"))
_JOINT_WORDS = frozenset(_W["words"]["joint"])
_JOINT_PARAM_WORDS = tuple(_W["words"]["joint_params"])
_WIDER = frozenset(_W["words"]["wider"])
_NARROWER = frozenset(_W["words"]["narrower"])
_MORE = frozenset(_W["words"]["more"])
_LESS = frozenset(_W["words"]["less"])
#: condition word -> the stems of its overlay's names and labels
_CONDITIONS: dict[str, tuple[str, ...]] = {k: tuple(v) for k, v in _W["conditions"].items()}
_ROUGHER: dict[str, float] = dict(_W["rougher"])
_GLOSSIER: dict[str, float] = dict(_W["glossier"])
_HIGHER = frozenset(_W["words"]["higher"])
_LOWER = frozenset(_W["words"]["lower"])
#: comparative tone words -> (lightness, saturation) multipliers
_COMPARATIVE: dict[str, tuple[float, float]] = {
    k: (float(v[0]), float(v[1])) for k, v in _W["comparative"].items()
}
_BIGGER = frozenset(_W["words"]["bigger"])
_SMALLER = frozenset(_W["words"]["smaller"])
_DENSER = frozenset(_W["words"]["denser"])
_SPARSER = frozenset(_W["words"]["sparser"])
_SIZE_FACTOR = float(_W["factors"]["size"])
_JOINT_FACTOR = float(_W["factors"]["joint"])
_AMOUNT_STEP = float(_W["factors"]["amount_step"])
#: words that carry no noun
_FILLER = frozenset(_W["words"]["filler"])


def tokens(request: str) -> list[str]:
    """The request's words, lower case (hyphens and punctuation split words)."""
    return re.findall(r"[a-z0-9]+(?:\.[0-9]+)?", request.lower())


def _stem(word: str) -> str:
    """A plural's singular, roughly: ``tiles`` -> ``tile``, ``patches`` -> ``patch``."""
    if len(word) <= 3 or not word.endswith("s") or word.endswith("ss"):
        return word
    if word.endswith("ies"):
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "sses", "xes")):
        return word[:-2]
    return word[:-1]


def param_words(p: Param, program: A.Program | None = None) -> set[str]:
    """The words a parameter answers to: its label and address parts (camelCase split), and
    for a layer's parameter the names its layer's coverage and channel refer to."""
    text = f"{p.label} {p.address}"
    text = re.sub(r"([a-z])([A-Z])", r"\1 \2", text)
    out = {_stem(w) for w in re.findall(r"[a-z]+", text.lower())}
    m = re.match(r"layer:(\d+)", p.address)
    if m and program is not None:
        idx = int(m.group(1))
        layers = program.layers
        layer = layers[idx - 1] if 0 < idx <= len(layers) else None
        if idx == 1 and _jointed(program):
            out |= {"grout", "mortar", "joint", "gap"}
        if layer is not None and layer.alpha is not None:
            for n in A.walk(layer.alpha):
                if isinstance(n, A.Ref):
                    split = re.sub(r"([a-z])([A-Z])", r"\1 \2", n.name).lower()
                    out |= {_stem(w) for w in re.findall(r"[a-z]+", split)}
    return out


def _jointed(program: A.Program) -> bool:
    """Whether a layer above the first is masked by a pattern with joints (Bricks): the first
    layer then shows through the joints, as mortar or grout."""
    for layer in program.layers[1:]:
        if isinstance(layer.alpha, A.Ref):
            d = program.define(layer.alpha.name)
            if d is not None and any(
                isinstance(n, A.Call) and n.func == "Bricks" for n in A.walk(d.expr)
            ):
                return True
    return False


def _matching(
    params: Sequence[Param],
    nouns: Sequence[str],
    program: A.Program | None,
    w: Words,
    synonyms: bool = True,
) -> list[Param]:
    """The parameters whose words include a noun of the request (or its role's synonyms)."""
    wanted: set[str] = set()
    for n in nouns:
        wanted.add(_stem(n))
        role = w.roles.get(n)
        if role == "grout":
            wanted |= {"grout", "mortar", "joint", "gap"}
        if synonyms and n in ("glaze", "tile", "tiles"):
            wanted |= {"glaze", "tile"}
    return [p for p in params if param_words(p, program) & wanted]


# ---- values --------------------------------------------------------------------------------


def _clamp(p: Param, v: float) -> float:
    lo = p.low if p.low is not None else -float("inf")
    hi = p.high if p.high is not None else float("inf")
    v = min(hi, max(lo, v))
    if p.kind in ("count", "seed"):
        return float(round(v))
    return float(f"{v:.6g}")


def _scaled(p: Param, factor: float) -> float:
    v = float(p.value)  # type: ignore[arg-type]
    return _clamp(p, v * factor)


def _changed(p: Param, new: Value) -> bool:
    if isinstance(new, tuple):
        return tuple(round(c) for c in new) != tuple(round(c) for c in p.value)  # type: ignore[union-attr]
    return abs(float(new) - float(p.value)) > 1e-9  # type: ignore[arg-type]


def _affects(ps: Sequence[Param]) -> tuple[str, ...]:
    out: dict[str, None] = {}
    for p in ps:
        out.update(dict.fromkeys(p.affects))
    return tuple(out)


def _assign(
    request: str, rule: str, note: str, new: dict[Param, Value], intended: Sequence[str]
) -> Plan:
    moved = {p.address: v for p, v in new.items() if _changed(p, v)}
    if not moved:
        raise EditRefused(
            request,
            f"{rule}: {', '.join(p.address for p in new)} already at the limit of its range",
            list(new),
        )
    return Plan(rule=rule, note=note, assignments=moved, intended=tuple(intended))


# ---- the rules -----------------------------------------------------------------------------


@dataclass(frozen=True)
class Context:
    request: str
    words: list[str]
    params: list[Param]
    program: A.Program
    vocabulary: Words

    @property
    def nouns(self) -> list[str]:
        return [t for t in self.words if t not in _FILLER]


def _tileable(c: Context) -> Plan | None:
    if not ({"tileable", "seamless", "tiling", "tile-able"} & set(c.words)):
        return None
    if c.program.view is not None and c.program.view.tileable:
        raise EditRefused(c.request, "the program is tileable already", c.params)
    return Plan(
        "tileable", "View(..., tileable=True)", view={"tileable": True}, intended=("alpha",)
    )


_SIZE_RE = re.compile(
    r"(\d+(?:\.\d+)?)\s*(mm|millimet(?:er|re)s?|cm|centimet(?:er|re)s?|m|met(?:er|re)s?|"
    r"in|inch(?:es)?|ft|foot|feet)\b"
)


def _physical(c: Context) -> Plan | None:
    m = _SIZE_RE.search(c.request.lower())
    if not m or _JOINT_WORDS & set(c.words):
        return None
    metres = float(m.group(1)) * c.vocabulary.units[m.group(2)]
    if metres <= 0:
        raise EditRefused(c.request, "a physical size must be positive", c.params)
    view = c.program.view
    side = 1.0 if view is None else abs(view.x2 - view.x1)
    unit_m = float(f"{metres / side:.6g}")
    return Plan(
        "physical size",
        f"the View spans {metres:g} m: unit_m = {unit_m:g}",
        view={"unit_m": unit_m},
        intended=(),
    )


def _joints(c: Context) -> Plan | None:
    ws = set(c.words)
    sized = _SIZE_RE.search(c.request.lower()) is not None
    if not (_JOINT_WORDS & ws) or not ((_WIDER | _NARROWER) & ws or sized):
        return None
    if ws & {"darker", "lighter", "paler"}:
        return None
    factor = _JOINT_FACTOR if _WIDER & ws else 1 / _JOINT_FACTOR
    size = _SIZE_RE.search(c.request.lower())
    unit_m = c.program.view.unit_m if c.program.view is not None else None
    found = [
        p
        for p in c.params
        if p.kind == "size" and any(k in p.address.lower() for k in _JOINT_PARAM_WORDS)
    ]
    found += [
        p
        for p in c.params
        if p.kind == "size"
        and p not in found
        and ({"grout", "mortar", "joint"} & set(p.label.lower().split()))
    ]
    if not found:
        raise EditRefused(c.request, "no joint (mortar, grout, gap) width parameter", c.params)
    if size is not None and unit_m:  # "5 mm grout": the width itself, in the View's units
        metres = float(size.group(1)) * c.vocabulary.units[size.group(2)]
        width = metres / unit_m
        new = {p: _clamp(p, width) for p in found}
        note = f"joints {metres * 1000:g} mm wide ({width:.4g} units)"
        return _assign(c.request, "joints", note, new, _affects(found))
    new = {p: _scaled(p, factor) for p in found}
    word = "wider" if factor > 1 else "narrower"
    return _assign(c.request, "joints", f"joints {word} (x{factor:.3g})", new, _affects(found))


def _amounts(c: Context) -> Plan | None:
    ws = set(c.words)
    conds = [w for w in c.words if w in _CONDITIONS]
    if not conds:
        return None
    more = bool(ws & _MORE) or not (ws & _LESS)
    stems = _CONDITIONS[conds[0]]
    found = [
        p
        for p in c.params
        if p.kind == "scalar"
        and any(s in p.label.lower() for s in stems)
        and any(k in p.label.lower() for k in ("amount", "cover", "coverage"))
    ]
    if not found:
        found = _overlay_covers(c, stems)
    if not found:
        raise EditRefused(
            c.request,
            f"no {conds[0]} amount in this program (add the overlay by generating "
            f"'{conds[0]} ...' from the library)",
            c.params,
        )
    step = _AMOUNT_STEP if more else -_AMOUNT_STEP
    new = {p: _clamp(p, float(p.value) + step) for p in found}  # type: ignore[arg-type]
    return _assign(
        c.request,
        "amount",
        f"{'more' if more else 'less'} {conds[0]} ({step:+g})",
        new,
        _affects(found),
    )


def _overlay_covers(c: Context, stems: Sequence[str]) -> list[Param]:
    """Cover amounts of composed overlays: a scalar Define named ``cover*`` that a Define
    named for the condition (``rust``, ``moss``, ``wear``) depends on."""
    uses: dict[str, set[str]] = {}
    for d in c.program.defines:
        refs = {n.name for n in A.walk(d.expr) if isinstance(n, A.Ref)}
        closure = set(refs)
        for r in refs:
            closure |= uses.get(r, set())
        uses[d.name] = closure
    out = []
    for p in c.params:
        name = p.address.removeprefix("define:")
        if p.kind != "scalar" or "." in name or not name.startswith("cover"):
            continue
        if any(
            name in deps and any(d.lower().startswith(s) for s in stems) for d, deps in uses.items()
        ):
            out.append(p)
    return out


def _roughness(c: Context) -> Plan | None:
    ws = set(c.words)
    amount = next((v for k, v in _ROUGHER.items() if k in ws), None)
    gloss = next((v for k, v in _GLOSSIER.items() if k in ws), None)
    if "roughness" in ws or "rough" in ws:
        if ws & _HIGHER:
            amount = amount or 0.4
        elif ws & _LOWER:
            gloss = gloss or 0.5
        elif amount is None and gloss is None:
            amount = 0.4
    if amount is None and gloss is None:
        return None
    found = [
        p
        for p in c.params
        if p.kind == "scalar"
        and "roughness" in p.affects
        and set(p.affects) <= {"roughness"}
        and ("rough" in p.label.lower() or "rough" in p.address.lower())
    ]
    skip = (
        {"roughness", "rough", "finish", "surface"}
        | _HIGHER
        | _LOWER
        | set(_ROUGHER)
        | set(_GLOSSIER)
    )
    nouns = [n for n in c.nouns if n not in skip]
    targets = _matching(found, nouns, c.program, c.vocabulary) or found
    if not targets:
        raise EditRefused(c.request, "no roughness parameter", c.params)
    new: dict[Param, Value] = {}
    for p in targets:
        v = float(p.value)  # type: ignore[arg-type]
        hi = min(1.0, p.high if p.high is not None else 1.0)
        new[p] = _clamp(p, v + (hi - v) * amount) if amount is not None else _clamp(p, v * gloss)  # type: ignore[operator]
    note = "rougher" if amount is not None else "glossier"
    return _assign(c.request, "roughness", note, new, ("roughness",))


def _colour_in(c: Context) -> tuple[RGB | None, tuple[float, float] | None, str | None, set[int]]:
    """The named colour, the tone (multipliers) and its word, and the word indices used."""
    w = c.vocabulary
    ws = c.words
    used: set[int] = set()
    rgb: RGB | None = None
    for n in (3, 2):
        for i in range(len(ws) - n + 1):
            phrase = " ".join(ws[i : i + n])
            if rgb is None and phrase in w.phrases:
                rgb, used = w.phrases[phrase], set(range(i, i + n))
    if rgb is None:
        for i, t in enumerate(ws):
            if t in w.named and t not in _CONDITIONS and t not in ("sand", "stone", "slate"):
                rgb, used = w.named[t], {i}
                break
    tone: tuple[float, float] | None = None
    tone_word: str | None = None
    for i, t in enumerate(ws):
        if i in used:
            continue
        if t in _COMPARATIVE:
            tone, tone_word = _COMPARATIVE[t], t
            used.add(i)
            break
        if (
            t in w.tones
            and t not in ("medium",)
            and (rgb is not None or t in ("dark", "light", "pale", "bright"))
        ):
            tone, tone_word = w.tones[t], t
            used.add(i)
            break
    return rgb, tone, tone_word, used


def _colour(c: Context) -> Plan | None:
    rgb, tone, tone_word, used = _colour_in(c)
    if rgb is None and tone is None:
        return None
    colours = [p for p in c.params if p.kind == "colour"]
    if not colours:
        raise EditRefused(c.request, "no colour parameter", c.params)
    nouns = [t for i, t in enumerate(c.words) if i not in used and t not in _FILLER]
    targets = _matching(colours, nouns, c.program, c.vocabulary)
    named_elsewhere = _matching(c.params, nouns, c.program, c.vocabulary) if nouns else []
    if not targets and (named_elsewhere or any(n in c.vocabulary.roles for n in nouns)):
        raise EditRefused(c.request, f"no colour parameter named like {' '.join(nouns)!r}", colours)
    target = targets[0] if targets else _main_colour(colours, c.program)
    current: RGB = clamp_rgb(tuple(float(x) for x in target.value))  # type: ignore[arg-type,union-attr]
    new = rgb if rgb is not None else current
    if tone is not None and tone_word is not None:
        new = apply_tone(new, tone_word, tone)
    value = tuple(float(x) for x in new)
    return _assign(
        c.request,
        "colour",
        f"{target.address} -> {new}",
        {target: value},  # type: ignore[dict-item]
        ("basecolor",),
    )


def _layer_of(p: Param) -> int:
    m = re.match(r"layer:(\d+)", p.address)
    return int(m.group(1)) if m else 0


def _main_colour(colours: Sequence[Param], program: A.Program) -> Param:
    """The colour a request without a noun changes: a colour slot Define that is not a joint's,
    else the colour of the first layer masked by a named pattern, else the first colour."""
    joint = {"grout", "mortar", "joint", "gap"}
    plain = [p for p in colours if not (param_words(p, program) & joint)] or list(colours)
    plain.sort(key=lambda p: (not p.address.startswith("define:"), _layer_of(p)))
    for p in plain:
        if p.address.startswith("define:"):
            return p
    for p in plain:
        m = re.match(r"layer:(\d+)", p.address)
        if m and int(m.group(1)) <= len(program.layers):
            if isinstance(program.layers[int(m.group(1)) - 1].alpha, A.Ref):
                return p
    return plain[0]


def _scale(c: Context) -> Plan | None:
    ws = set(c.words)
    if ws & _BIGGER:
        size_f, freq_f = _SIZE_FACTOR, 1 / _SIZE_FACTOR
    elif ws & _SMALLER:
        size_f, freq_f = 1 / _SIZE_FACTOR, _SIZE_FACTOR
    elif ws & _DENSER:
        size_f, freq_f = 1 / _SIZE_FACTOR, _SIZE_FACTOR
    elif ws & _SPARSER:
        size_f, freq_f = _SIZE_FACTOR, 1 / _SIZE_FACTOR
    else:
        return None
    joint = ("mortar", "grout", "gap", "joint", "feather", "seam", "gutter")
    scalable = [
        p
        for p in c.params
        if p.kind in ("size", "frequency") and not any(k in p.address.lower() for k in joint)
    ]
    nouns = [
        t
        for t in c.words
        if t not in _FILLER
        and t not in (_BIGGER | _SMALLER | _DENSER | _SPARSER | {"feature", "features", "pattern"})
    ]
    targets = _matching(scalable, nouns, c.program, c.vocabulary, synonyms=False) or scalable
    if not targets:
        raise EditRefused(c.request, "no size or frequency parameter", c.params)
    new = {p: _scaled(p, size_f if p.kind == "size" else freq_f) for p in targets}
    return _assign(
        c.request,
        "scale",
        f"features x{size_f:.3g}",
        new,
        _affects(targets),
    )


#: The rules, in the order they are tried.
RULES: tuple[Callable[[Context], Plan | None], ...] = (
    _tileable,
    _physical,
    _joints,
    _amounts,
    _roughness,
    _colour,
    _scale,
)


def plan_edit(program: A.Program, params: Sequence[Param], request: str) -> Plan:
    """The offline plan for ``request`` on ``program`` (its parameter list ``params``).
    Raises :class:`EditRefused` when no rule maps the request."""
    c = Context(request, tokens(request), list(params), program, words())
    for rule in RULES:
        plan = rule(c)
        if plan is not None:
            return plan
    raise EditRefused(
        request,
        "no offline rule understands it (colours, rougher/glossier, bigger/smaller, "
        "denser/sparser, wider/narrower joints, more/less wear, dirt, rust or moss, tileable, "
        "a physical size); use --model for other edits",
        params,
    )
