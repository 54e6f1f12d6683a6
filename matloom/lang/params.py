"""Exposed parameters of a program: what ``matloom params`` lists and ``matloom set`` changes.

A parameter is a number (or an sRGB colour) written as a literal where an edit is expected:

* ``define:NAME``: a Define whose value is a constant written without references
  (``Define(grout, 0.02)``); three such Defines ``C_r``, ``C_g``, ``C_b`` (the library's colour
  slots) are one colour parameter ``define:C`` (each component stays settable on its own as
  ``define:C_r``);
* ``layer:N.CHANNEL``: a layer channel written as a literal (N is 1-based, the bottom layer
  first; ``layer:N.alpha`` for a literal coverage); a colour channel is one colour parameter
  when its three components are literals (``.emissive``'s strength is ``layer:N.emissive.strength``);
* ``define:NAME.CALL.PARAM`` / ``layer:N.CHANNEL.CALL.PARAM``: a literal static parameter of a
  call inside that Define or channel (``define:tiles.Bricks.mortar``); the second call of the same
  name in one owner is ``CALL#2``.

Kinds, ranges and units come from the registry (:class:`~matloom.vocab.spec.ParamSpec`,
:class:`~matloom.vocab.spec.ChannelSpec`); a constant Define written as a whole static parameter
(``Bricks(mortar=grout)``) or a whole channel argument takes that parameter's kind and range.
``affects`` is the dependency analysis (:func:`matloom.lang.deps.channel_dependencies`).
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterator, Mapping
from dataclasses import asdict, dataclass, replace
from typing import Any

from matloom.lang import ast as A
from matloom.lang.deps import BLENDED, COVERAGE, DERIVED, MAXED, channel_dependencies
from matloom.lang.diagnostics import ProgramError
from matloom.lang.static import static_number
from matloom.vocab import CHANNELS, FUNCTIONS, Kind, ParamSpec
from matloom.vocab.spec import ChannelSpec

KINDS: tuple[str, ...] = ("colour", "scalar", "frequency", "size", "count", "angle", "seed")
"""Every parameter kind, in the order tables list them."""

Colour = tuple[float, float, float]
Value = float | int | Colour

#: Static parameters measured in coordinate units (lengths and positions).
_SIZES = frozenset(
    {"brick_width", "brick_height", "mortar", "feather", "width", "height", "radius", "rx", "ry"}
    | {"dx", "dy", "x", "y", "cx", "cy", "start_x", "start_y", "c1x", "c1y", "c2x", "c2y"}
    | {"transition_width"}
)
#: Friendlier words for some static parameter names.
_PARAM_WORDS = {
    "base_freq": "frequency",
    "base_freq_x": "frequency x",
    "base_freq_y": "frequency y",
    "mortar": "mortar width",
    "brick_width": "brick width",
    "brick_height": "brick height",
    "warp_width": "thread width",
    "degrees": "angle",
}
#: Labels of channels whose name is not plain words.
_CHANNEL_WORDS = {"basecolor": "base colour", "ior": "index of refraction", "alpha": "coverage"}
_UNITS = {
    "frequency": "cycles/unit",
    "angle": "degrees",
    "colour": "sRGB 0-255",
    "size": "units",
}
_RGB = ("r", "g", "b")


@dataclass(frozen=True)
class Param:
    """One exposed parameter (see the module docstring for the addresses).

    ``value`` is a number or an (r, g, b) tuple (sRGB 0..255); ``low``/``high`` the registry
    range (None: unbounded); ``unit`` ``"units"`` (coordinate units) for sizes, ``"cycles/unit"``,
    ``"degrees"``, ``"sRGB 0-255"`` or None; ``metres`` a size's value in metres where the View
    gives ``unit_m``; ``affects`` the sorted output maps that depend on it.
    """

    address: str
    value: Value
    kind: str
    low: float | None
    high: float | None
    unit: str | None
    label: str
    affects: tuple[str, ...]
    line: int
    col: int
    metres: float | None = None

    def to_json(self) -> dict[str, Any]:
        out = asdict(self)
        out["value"] = list(self.value) if isinstance(self.value, tuple) else self.value
        out["affects"] = list(self.affects)
        return out


@dataclass(frozen=True)
class _Site:
    """Where a parameter's literal(s) live and how to replace them."""

    where: str  # "define", "channel", "static"
    define: tuple[str, ...] = ()  # Define names (three for a colour slot)
    layer: int = -1  # 0-based
    channel: str = ""
    args: tuple[int, ...] = ()  # channel argument indices
    call_start: int = -1  # static: the call's span start
    func: str = ""
    param: str = ""
    integer: bool = False  # count / seed: whole numbers only
    lo_open: bool = False
    hi_open: bool = False
    nonzero: bool = False


# ---------------------------------------------------------------------------- text helpers
def words(name: str) -> str:
    """Label words of an identifier: ``groutWidth`` -> ``grout width``, ``tile_r`` -> ``tile r``."""
    spaced = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", " ", name).replace("_", " ")
    return " ".join(spaced.lower().split())


def _literal(node: A.Node | None) -> float | int | None:
    """The number of a literal (``3``, ``-0.5``), else None."""
    if isinstance(node, A.Num) and not isinstance(node.value, bool):
        return node.value
    if isinstance(node, A.Neg) and isinstance(node.operand, A.Num):
        return -node.operand.value
    return None


def _constant(node: A.Node) -> float | int | None:
    """Value of a Define's expression that is a constant written without references."""
    for n in A.walk(node):
        if isinstance(n, A.Ref) or (isinstance(n, A.Call) and n.func in ("X", "Y")):
            return None
    v = static_number(node)
    if v is None or isinstance(v, bool) or not math.isfinite(v):
        return None
    return v


def _keys(node: A.Node) -> frozenset[str]:
    """Dependency keys (``line:col``) of the literals inside ``node``."""
    return frozenset(f"{n.span.line}:{n.span.col}" for n in A.walk(node) if isinstance(n, A.Num))


def _pos(node: A.Node) -> tuple[int, int]:
    return node.span.line, node.span.col


# ---------------------------------------------------------------------------- kinds
def _param_kind(p: ParamSpec) -> str:
    if p.is_seed:
        return "seed"
    if p.is_frequency:
        return "frequency"
    if p.kind is Kind.INT:
        return "count"
    if p.name in ("degrees", "rotate"):
        return "angle"
    if p.name in _SIZES:
        return "size"
    return "scalar"


def _channel_kind(c: ChannelSpec, arg: int) -> tuple[str, float | None, float | None]:
    if arg in c.colour_args:
        return "colour", 0.0, 255.0
    if c.name == "anisotropy_angle":
        return "angle", None, None
    if c.name == "height":
        return "size", None, None
    if c.colour_args:  # emissive strength
        return "scalar", 0.0, None
    return "scalar", c.clamp_lo, c.clamp_hi


def _is_static(p: ParamSpec) -> bool:
    return p.kind in (Kind.FLOAT, Kind.INT)


# ---------------------------------------------------------------------------- listing
class _Lister:
    def __init__(self, program: A.Program, labels: Mapping[str, str]) -> None:
        self.program = program
        self.labels = labels
        deps = channel_dependencies(program)
        self.deps = {out: frozenset(r.key for r in refs) for out, refs in deps.items()}
        self.sites: dict[str, _Site] = {}
        self.params: list[Param] = []
        self.order: list[tuple[int, ...]] = []  # sort keys: a call's parameters in its order
        self.uses = _define_uses(program)
        self.reach = _reach(program)

    def affects(self, keys: frozenset[str]) -> tuple[str, ...]:
        return tuple(sorted(out for out, ks in self.deps.items() if ks & keys))

    def add(
        self, address: str, value: Value, kind: str, lo: float | None, hi: float | None,
        label: str, keys: frozenset[str], pos: tuple[int, int], site: _Site,
        affects: tuple[str, ...] | None = None, order: tuple[int, ...] = (),
    ) -> None:  # fmt: skip
        unit = _UNITS.get(kind)
        unit_m = self.program.unit_m
        metres = None
        if kind == "size" and unit_m is not None and not isinstance(value, tuple):
            metres = float(value) * unit_m
        label = self.labels.get(address, label)
        if affects is None:
            affects = self.affects(keys)
        p = Param(address, value, kind, lo, hi, unit, label, affects, *pos, metres)
        self.params.append(p)
        self.order.append(order or pos)
        self.sites[address] = site

    def run(self) -> None:
        self.defines()
        for i, layer in enumerate(self.program.layers):
            self.layer(i, layer)

    def defines(self) -> None:
        consts = {d.name: d for d in self.program.defines if _constant(d.expr) is not None}
        slots = _colour_slots(consts, self.program)
        grouped = {f"{s}_{c}" for s in slots for c in _RGB}
        for d in self.program.defines:
            if d.name in consts and d.name not in grouped:
                self.define(d)
            elif d.name in consts and d.name.endswith("_r") and d.name[:-2] in slots:
                self.colour_slot(d.name[:-2], [consts[f"{d.name[:-2]}_{c}"] for c in _RGB])
            self.calls(f"define:{d.name}", words(d.name), d.expr)

    def define(self, d: A.Define) -> None:
        value = _constant(d.expr)
        assert value is not None
        kind, lo, hi, site = "scalar", None, None, _Site("define", define=(d.name,))
        use = self.uses.get(d.name)
        if isinstance(use, ParamSpec):
            kind, lo, hi = _param_kind(use), use.lo, use.hi
            site = replace(site, integer=kind in ("count", "seed"), lo_open=use.lo_open)
            site = replace(site, hi_open=use.hi_open, nonzero=use.nonzero)
        elif isinstance(use, tuple):
            kind, lo, hi = _channel_kind(*use)
        keys = _keys(d.expr)
        self.add(f"define:{d.name}", value, kind, lo, hi, words(d.name), keys, _pos(d), site)

    def colour_slot(self, slot: str, ds: list[A.Define]) -> None:
        value = tuple(float(_constant(d.expr)) for d in ds)  # type: ignore[arg-type]
        keys = frozenset().union(*(_keys(d.expr) for d in ds))
        site = _Site("define", define=tuple(d.name for d in ds))
        label = f"{words(slot)} colour"
        self.add(f"define:{slot}", value, "colour", 0.0, 255.0, label, keys, _pos(ds[0]), site)  # type: ignore[arg-type]

    def layer(self, i: int, layer: A.Layer) -> None:
        owner = f"layer {i + 1}"
        if isinstance(layer.alpha, A.Ref):
            owner = words(layer.alpha.name)
        if layer.alpha is not None:
            self.channel(i, owner, "alpha", (layer.alpha,))
        for ch in layer.channels:
            self.channel(i, owner, ch.name, ch.args)

    def channel(self, i: int, owner: str, name: str, args: tuple[A.Node, ...]) -> None:
        spec = CHANNELS[name]
        base = f"layer:{i + 1}.{name}"
        label = _CHANNEL_WORDS.get(name, words(name))
        label = f"{owner} {label}" if i > 0 or not owner.startswith("layer") else label
        nums = [_literal(a) for a in args]
        colour = spec.colour_args[:3] if spec.colour_args else ()
        if colour and all(nums[k] is not None for k in colour):
            value = tuple(float(nums[k]) for k in colour)  # type: ignore[arg-type]
            keys = frozenset().union(*(_keys(args[k]) for k in colour))
            site = _Site("channel", layer=i, channel=name, args=tuple(colour))
            self.add(base, value, "colour", 0.0, 255.0, label, keys, _pos(args[0]), site)  # type: ignore[arg-type]
        for k, a in enumerate(args):
            if k in colour:
                continue
            v = nums[k]
            if v is not None:
                kind, lo, hi = _channel_kind(spec, k)
                addr = base if len(args) == 1 else f"{base}.{spec.arg_names[k]}"
                lab = label if len(args) == 1 else f"{label} {spec.arg_names[k]}"
                site = _Site("channel", layer=i, channel=name, args=(k,))
                self.add(addr, v, kind, lo, hi, lab, _keys(a), _pos(a), site)
        for a in args:
            self.calls(base, label, a)

    def calls(self, base: str, owner: str, expr: A.Node) -> None:
        """Literal static parameters of the calls inside ``expr``; a pattern's (Bricks, Weave)
        unwritten numeric parameters too, at their defaults (setting one writes it)."""
        seen: dict[str, int] = {}
        for call in sorted(_calls(expr), key=lambda c: c.span.start):
            spec = FUNCTIONS.get(call.func)
            if spec is None or spec.name == "Constant":
                continue
            seen[call.func] = seen.get(call.func, 0) + 1
            n = seen[call.func]
            name = call.func if n == 1 else f"{call.func}#{n}"
            label = owner if n == 1 else f"{owner} ({call.func} {n})"
            for k, p in enumerate(spec.params):
                node = call.arg(p.name)
                v = _literal(node) if node is not None else _unwritten(call, spec.family, p)
                if not _is_static(p) or v is None:
                    continue
                kind = _param_kind(p)
                site = _Site(
                    "static", call_start=call.span.start, func=call.func, param=p.name,
                    integer=kind in ("count", "seed"), lo_open=p.lo_open, hi_open=p.hi_open,
                    nonzero=p.nonzero,
                )  # fmt: skip
                lab = _join(label, _PARAM_WORDS.get(p.name, words(p.name)))
                addr = f"{base}.{name}.{p.name}"
                if node is not None:
                    keys, pos, affects = _keys(node), _pos(node), None
                else:
                    keys, pos, affects = frozenset(), _pos(call), self.outputs(base)
                order = (*_pos(call), k)
                self.add(addr, v, kind, p.lo, p.hi, lab, keys, pos, site, affects, order)

    def outputs(self, base: str) -> tuple[str, ...]:
        """The maps that depend on an owner (``define:NAME`` or ``layer:N.CHANNEL``)."""
        kind, _, rest = base.partition(":")
        if kind == "define":
            return tuple(sorted(self.reach.get(rest, ())))
        return tuple(sorted(_expand({rest.split(".")[1]})))


def _join(owner: str, what: str) -> str:
    """``brick`` + ``brick width`` -> ``brick width`` (no repeated word)."""
    first, _, rest = what.partition(" ")
    return f"{owner} {rest}" if rest and owner.split()[-1] == first else f"{owner} {what}"


def _unwritten(call: A.Call, family: str, p: ParamSpec) -> float | int | None:
    """The default of a pattern's numeric parameter that ``call`` does not write (None for
    others, and for an axis override's base when an override is written)."""
    if family != "pattern" or p.is_seed or isinstance(p.default, bool):
        return None
    if not isinstance(p.default, int | float) or p.used_when is not None:
        return None
    if any(w.startswith(p.name + "_") for w in call.written()):
        return None
    return p.default


def _expand(channels: set[str]) -> set[str]:
    """Channel names -> output maps (coverage enters every blended map, height its derived)."""
    out = set(channels)
    if COVERAGE in out:
        out |= set(BLENDED) | set(MAXED)
    out |= {d for d, src in DERIVED.items() if src in out}
    return out


def _reach(program: A.Program) -> dict[str, set[str]]:
    """Define name -> the output maps that use it (directly or through other Defines)."""
    refs: dict[str, set[str]] = {}
    for d in program.defines:
        names = {n.name for n in A.walk(d.expr) if isinstance(n, A.Ref)}
        refs[d.name] = {d.name}.union(*(refs.get(r, {r}) for r in names))
    reach: dict[str, set[str]] = {d.name: set() for d in program.defines}
    for layer in program.layers:
        pairs = [(COVERAGE, layer.alpha)] if layer.alpha is not None else []
        pairs += [(ch.name, a) for ch in layer.channels for a in ch.args]
        for channel, expr in pairs:
            for n in A.walk(expr):
                if isinstance(n, A.Ref):
                    for name in refs.get(n.name, ()):
                        reach.setdefault(name, set()).add(channel)
    return {name: _expand(chs) for name, chs in reach.items()}


def _calls(node: A.Node) -> Iterator[A.Call]:
    return (n for n in A.walk(node) if isinstance(n, A.Call))


def _colour_slots(consts: Mapping[str, A.Define], program: A.Program) -> set[str]:
    """Colour slots: constant Defines ``C_r``, ``C_g``, ``C_b`` and no Define ``C`` (whose
    address ``define:C`` would be the slot's)."""
    return {
        n[:-2]
        for n in consts
        if n.endswith("_r")
        and all(f"{n[:-2]}_{c}" in consts for c in _RGB)
        and program.define(n[:-2]) is None
    }


_Use = ParamSpec | tuple[ChannelSpec, int]


def _define_uses(program: A.Program) -> dict[str, _Use]:
    """Define name -> the first static parameter or channel argument written as just its name."""
    uses: dict[str, _Use] = {}
    exprs = [d.expr for d in program.defines]
    for layer in program.layers:
        if layer.alpha is not None:
            if isinstance(layer.alpha, A.Ref):
                uses.setdefault(layer.alpha.name, (CHANNELS[COVERAGE], 0))
            exprs.append(layer.alpha)
        for ch in layer.channels:
            for k, a in enumerate(ch.args):
                if isinstance(a, A.Ref):
                    uses.setdefault(a.name, (CHANNELS[ch.name], k))
                exprs.append(a)
    for expr in exprs:
        for call in _calls(expr):
            spec = FUNCTIONS.get(call.func)
            for arg in call.args:
                p = spec.param(arg.param) if spec is not None else None
                if p is not None and _is_static(p) and isinstance(arg.value, A.Ref):
                    uses.setdefault(arg.value.name, p)
    return uses


def list_params(program: A.Program | str, labels: Mapping[str, str] | None = None) -> list[Param]:
    """Every exposed parameter of ``program`` (or of program text, which is parsed first), in
    source order. ``labels`` (address -> label) overrides the labels made from the names."""
    return _list(_program(program), labels or {})[0]


def _list(program: A.Program, labels: Mapping[str, str]) -> tuple[list[Param], dict[str, _Site]]:
    lister = _Lister(program, labels)
    lister.run()
    order = sorted(range(len(lister.params)), key=lambda k: lister.order[k])
    return [lister.params[k] for k in order], lister.sites


def _program(program: A.Program | str) -> A.Program:
    if isinstance(program, A.Program):
        return program
    from matloom.lang.api import analyse

    parsed, diags = analyse(program)
    if parsed is None or any(d.is_error for d in diags):
        raise ProgramError(diags, program)
    return parsed


# ---------------------------------------------------------------------------- setting
def set_params(program: A.Program | str, values: Mapping[str, Value]) -> tuple[str, list[str]]:
    """Set parameters by address; return the new program text (canonical, comments and names
    kept) and the warnings (one per value clamped into its range).

    Raises ValueError (a one-line message) for an unknown address, naming the closest ones, and
    for a value of the wrong kind (a colour for a number, a fraction for a count, ...).
    """
    from matloom.lang.printer import format_program

    prog, warnings = edit_program(_program(program), values)
    return format_program(prog, comments=True), warnings


Listing = tuple[list[Param], dict[str, "_Site"]]  # the parameters and where their literals are


def listing(program: A.Program) -> Listing:
    """The parameters of ``program`` and their sites, for :func:`edit_program` (a caller that
    edits one program many times, like the studio's sliders, keeps it)."""
    return _list(program, {})


def edit_program(
    program: A.Program, values: Mapping[str, Value], listed: Listing | None = None
) -> tuple[A.Program, list[str]]:
    """:func:`set_params` on a parsed program: the edited program (not yet printed or checked)
    and the warnings. ``listed``: the program's :func:`listing`, when the caller has it."""
    params, sites = listed if listed is not None else listing(program)
    by_address = {p.address: p for p in params}
    warnings: list[str] = []
    prog = program
    for address, value in values.items():
        param, site = _resolve(address, by_address, sites)
        prog = _apply(prog, site, _checked(param, site, value, warnings))
    return prog, warnings


def _resolve(
    address: str, by_address: Mapping[str, Param], sites: Mapping[str, _Site]
) -> tuple[Param, _Site]:
    if address in by_address:
        return by_address[address], sites[address]
    m = re.fullmatch(r"define:(\w+)_([rgb])", address)
    slot = by_address.get(f"define:{m.group(1)}") if m else None
    if m is not None and slot is not None and slot.kind == "colour":
        k = _RGB.index(m.group(2))
        name = sites[slot.address].define[k]
        value = slot.value[k]  # type: ignore[index]
        comp = replace(slot, address=address, value=value, kind="scalar", unit=None)
        return comp, _Site("define", define=(name,))
    close = difflib.get_close_matches(address, list(by_address), n=4, cutoff=0.5)
    if not close:
        close = [a for a in by_address if a.split(".")[0] == address.split(".")[0]][:4]
    hint = f"; close: {', '.join(close)}" if close else ""
    if not by_address:
        hint = "; the program has no parameters"
    raise ValueError(f"unknown parameter {address!r}{hint}")


def _checked(param: Param, site: _Site, value: object, warnings: list[str]) -> Value:
    """``value`` validated for ``param``: colours as 3 numbers, counts and seeds whole, clamped
    into the range with a warning."""
    if param.kind == "colour":
        if not (isinstance(value, tuple | list) and len(value) == 3):
            raise ValueError(f"{param.address} is a colour: give r,g,b (0-255) or #rrggbb")
        comps = [_number(param.address, v) for v in value]
        clamped = tuple(min(255.0, max(0.0, float(v))) for v in comps)
        if list(clamped) != [float(v) for v in comps]:
            warnings.append(
                f"{param.address}: ({', '.join(_fmt(v) for v in comps)}) is outside [0, 255]; "
                f"clamped to ({', '.join(_fmt(v) for v in clamped)})"
            )
        return clamped  # type: ignore[return-value]
    v = _number(param.address, value)
    if site.integer:
        if float(v) != int(v):
            raise ValueError(f"{param.address} is a {param.kind}: give a whole number, not {v}")
        v = int(v)
    lo, hi = param.low, param.high
    if (site.lo_open and lo is not None and v <= lo) or (
        site.hi_open and hi is not None and v >= hi
    ):
        raise ValueError(f"{param.address} must be {_range(param, site)}, got {_fmt(v)}")
    if site.nonzero and v == 0:
        raise ValueError(f"{param.address} must be non-zero")
    new = v
    if lo is not None and v < lo:
        new = int(lo) if site.integer else lo
    if hi is not None and v > hi:
        new = int(hi) if site.integer else hi
    if new != v:
        warnings.append(
            f"{param.address}: {_fmt(v)} is outside {_range(param, site)}; clamped to {_fmt(new)}"
        )
    return new


def _number(address: str, value: object) -> float | int:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{address} takes a finite number, got {value!r}")
    return value


def _fmt(v: float | int) -> str:
    return str(int(v)) if float(v).is_integer() else repr(float(v))


def _range(p: Param, site: _Site) -> str:
    lo = "-inf" if p.low is None else _fmt(p.low)
    hi = "inf" if p.high is None else _fmt(p.high)
    return f"{'(' if site.lo_open else '['}{lo}, {hi}{')' if site.hi_open else ']'}"


def _node(v: float | int) -> A.Node:
    if isinstance(v, float) and v.is_integer() and abs(v) < 2**53:
        v = int(v)
    return A.Neg(A.Num(-v)) if v < 0 else A.Num(v)


def _apply(prog: A.Program, site: _Site, value: Value) -> A.Program:
    vals = list(value) if isinstance(value, tuple) else [value]
    if site.where == "define":
        new = dict(zip(site.define, vals, strict=True))
        defines = tuple(
            replace(d, expr=_node(new[d.name])) if d.name in new else d for d in prog.defines
        )
        return replace(prog, defines=defines)
    if site.where == "channel":
        layers = list(prog.layers)
        layer = layers[site.layer]
        if site.channel == COVERAGE:  # the coverage is the Layer(...) argument
            layers[site.layer] = replace(layer, alpha=_node(vals[0]))
        else:
            chans = []
            for ch in layer.channels:
                if ch.name == site.channel:
                    args = list(ch.args)
                    for k, v in zip(site.args, vals, strict=True):
                        args[k] = _node(v)
                    ch = replace(ch, args=tuple(args))
                chans.append(ch)
            layers[site.layer] = replace(layer, channels=tuple(chans))
        return replace(prog, layers=tuple(layers))
    from matloom.lang.rewrite import map_program

    def fn(node: A.Node) -> A.Node:
        if isinstance(node, A.Call) and node.span.start == site.call_start:
            if node.func == site.func:
                new = {a.param: a for a in node.args}
                old = new.get(site.param)
                arg = A.Arg(site.param, _node(vals[0]))
                new[site.param] = replace(old, value=arg.value) if old is not None else arg
                order = FUNCTIONS[node.func].param_names
                args = sorted(new.values(), key=lambda a: order.index(a.param))
                return replace(node, args=tuple(args))
        return node

    return map_program(prog, fn)
