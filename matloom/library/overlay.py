"""Overlays: condition layers ("mossy", "rusty", "wet" ...) kept as data and composed onto an
entry at the AST level.

An overlay is a ``.mat`` file in ``matloom/library/overlays/`` with a front matter (see
docs/library.md) and a complete program, so ``matloom check`` and ``matloom preview`` work on it.
Its **first layer stands in for the host material** and is dropped when composing; the other
layers, and the Defines they use, are appended on top of the entry's layers. Composition
(:func:`compose`):

* binds the overlay's ``host`` colour Defines to the entry's main colour slot (so "worn" can
  lighten whatever the entry's colour is);
* sets the overlay's slots (``cover`` from the amount words, its colour from the prompt);
* rescales noise frequencies and heights from the overlay's View to the entry's, so the overlay
  keeps the same number of features across the material (times a size factor: "small cracks");
* renames Defines that clash with the entry's names and re-derives seeds for the user seed.
"""

from __future__ import annotations

import functools
from collections.abc import Collection
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TypeGuard

from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.diagnostics import ProgramError
from matloom.lang.rewrite import map_expr
from matloom.library.entry import FrontMatterReader, LibraryError, split_front_matter
from matloom.library.relief import height_expr, relief_of
from matloom.vocab import FUNCTIONS

OVERLAY_DIR = Path(__file__).resolve().parent / "overlays"
_FREQ_PARAMS = ("base_freq", "base_freq_x", "base_freq_y")
#: the Define a composed overlay's relief reads the host's height from (``host_height2``, ...
#: when several overlays are composed)
HOST_HEIGHT = "host_height"
#: Lengths an overlay's instanced motifs are drawn with (``Tile`` cells, shape radii, centres,
#: feathers and strokes): scaled like the noise periods, so scratches drawn as shapes keep
#: their size relative to the host's features, and their count per View (a tileable repeat).
_LENGTH_PARAMS = frozenset(
    {"width", "height", "rx", "ry", "cx", "cy", "feather", "radius", "x", "y", "w", "h"}
)


@dataclass(frozen=True)
class Overlay:
    """One overlay: what requests it, its slots and its program text."""

    name: str
    path: Path
    description: str
    triggers: tuple[str, ...]
    program: str
    colours: tuple[str, ...] = ()
    host: str | None = None
    cover: str | None = None
    weak: tuple[str, ...] = ()
    scalars: dict[str, str] = field(default_factory=dict)
    #: the Define bound to the host's relief (0 low .. 1 high, :mod:`matloom.library.relief`)
    relief: str | None = None
    #: the Define bound to the host's composite height, in the overlay's height units (its
    #: stand-in value where the host has no height line): what lies on the surface (drops of
    #: water) raises its height from it, ``.height(host_surface + drop * 0.004)``
    surface: str | None = None

    @property
    def streaks(self) -> str | None:
        """The scalar that turns its patches into streaks running down (0 or 1), if any."""
        return next((k for k, kind in self.scalars.items() if kind == "streaks"), None)

    @property
    def ring(self) -> str | None:
        """The scalar that draws its marks as rings, their rims only (0 or 1), if any."""
        return next((k for k, kind in self.scalars.items() if kind == "ring"), None)

    @property
    def accent_slot(self) -> str | None:
        """The colour slot of what the overlay adds: its first that is not the host's."""
        return next((c for c in self.colours if c != self.host), None)

    @functools.cached_property
    def ast(self) -> A.Program:
        """The parsed program (cached)."""
        return parse(self.program)


def load_overlay(path: Path | str) -> Overlay:
    """Read and validate one overlay file (errors name the file and the key)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise LibraryError(f"{path}: cannot read: {exc}") from None
    data, program, _ = split_front_matter(text, path)
    r = FrontMatterReader(data, path)
    scalars = r.table("scalars")
    cover = next((k for k, kind in scalars.items() if kind == "cover"), None)
    host = r.get("host", None, required=False)
    if host is not None and not (isinstance(host, str) and host):
        raise r.fail("host", f"expected the name of a colour slot, got {host!r}")
    relief = r.get("relief", None, required=False)
    if relief is not None and not (isinstance(relief, str) and relief):
        raise r.fail("relief", f"expected the name of a Define, got {relief!r}")
    surface = r.get("surface", None, required=False)
    if surface is not None and not (isinstance(surface, str) and surface):
        raise r.fail("surface", f"expected the name of a Define, got {surface!r}")
    overlay = Overlay(
        name=path.stem,
        path=path,
        description=r.text("description"),
        triggers=tuple(t.lower() for t in r.words("triggers", required=True)),
        program=program,
        colours=r.words("colours"),
        host=host,
        cover=cover,
        weak=tuple(t.lower() for t in r.words("weak")),
        scalars=dict(scalars),
        relief=relief,
        surface=surface,
    )
    r.finish()
    if host is not None and host not in overlay.colours:
        raise r.fail("host", f"{host!r} is not one of 'colours'")
    return overlay


# ----------------------------------------------------------------------------- AST helpers
def define_value(program: A.Program, name: str, value: float | A.Node) -> A.Program:
    """``program`` with Define ``name`` set to ``value`` (unchanged when there is no such Define)."""
    node = value if not isinstance(value, (int, float)) else _num(value)
    defines = tuple(replace(d, expr=node) if d.name == name else d for d in program.defines)
    return replace(program, defines=defines)


def _num(value: float) -> A.Node:
    v: int | float = int(value) if float(value).is_integer() else round(float(value), 6)
    return A.Num(abs(v)) if v >= 0 else A.Neg(A.Num(-v))


def constant(program: A.Program, name: str) -> float | None:
    """The value of Define ``name`` when it is a plain number, else None."""
    d = program.define(name)
    if d is None:
        return None
    if isinstance(d.expr, A.Num):
        return float(d.expr.value)
    if isinstance(d.expr, A.Neg) and isinstance(d.expr.operand, A.Num):
        return -float(d.expr.operand.value)
    return None


def prune_defines(program: A.Program) -> A.Program:
    """``program`` without the Defines that no layer uses, directly or through other Defines
    (what the checker's W001 reports; a parameterised Define is used by a call of its name):
    adaptation can leave some ("scagliola" sets a derived
    colour to a constant, so the luminance its expression read is used no more)."""
    by_name = {d.name: d for d in program.defines}
    used: set[str] = set()
    stack = [e for owner, e in A.program_expressions(program) if owner[0] == "layer"]
    while stack:
        for n in A.walk(stack.pop()):
            # a Ref, or a Call of a parameterised Define ("thread(d)", language 3)
            name = n.name if isinstance(n, A.Ref) else n.func if isinstance(n, A.Call) else None
            if name is not None and name in by_name and name not in used:
                used.add(name)
                stack.append(by_name[name].expr)
    if len(used) == len(program.defines):
        return program
    return replace(program, defines=tuple(d for d in program.defines if d.name in used))


def rename_refs(node: A.Node, names: dict[str, str]) -> A.Node:
    """``node`` with every Ref renamed through ``names``."""

    def fn(n: A.Node) -> A.Node:
        if isinstance(n, A.Ref) and n.name in names:
            return replace(n, name=names[n.name])
        return n

    return map_expr(node, fn)


def is_noise_call(node: A.Node) -> TypeGuard[A.Call]:
    """Is ``node`` a call with noise frequencies (a ``base_freq`` parameter)? The one place the
    library reads a function's parameters to size an overlay's features (and so keep its noise
    periods whole numbers across the View)."""
    if not isinstance(node, A.Call) or node.func not in FUNCTIONS:
        return False
    return any(p.name == "base_freq" for p in FUNCTIONS[node.func].params)


def _drawn(node: A.Node) -> TypeGuard[A.Call]:
    """Is ``node`` a ``Tile`` or a shape (lengths, not frequencies, size it)?"""
    return (
        isinstance(node, A.Call)
        and node.func in FUNCTIONS
        and (node.func == "Tile" or FUNCTIONS[node.func].family == "shape")
    )


def scale_features(node: A.Node, factor: float) -> A.Node:
    """Multiply the frequency parameters of every noise call in ``node`` by ``factor`` (and
    divide the number lengths of every ``Tile`` and shape by it)."""

    def fn(n: A.Node) -> A.Node:
        if _drawn(n):
            return replace(
                n,
                args=tuple(
                    replace(a, value=_num(a.value.value / factor))
                    if a.param in _LENGTH_PARAMS and isinstance(a.value, A.Num)
                    else a
                    for a in n.args
                ),
            )
        if not is_noise_call(n):
            return n
        args = []
        seen = set()
        for a in n.args:
            if a.param in _FREQ_PARAMS and isinstance(a.value, A.Num):
                a = replace(a, value=_num(a.value.value * factor))
            seen.add(a.param)
            args.append(a)
        if not seen & set(_FREQ_PARAMS):
            args.append(A.Arg("base_freq", _num(factor)))
        return replace(n, args=tuple(args))

    return map_expr(node, fn)


def _scaled_height(layer: A.Layer, factor: float) -> A.Layer:
    if abs(factor - 1) < 1e-9:
        return layer
    chans = tuple(
        replace(c, args=tuple(A.BinOp("*", a, _num(factor)) for a in c.args))
        if c.name == "height"
        else c
        for c in layer.channels
    )
    return replace(layer, channels=chans)


def view_width(program: A.Program) -> float:
    x1, _, x2, _ = program.view_tuple
    return abs(x2 - x1) or 1.0


def fresh_name(stem: str, taken: Collection[str]) -> str:
    """``stem``, or ``stem2``, ``stem3`` ... : the first of them not in ``taken``."""
    name, k = stem, 2
    while name in taken:
        name, k = f"{stem}{k}", k + 1
    return name


def compose(
    host: A.Program,
    overlay: Overlay,
    *,
    main_colour: str | None,
    cover: float | None = None,
    colour: tuple[int, int, int] | None = None,
    reseed: object = None,
    scale: float = 1.0,
    streaks: bool = False,
    follow_relief: bool = True,
    ring: bool = False,
) -> A.Program:
    """``host`` with ``overlay``'s layers (all but its first) and their Defines on top.

    ``main_colour`` is the entry's main colour slot (bound to the overlay's ``host`` colour);
    ``cover`` and ``colour`` set the overlay's slots; ``reseed`` (a callable taking and returning
    a program) re-derives the overlay's seeds; ``scale`` sizes the overlay's features ("small
    cracks" 0.65: smaller cells with thinner lines, the same cover); ``streaks``: its patches
    run down the surface as streaks (an overlay with a ``streaks`` scalar). The overlay's
    ``relief`` Define is bound to the host's relief (:func:`~matloom.library.relief.relief_of`)
    when the host has one, so what settles in hollows finds the host's joints and pits; its
    ``surface`` Define to the host's height, so what lies on the surface (drops) sits on it.
    ``ring``: its marks are rings, their rims only (an overlay with a ``ring`` scalar: "coffee
    rings"). ``follow_relief=False`` leaves the ``relief`` Define its stand-in value (a request that
    places the overlay on the relief's high or low parts itself).
    """
    ov = overlay.ast
    if cover is not None and overlay.cover:
        ov = define_value(ov, overlay.cover, cover)
    if streaks and overlay.streaks:
        ov = define_value(ov, overlay.streaks, 1)
    if ring and overlay.ring:
        ov = define_value(ov, overlay.ring, 1)
    if colour is not None and overlay.colours:
        slot = overlay.accent_slot
        if slot is not None:
            for ch, v in zip("rgb", colour, strict=True):
                ov = define_value(ov, f"{slot}_{ch}", v)
    names: dict[str, str] = {}
    drop: set[str] = set()
    if overlay.host and main_colour:
        for ch in "rgb":
            names[f"{overlay.host}_{ch}"] = f"{main_colour}_{ch}"
            drop.add(f"{overlay.host}_{ch}")
    taken = {d.name for d in host.defines}
    for d in ov.defines:
        if d.name in drop:
            continue
        new = fresh_name(d.name, taken)
        if new != d.name:
            names[d.name] = new
        taken.add(new)
    factor = view_width(ov) / view_width(host)
    defines = [
        replace(
            d,
            name=names.get(d.name, d.name),
            expr=scale_features(rename_refs(d.expr, names), factor / scale),
        )
        for d in ov.defines
        if d.name not in drop
    ]
    relief = (
        overlay.relief if follow_relief and overlay.relief and ov.define(overlay.relief) else None
    )
    surface = overlay.surface if overlay.surface and ov.define(overlay.surface) else None
    if relief or surface:
        defines = _bind_relief(
            host,
            defines,
            names.get(relief, relief) if relief else None,
            taken,
            surface=names.get(surface, surface) if surface else None,
            factor=factor,
        )
    layers = []
    for layer in ov.layers[1:]:
        alpha = rename_refs(layer.alpha, names) if layer.alpha is not None else None
        chans = tuple(
            replace(c, args=tuple(rename_refs(a, names) for a in c.args)) for c in layer.channels
        )
        layers.append(_scaled_height(replace(layer, alpha=alpha, channels=chans), 1 / factor))
    added = replace(ov, view=host.view, defines=tuple(defines), layers=tuple(layers))
    if callable(reseed):
        added = reseed(added)
    return replace(host, defines=host.defines + added.defines, layers=host.layers + added.layers)


def _bind_relief(
    host: A.Program,
    defines: list[A.Define],
    name: str | None,
    taken: set[str],
    *,
    surface: str | None = None,
    factor: float = 1.0,
) -> list[A.Define]:
    """``defines`` with Define ``name`` bound to the host's relief rank and Define ``surface``
    to its height times ``factor`` (the overlay's View width over the host's: the composed
    layers' heights are scaled by its inverse), both read from a new Define of the host's
    height placed before the first of them (the host's own names: bound after the renames).
    A relief too flat to follow leaves ``name`` as it is but still gives ``surface``."""
    height = fresh_name(HOST_HEIGHT, taken)
    found = relief_of(host, height) if name else None
    expr = found[0] if found is not None else height_expr(host) if surface else None
    if expr is None:
        return defines
    bound: dict[str, A.Node] = {}
    if found is not None and name:
        bound[name] = found[1]
    if surface:
        bound[surface] = A.BinOp("*", A.Ref(height), _num(factor))
    if not bound:
        return defines
    taken.add(height)
    out: list[A.Define] = []
    for d in defines:
        if d.name in bound:
            if height not in {o.name for o in out}:
                out.append(replace(d, name=height, expr=expr, comments=()))
            out.append(replace(d, expr=bound[d.name]))
        else:
            out.append(d)
    return out


def check_overlay(overlay: Overlay) -> None:
    """Raise :class:`LibraryError` when the overlay's program does not fit the rules."""
    try:
        program = overlay.ast
    except ProgramError as exc:
        raise LibraryError(f"{overlay.path}: {exc}") from None
    if len(program.layers) < 2:
        raise LibraryError(
            f"{overlay.path}: needs a stand-in host layer and at least one overlay layer"
        )
    for slot in overlay.colours:
        for ch in "rgb":
            if program.define(f"{slot}_{ch}") is None:
                raise LibraryError(
                    f"{overlay.path}: colour slot {slot!r} has no Define {slot}_{ch}"
                )
    if overlay.cover and program.define(overlay.cover) is None:
        raise LibraryError(f"{overlay.path}: scalar {overlay.cover!r} has no Define")
    for name in (overlay.streaks, overlay.ring, overlay.relief, overlay.surface):
        if name and program.define(name) is None:
            raise LibraryError(f"{overlay.path}: {name!r} has no Define")
