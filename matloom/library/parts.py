"""Reading a request as parts: what it asks for, as the composer's vocabulary.

:func:`read_parts` runs the request reader (:func:`matloom.library.query.read`: colours, finish
words, overlays, sizes, counts) and reads on top of it:

* the **named material** ("malachite", "peat moss"): the longest phrase the composer's table of
  named materials knows (:func:`matloom.library.compose.named.named_material`);
* the **material class**: the last class word of the head clause ("basalt fibre *cloth*"), as a
  key of the composer's ``BASES`` (``[bases]`` of ``data/parts.toml``);
* the **fabric construction** (weave, knit, print, embroidery, pile);
* the **layout** (grid, rows, brick, herringbone, hexagons, stripes, checks, scatter,
  perforations, quilting) and the **motif** (shapes and simple figures: "stars", "foxes",
  "oval", "animal figures"), as keys of ``LAYOUTS`` and ``MOTIFS``; a word before a figure noun
  that no table knows ("giraffe figures") is an **unknown motif**, reported as not shown;
* the **translucency** and the finish (roughness, metalness);
* the **colour roles**: ``base`` (the ground), ``secondary``, ``accent``, ``grout``, ``motif``
  ("white *stars*") and ``stripe`` ("red and white *stripes*").

Every rule records the tokens it used (:attr:`Parts.used`), so the author can report every word
and every part it did not show. :func:`to_spec` turns the parts into a
:class:`~matloom.library.compose.spec.CompositionSpec`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from matloom.library.colour import RGB
from matloom.library.compose.spec import CompositionSpec, Finish, MotifSpec
from matloom.library.data import Words, words
from matloom.library.parts_words import (
    PartsWords,
    class_words,
    named_lookup,
    parts_words,
    vocabulary,
)
from matloom.library.query import Request, plural_stem, read

#: the longest phrase a table key may be (words)
_LONGEST = 3
#: figure nouns that make an unknown word before them a motif ("giraffe figures"); "pattern"
#: and "shapes" only attach to a known motif ("star shapes"), never to an unknown word
_GENERIC_FIGURES = frozenset({"pattern", "patterns", "shape", "shapes"})
#: how far (tokens) a colour looks ahead for the noun that gives it its role
_ROLE_WINDOW = 4
_JOIN = frozenset({"and", "or", ",", "/", "&"})
#: words that make a layout noun one thing ("a stripe")
_ONE = frozenset({"a", "an", "one", "single"})
#: the roughness and metalness a finish key asks for besides ``finish_roughness``
_METALLIC = {"metallic": 0.85, "brushed": 0.8}


@dataclass(frozen=True)
class Pattern:
    """A layout or motif the request names: the composer's key (empty for an unknown motif),
    the words said and the token index they start at."""

    key: str
    words: str
    index: int
    #: said as a part of the request ("with white stars", "fox figures", "striped"), not in
    #: passing ("autumn leaves", "tiles"): only these make the author compose
    explicit: bool = True


@dataclass(frozen=True)
class PartColour:
    """A colour of the request with its role in the composition."""

    role: str
    rgb: RGB
    words: str


@dataclass(frozen=True)
class Parts:
    """A request read as parts (see the module docstring); keys are the composer's."""

    prompt: str
    request: Request
    #: a key of ``BASES``: the class the request's class word names
    material_class: str | None = None
    class_words: str = ""
    #: a named material the composer's table knows ("malachite"), as it was said
    named: str | None = None
    #: the words that named it ("volcanic glass" for obsidian)
    named_words: str = ""
    #: the base the named material belongs to (from the composer's table)
    named_base: str | None = None
    colours: tuple[PartColour, ...] = ()
    finish: Finish = field(default_factory=Finish)
    #: every layout / motif the request names, in request order
    layouts: tuple[Pattern, ...] = ()
    motifs: tuple[Pattern, ...] = ()
    #: motifs no table holds ("giraffe figures"): always reported as not shown
    unknown_motifs: tuple[Pattern, ...] = ()
    construction: str | None = None
    construction_words: str = ""
    overlays: tuple[str, ...] = ()
    size_m: float | None = None
    count: int | None = None
    scale: float = 1.0
    #: token index -> the part that used it
    used: Mapping[int, str] = field(default_factory=lambda: MappingProxyType({}))

    @property
    def layout(self) -> str | None:
        return self.layouts[0].key if self.layouts else None

    @property
    def motif(self) -> str | None:
        return self.motifs[0].key if self.motifs else None

    @property
    def base(self) -> str | None:
        """The base a composed program starts from: the class word's, else the named
        material's, else the construction's."""
        if self.material_class:
            return self.material_class
        if self.named_base:
            return self.named_base
        if self.construction:
            return parts_words().construction_bases.get(self.construction)
        return None

    @property
    def translucency(self) -> float | None:
        return self.finish.translucency

    def roles(self) -> dict[str, list[str]]:
        """Role -> the colour words with that role."""
        out: dict[str, list[str]] = {}
        for c in self.colours:
            out.setdefault(c.role, []).append(c.words)
        return out

    def summary(self) -> str:
        """One line for the explanation: every part that was read."""
        bits: list[str] = []
        if self.material_class:
            bits.append(f"class {self.material_class} ({self.class_words})")
        if self.named:
            said = f" ({self.named_words})" if self.named_words != self.named else ""
            bits.append(f"named {self.named}{said}")
        if self.construction:
            bits.append(f"construction {self.construction} ({self.construction_words})")
        if self.colours:
            bits.append("colours " + ", ".join(f"{c.words} ({c.role})" for c in self.colours))
        if self.finish.words:
            bits.append("finish " + " ".join(self.finish.words))
        bits += [f"layout {p.key} ({p.words})" for p in self.layouts]
        bits += [f"motif {p.key} ({p.words})" for p in self.motifs]
        bits += [f"motif ? ({p.words})" for p in self.unknown_motifs]
        if self.overlays:
            bits.append("overlays " + ", ".join(self.overlays))
        if self.size_m is not None:
            bits.append(f"size {self.size_m:g} m")
        if self.count is not None:
            bits.append(f"count {self.count}")
        if self.scale != 1.0:
            bits.append(f"scale x{self.scale:.3g}")
        return "; ".join(bits) or "nothing recognised"


class _PartsReader:
    def __init__(self, req: Request, w: Words, pw: PartsWords) -> None:
        self.req = req
        self.t = req.tokens
        self.w = w
        self.pw = pw
        self.used: dict[int, str] = {}
        self.motif_parts: list[Pattern] = []

    def at(self, i: int) -> str:
        return self.t[i] if 0 <= i < len(self.t) else ""

    def free(self, i: int, *, finish_ok: bool = False) -> bool:
        """Is token ``i`` a word no rule of the reader nor of the parts took?"""
        if i in self.used or i in self.req.negated or not self.at(i)[:1].isalpha():
            return False
        rule = self.req.used.get(i)
        if rule is None or i in self.req.lone_materials:
            return True
        return finish_ok and rule == "finish"

    def phrases(self, table: dict[str, str], *, finish_ok: bool = False):  # noqa: ANN201
        """(start, end, key, words) of every phrase of ``table`` in the free tokens, longest
        first at each position, left to right; the last word may be a plural."""
        i = 0
        while i < len(self.t):
            for n in range(_LONGEST, 0, -1):
                idx = range(i, i + n)
                if i + n > len(self.t) or not all(self.free(k, finish_ok=finish_ok) for k in idx):
                    continue
                words = [self.t[k] for k in idx]
                said = " ".join(words)
                key = table.get(said)
                plural = False
                if key is None:
                    key = table.get(" ".join([*words[:-1], plural_stem(words[-1])]))
                    plural = key is not None
                if key is not None:
                    yield i, i + n, key, said, plural
                    i += n - 1
                    break
            i += 1

    # ------------------------------------------------------------------ material
    def named(self) -> tuple[str | None, str, str | None]:
        """(the named material's name, the words said, its base): the head clause's first,
        then the longest, then the first said; every phrase naming the same material is used
        ("obsidian volcanic glass")."""
        end = self.req.head_end or len(self.t)
        found: list[tuple[int, int, str, Any]] = []
        i = 0
        while i < len(self.t):
            for n in range(_LONGEST, 0, -1):
                idx = range(i, i + n)
                if i + n > len(self.t) or not all(self.named_free(k, n > 1) for k in idx):
                    continue
                words = [self.t[k] for k in idx]
                if words[0] in self.w.stop_words or words[-1] in self.w.stop_words:
                    continue
                said = " ".join(words)
                hit = named_lookup(said)
                if hit is None and plural_stem(words[-1]) != words[-1]:
                    hit = named_lookup(" ".join([*words[:-1], plural_stem(words[-1])]))
                if hit is not None:
                    found.append((i, i + n, said, hit))
                    i += n - 1
                    break
            i += 1
        found = [f for f in found if not self.names_a_part(f[1])]
        head = [f for f in found if f[0] < end]
        if not head:  # a named material after the head ("velvet with gold dots") is a detail
            if any(self.is_material(w) for w in self.t[:end]):
                return None, "", None
            last = self.req.sentence_end or len(self.t)
            head = [f for f in found if f[0] < last and self.names_material(f[0], f[1])]
        if not head:
            return None, "", None
        i, j, said, hit = min(head, key=lambda f: (-(f[1] - f[0]), f[0]))
        name = str(getattr(hit, "name", said))
        for a, b, _, other in found:
            if str(getattr(other, "name", "")) == name:
                for k in range(a, b):
                    self.used[k] = "named"
        base = getattr(hit, "base", None)
        return name, said, base if isinstance(base, str) else None

    def is_material(self, word: str) -> bool:
        """Is ``word`` a class word or a material noun ("carpet", "lacquer" is not)?"""
        table, nouns = class_words(), self.w.materials
        return any(w in table or w in nouns for w in (word, plural_stem(word)))

    def names_a_part(self, j: int) -> bool:
        """Is the named phrase ending at ``j`` the kind of a plant part rather than the material
        ("oak and maple leaves", "pine needles", "walnut shells": ``[named_parts]``)?"""
        k = j
        if self.at(k) in _JOIN and k + 1 < len(self.t):  # "oak and maple leaves"
            k += 2
        nxt = self.at(k)
        return nxt in parts_words().named_parts or plural_stem(nxt) in parts_words().named_parts

    def names_material(self, i: int, j: int) -> bool:
        """Does the named phrase at ``i:j`` after the head name the material: not a metal's
        colour name ("with gold cherry blossoms") nor a colour before a motif or layout ("gold
        diamond pattern")?"""
        if j - i == 1 and self.t[i] in self.w.metal_colours:
            return False
        nxt = self.at(j)
        tables = (vocabulary("motifs"), vocabulary("layouts"))
        return not any(nxt in t or plural_stem(nxt) in t for t in tables)

    def named_free(self, i: int, phrase: bool = False) -> bool:
        """Named materials may take overlay words ("peat moss", "rust"); a colour only inside
        a longer name ("rose quartz", "black sand"), where the colour stays read too."""
        if self.free(i):
            return True
        if i in self.used or i in self.req.negated:
            return False
        rule = self.req.used.get(i)
        return rule == "overlay" or (phrase and rule == "colour")

    def material_class(self) -> tuple[str | None, str]:
        """The class of the head clause's first noun phrase: its first class word, or the last
        of the class words right after it ("basalt fibre cloth": cloth; "wool fabric":
        fabric), not a class word of a later phrase ("paper held in a wood frame": paper)."""
        end = self.req.head_end or len(self.t)
        start = 0
        if self.req.term_end:  # "Tweed: a rough woollen fabric, ...": the definition's head
            start = self.req.term_end + 1
            ends = [k for k in range(start, len(self.t)) if self.t[k] in self.w.head_end]
            end = ends[0] if ends else len(self.t)
        found = self.phrases(class_words(), finish_ok=True)
        hits = [h for h in found if start <= h[0] < end]
        if not hits:
            return None, ""
        i, j, key, said, _ = hits[0]
        for h in hits[1:]:
            gap = range(j, h[0])
            if len(gap) > 1 or any(self.t[k] in self.w.stop_words for k in gap):
                break
            i, j, key, said = h[0], h[1], h[2], h[3]
        for k in range(i, j):
            self.used[k] = "class"
        return key, said

    def construction(self) -> tuple[str | None, str]:
        """The fabric construction; a class word may say it too ("knitted")."""
        taken = {k: p for k, p in self.used.items() if p == "class"}
        for k in taken:
            del self.used[k]
        found: tuple[str | None, str] = (None, "")
        for i, j, key, said, _ in self.phrases(self.pw.constructions, finish_ok=True):
            for k in range(i, j):
                self.used[k] = "construction"
            found = (key, said)
            break
        for k, p in taken.items():
            self.used.setdefault(k, p)
        return found

    # ------------------------------------------------------------------ pattern
    def layouts(self) -> list[Pattern]:
        """The layouts said; a weak layout word ("tiles", "scattered") only when no other
        layout is named ("hexagon tiles" is hexagons)."""
        out: list[Pattern] = []
        for i, j, key, said, _ in self.phrases(vocabulary("layouts"), finish_ok=True):
            for k in range(i, j):
                self.used[k] = "layout"
            explicit = not self.pw.weak(said) and not self.one_thing(i, said)
            out.append(Pattern(key, said, i, explicit=explicit))
        strong = [x for x in out if x.explicit]
        return strong or out[:1]

    def one_thing(self, i: int, said: str) -> bool:
        """Is the layout noun at ``i`` said once ("a yellow hazard stripe"): a singular noun
        whose plural is a layout word, after "a", "an", "one" or "single"?"""
        table = vocabulary("layouts")
        if not any(said + end in table for end in ("s", "es")):
            return False
        for k in range(i - 1, max(i - 5, -1), -1):
            if self.t[k] in _ONE:
                return True
            if self.t[k] in self.w.clause_end or self.t[k] in {",", "with", "and"}:
                return False
        return False

    def introduced(self, i: int) -> bool:
        """Is the motif at ``i`` introduced as drawn on the surface: after "with", "of" ...
        past colour, size, count, finish and small words and at most two other words ("with
        small hand painted stars")?"""
        others = 0
        for k in range(i - 1, max(i - 8, -1), -1):
            word = self.t[k]
            if word in self.pw.motif_intro:
                return True
            if word in self.w.clause_end or word == ",":
                return False
            rule = self.req.used.get(k)
            skip = rule in {"colour", "scale", "count", "amount", "size", "finish"}
            skip = skip or self.w.colour(word) is not None  # "with gold dots"
            if not (skip or word in self.w.stop_words or word in _JOIN or self.used.get(k)):
                others += 1
                if others > 2 or rule is not None:
                    return False
        return False

    def motifs(self) -> tuple[list[Pattern], list[Pattern]]:
        """The motifs said (see ``[motif_adjectives]``) and the unknown ones."""
        out: list[Pattern] = []
        unknown: list[Pattern] = []
        for i, j, key, said, plural in list(self.phrases(vocabulary("motifs"))):
            last = said.split()[-1]
            if self.at(j) in self.pw.techniques:
                continue  # "cross-stitch", "cross-hatched": how it is made, not a motif
            figure = self.at(j) in self.pw.figures
            adjective = said.split()[0] in self.pw.motif_adjectives
            many = plural or plural_stem(last) != last
            intro = self.introduced(i)
            if not (adjective or many or figure or intro):
                continue  # "fish scales", "tree bark", "heart pine": no motif
            for k in range(i, j + figure):
                self.used[k] = "motif"
            words = said + (f" {self.at(j)}" if figure else "")
            out.append(Pattern(key, words, i, explicit=figure or intro or adjective))
        self.motif_parts = out
        for i, word in enumerate(self.t):
            if word not in self.pw.figures or word in _GENERIC_FIGURES or i in self.used:
                continue
            prev = self.at(i - 1)
            if self.free(i - 1) and prev not in self.w.stop_words and len(prev) > 2:
                self.used[i - 1] = self.used[i] = "motif"
                unknown.append(Pattern("", f"{prev} {word}", i - 1))
        return out, unknown

    def translucency(self) -> float | None:
        for i, j, key, _said, _ in self.phrases(
            {k: k for k in self.pw.translucency}, finish_ok=True
        ):
            for k in range(i, j):
                self.used.setdefault(k, "translucency")
            return self.pw.translucency[key]
        return None

    # ------------------------------------------------------------------ colours
    def role(self, index: int, words: str, query_role: str | None) -> str:
        """The role of the colour said at ``index``: the motif, stripe or grout noun after it
        (past a list of colours: "red and white stripes"), "stars in gold", else the reader's."""
        k = index + len(words.split())
        while k < len(self.t) and (self.t[k] in _JOIN or self.req.used.get(k) == "colour"):
            k += 1
        for j in range(k, min(k + _ROLE_WINDOW, len(self.t))):
            word = self.t[j]
            if word in self.w.clause_end or word in {",", "with", "on", "over"}:
                break
            part = self.used.get(j)
            if part == "motif":
                return "motif"
            if part == "layout" and self.layout_key(j) in self.pw.colour_layouts:
                return self.pw.colour_layouts[self.layout_key(j) or ""]
            if self.w.roles.get(word) == "grout":
                return "grout"
        if self.at(index - 1) in {"in", "of"} and self.used.get(index - 2) == "motif":
            return "motif"
        if query_role == "grout":
            return "grout"
        if query_role in {"accent", "frame"}:
            return "accent"
        return query_role or ""

    def layout_key(self, j: int) -> str | None:
        table = vocabulary("layouts")
        return table.get(self.t[j]) or table.get(plural_stem(self.t[j]))

    def colours(self) -> list[PartColour]:
        out: list[PartColour] = []
        for m in self.req.colours:
            if m.role == "overlay":
                continue  # the overlay's own colour ("green moss")
            role = self.role(m.index, m.words, m.role)
            if not role or (role == "base" and any(c.role == "base" for c in out)):
                role = "secondary" if any(c.role == "base" for c in out) else "base"
            out.append(PartColour(role, m.rgb, m.words))
        for p in self.motif_parts:  # "gold polka dots": a material colour name before a motif
            k = p.index - 1
            rgb = self.w.colour(self.at(k))
            if rgb is not None and self.free(k) and self.at(k) not in self.w.stop_words:
                self.used[k] = "colour"
                out.append(PartColour("motif", rgb, self.at(k)))
        if not any(c.role == "base" for c in out):
            pairs = [c for c in out if c.role in {"stripe", "accent"}]
            if len(pairs) >= 2:  # "red and white stripes": the first is the ground
                first = out.index(pairs[0])
                out[first] = PartColour("base", pairs[0].rgb, pairs[0].words)
        return out

    # ------------------------------------------------------------------ finish
    def finish(self, translucency: float | None) -> Finish:
        rough: float | None = None
        metal: float | None = None
        said: list[str] = []
        for key, word in self.req.finishes:
            said.append(word)
            if rough is None and key in self.w.finish_roughness:
                rough = self.w.finish_roughness[key]
            if metal is None and key in _METALLIC:
                metal = _METALLIC[key]
        if translucency is not None:
            said += [self.t[k] for k, p in sorted(self.used.items()) if p == "translucency"]
        return Finish(rough, metal, translucency, tuple(dict.fromkeys(said)))


def read_parts(
    prompt: str,
    *,
    req: Request | None = None,
    triggers: dict[str, str] | None = None,
    weak: set[str] | None = None,
) -> Parts:
    """Read ``prompt`` as parts. ``req`` is the reader's request when the caller has it
    (the author does); else the prompt is read with ``triggers``/``weak`` (the library's overlay
    words, read from the installed library when not given)."""
    w = words()
    if req is None:
        if triggers is None:
            from matloom.library.index import library

            lib = library()
            triggers, weak = lib.triggers, lib.weak_triggers
        req = read(prompt or "", w, triggers, weak)
    r = _PartsReader(req, w, parts_words())
    named, named_words, named_base = r.named()
    material_class, class_words = r.material_class()
    construction, construction_words = r.construction()
    layouts = r.layouts()
    motifs, unknown = r.motifs()
    translucency = r.translucency()
    overlays = tuple(
        m.name
        for m in req.overlays
        if not all(r.used.get(k) == "named" for k in range(m.index, m.index + len(m.word.split())))
    )
    return Parts(
        prompt=prompt or "",
        request=req,
        material_class=material_class,
        class_words=class_words,
        named=named,
        named_words=named_words,
        named_base=named_base,
        colours=tuple(r.colours()),
        finish=r.finish(translucency),
        layouts=tuple(layouts),
        motifs=tuple(motifs),
        unknown_motifs=tuple(unknown),
        construction=construction,
        construction_words=construction_words,
        overlays=overlays,
        size_m=next((z.metres for z in req.sizes if not z.extent), None),
        count=req.counts[0].value if req.counts else None,
        scale=req.scale,
        used=MappingProxyType(dict(r.used)),
    )


def to_spec(parts: Parts, *, base: str | None = None, seed: int = 0) -> CompositionSpec:
    """The composition the parts ask for. ``base`` overrides the parts' own base (the author
    passes the best entry's class when the request names none); ValueError when there is no
    base at all."""
    key = base or parts.base
    if key is None:
        raise ValueError("the request names no material class to compose")
    motif = None
    if parts.motifs:
        first = parts.motifs[0]
        colour = next((c.rgb for c in parts.colours if c.role == "motif"), None)
        motif = MotifSpec(shape=first.key, colour=colour, words=(first.words,))
    return CompositionSpec(
        base=key,
        colours=tuple((c.role, c.rgb) for c in parts.colours),
        finish=parts.finish,
        layout=parts.layout,
        motif=motif,
        size_m=parts.size_m,
        named=parts.named,
        seed=seed,
    )
