"""Which parameters a request's nouns name: the words of a parameter are its label and address;
when no parameter's own words match, the names of the layer it feeds count too (a Define used
only in the ``paint`` layer's channels answers to "paint", and through the noun families of
``words.toml`` to "coating"; a layer's names are those its coverage reads positively), and the
first layer of a jointed program answers to "grout", "mortar", "joint".
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

from matloom.author.edit.lexicon import EditWords, split_words, stem
from matloom.lang import ast as A
from matloom.lang.params import Param
from matloom.vocab import FUNCTIONS

if TYPE_CHECKING:
    from matloom.author.edit.plan import Context

#: Address parts that are structure, not names.
_STRUCTURAL = frozenset({"define", "layer", "colour"})


def define_closure(program: A.Program) -> dict[str, frozenset[str]]:
    """Define name -> every Define it reads, directly or through others (itself included)."""
    out: dict[str, frozenset[str]] = {}
    for d in program.defines:
        names = {d.name}
        for n in A.walk(d.expr):
            if isinstance(n, A.Ref):
                names |= out.get(n.name, frozenset({n.name}))
        out[d.name] = frozenset(names)
    return out


def refs_of(node: A.Node | None, closure: dict[str, frozenset[str]]) -> frozenset[str]:
    """The Defines ``node`` reads, directly or through others."""
    if node is None:
        return frozenset()
    out: set[str] = set()
    for n in A.walk(node):
        if isinstance(n, A.Ref):
            out |= closure.get(n.name, frozenset({n.name}))
    return frozenset(out)


def jointed(program: A.Program, joint: frozenset[str] = frozenset()) -> bool:
    """Whether a layer above the first is masked by a pattern with joints (a Bricks, or a
    Define named for a joint such as ``jointdist`` or ``gap``): the first layer then shows
    through the joints, as mortar or grout."""
    closure = define_closure(program)
    for layer in program.layers[1:]:
        if isinstance(layer.alpha, A.Ref):
            d = program.define(layer.alpha.name)
            if d is not None and any(
                isinstance(n, A.Call) and n.func == "Bricks" for n in A.walk(d.expr)
            ):
                return True
            names = closure.get(layer.alpha.name, frozenset())
            if any(split_words(n) & joint for n in names if n != layer.alpha.name):
                return True
    return False


def layer_words(program: A.Program, index: int, ew: EditWords, deep: bool = False) -> set[str]:
    """The words of layer ``index`` (0-based): the names its coverage reads positively (with
    ``deep``, the names those read in turn: the ``paint`` layer draws the ``tulip``), and the
    joint words for the first layer of a jointed program."""
    layers = program.layers
    if not 0 <= index < len(layers):
        return set()
    out: set[str] = set()
    if index == 0 and jointed(program, ew.nouns["joint"]):
        out |= ew.nouns["joint"]
    names = set(mask_names(layers[index].alpha))
    if deep:
        closure = define_closure(program)
        names |= {r for n in list(names) for r in closure.get(n, ())}
    for name in names:
        out |= split_words(name)
    return out


def mask_names(node: A.Node | None) -> list[str]:
    """The names a coverage reads *positively*: ``rust * (1 - paint)`` is rust (where there
    is no paint), ``paint * tile`` paint and tile."""
    if node is None:
        return []
    if isinstance(node, A.Ref):
        return [node.name]
    if isinstance(node, A.BinOp):
        if node.op == "-":
            return mask_names(node.left)
        return mask_names(node.left) + mask_names(node.right)
    if isinstance(node, A.Neg):
        return []
    if isinstance(node, A.Call):
        return [n for a in node.args for n in mask_names(a.value)]
    return []


def _owner_names(p: Param) -> tuple[str, ...]:
    """The Define names a ``define:`` / ``colour:`` parameter lives in (a colour slot's three)."""
    m = re.match(r"(define|colour):(\w+)", p.address)
    if m is None:
        return ()
    name = m.group(2)
    if p.kind == "colour" and "." not in p.address:
        return (name, f"{name}_r", f"{name}_g", f"{name}_b")
    return (name,)


def layer_of(p: Param) -> int:
    """The 1-based layer of a ``layer:N...`` parameter, else 0."""
    m = re.match(r"layer:(\d+)", p.address)
    return int(m.group(1)) if m else 0


def param_layers(p: Param, program: A.Program) -> set[int]:
    """The layers (0-based) whose channels (not coverage) the parameter feeds."""
    n = layer_of(p)
    if n:
        return {n - 1}
    names = set(_owner_names(p))
    if not names:
        return set()
    closure = define_closure(program)
    out = set()
    for i, layer in enumerate(program.layers):
        if any(refs_of(a, closure) & names for ch in layer.channels for a in ch.args):
            out.add(i)
    return out


def own_words(p: Param) -> set[str]:
    """The words of a parameter's label and address (not the names of the functions in it:
    ``define:figure.Tile.width`` is no tile)."""
    parts = p.address.removesuffix(".base").split(".")
    address = ".".join(x for x in parts if x.split("#")[0] not in FUNCTIONS)
    label = p.label.replace(" base (", " (") if p.address.endswith(".base") else p.label
    label = re.sub(r"\((\w+) \d+\)", "", label)  # "(Tile 2)": the second call's tag
    return (split_words(label) | split_words(address)) - _STRUCTURAL


def param_words(p: Param, program: A.Program | None, ew: EditWords) -> set[str]:
    """The words a parameter answers to: its own, and the words of the layer whose channels
    it feeds when it feeds one layer only (see the module docstring)."""
    out = own_words(p)
    if program is not None:
        layers = param_layers(p, program)
        if len(layers) == 1:
            out |= layer_words(program, next(iter(layers)), ew, deep=True)
    return out


def wanted(nouns: Iterable[str], ew: EditWords, families: bool = True) -> set[str]:
    """The words the nouns stand for (with their families)."""
    out: set[str] = set()
    for n in nouns:
        out |= ew.family(n) if families else {stem(n)}
    return out


def overlaps(names: Iterable[str], want: Iterable[str]) -> bool:
    """Whether a word of ``names`` is a word of ``want``, or one is a part of the other: a
    name that begins a noun ("hex" of "hexagons"), a name of 5 letters or more inside one
    ("stitch" of "topstitching"), a noun of 4 letters or more inside a name ("knot" of
    ``knotcore``)."""
    names, want = set(names), set(want)
    if names & want:
        return True
    for w in names:
        for n in want:
            if len(w) >= 3 and n.startswith(w):
                return True
            if len(w) >= 5 and w in n:
                return True
            if len(n) >= 4 and n in w:
                return True
    return False


def matching(
    params: Sequence[Param],
    nouns: Sequence[str],
    program: A.Program | None,
    ew: EditWords,
    families: bool = True,
) -> list[Param]:
    """The parameters whose own words include a noun of the request (or its family's words);
    when none does, those whose layer's words do."""
    want = wanted(nouns, ew, families)
    if not want:
        return []
    direct = [p for p in params if overlaps(own_words(p), want)]
    if direct or program is None:
        return direct
    return [p for p in params if overlaps(param_words(p, program, ew), want)]


def coverage_params(
    params: Sequence[Param], nouns: Sequence[str], program: A.Program, ew: EditWords
) -> list[Param]:
    """The parameters that shape the coverage of the layers the nouns name (the size of the
    "stones" is what draws the stone layer's mask, not a noise in its colour; a noise the mask
    shares with a channel goes with it, so cells keep their tones)."""
    want = wanted(nouns, ew)
    closure = define_closure(program)
    names: set[str] = set()
    layers: set[int] = set()
    named = [
        i for i in range(1, len(program.layers)) if overlaps(layer_words(program, i, ew), want)
    ]
    # a layer whose coverage is the noun alone (``Layer(tile)``) before one it only limits
    # (``Layer(paint * tile)``)
    pure = [
        i
        for i in named
        if all(overlaps(split_words(n), want) for n in mask_names(program.layers[i].alpha))
    ]
    for i in pure or named:
        names |= refs_of(program.layers[i].alpha, closure)
        layers.add(i)
    out = []
    for p in params:
        m = re.match(r"define:(\w+)", p.address)
        if (m and m.group(1) in names) or (
            layer_of(p) - 1 in layers and p.address.startswith(f"layer:{layer_of(p)}.alpha")
        ):
            out.append(p)
    return out


def named_in_program(program: A.Program, nouns: Sequence[str], ew: EditWords) -> bool:
    """Whether a noun (or its family) names a Define or a layer of the program."""
    want = wanted(nouns, ew)
    if not want:
        return False
    if any(overlaps(split_words(d.name), want) for d in program.defines):
        return True
    return any(overlaps(layer_words(program, i, ew), want) for i in range(len(program.layers)))


def main_colour(colours: Sequence[Param], program: A.Program, ew: EditWords) -> Param:
    """The colour a request without a noun changes: a colour slot Define that is not a joint's,
    else the colour of the first layer masked by a named pattern, else the first colour."""
    joint = ew.nouns["joint"]
    plain = [p for p in colours if not (param_words(p, program, ew) & joint)] or list(colours)
    plain.sort(key=lambda p: (not p.address.startswith(("define:", "colour:")), layer_of(p)))
    for p in plain:
        if p.address.startswith(("define:", "colour:")):
            return p
    for p in plain:
        n = layer_of(p)
        if n and n <= len(program.layers) and isinstance(program.layers[n - 1].alpha, A.Ref):
            return p
    return plain[0]


def layer_colours(c: Context, colours: Sequence[Param], nouns: Sequence[str]) -> list[Param]:
    """The colours of the layers (above the first) whose coverage a noun names ("the slabs" is
    the layer ``Layer(slab)``): those that feed the layer's channels, not the joints'."""
    want = wanted(nouns, c.ew)
    if not want:
        return []
    layers = {
        i
        for i in range(1, len(c.program.layers))
        if overlaps(
            {w for n in mask_names(c.program.layers[i].alpha) for w in split_words(n)}, want
        )
    }
    if not layers:
        return []
    joint = c.ew.nouns["joint"]
    return [
        p
        for p in colours
        if param_layers(p, c.program) & layers
        and not overlaps(param_words(p, c.program, c.ew), joint)
    ]


#: Names a material's main part goes by ("the baseplate", "the body").
_MAIN_PARTS = ("base", "body", "main", "ground")


def material_noun(c: Context, nouns: Sequence[str]) -> bool:
    """Whether a noun names the material itself (a material word of the library, a noun
    family of ``words.toml`` but the joints', "base..."), not a part it may lack ("the
    hinges", "the topstitching")."""
    materials = {stem(m) for m in c.vocabulary.materials}
    families = set().union(*(v for k, v in c.ew.nouns.items() if k != "joint"))
    return any(
        stem(n) in materials or stem(n) in families or n.startswith(_MAIN_PARTS) for n in nouns
    )


#: A parameter that is the width of a drawn line (``Stroke(path, width)``).
_STROKE_WIDTH = re.compile(r"\.Stroke(?:#\d+)?\.width$")


def stroke_widths(params: Sequence[Param], nouns: Sequence[str], ew: EditWords) -> list[Param]:
    """The widths of the drawn lines a request names ("thinner rune strokes": the runes'
    strokes; "thicker scratched lines": every stroke), when a noun of it is a line word
    (``line_nouns`` of words.toml); empty when it names none or nothing is drawn by strokes
    ("thicker bars" of a grid)."""
    if not set(nouns) & ew["line_nouns"]:
        return []
    widths = [p for p in params if _STROKE_WIDTH.search(p.address)]
    named = [p for p in widths if overlaps(own_words(p), wanted(nouns, ew, families=False))]
    return named or widths
