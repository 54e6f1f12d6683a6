"""The cover pass: does a retrieved entry show what the request asks for, or must the author
compose it?

An entry **covers** a part when its own words (name, description, tags, synonyms, preset
words: the retrieval index's terms) hold the part's words, stemmed:

* the **named material**: every word of it ("peat moss": peat *and* moss);
* the **material class**: its words hold the class word said or another word of that class,
  or its category is the class's (or one ``[covers]`` of ``data/parts.toml`` lists for it) and
  the class is that whole category ("fabric"; "knit" or "marble" need their words);
* each **motif** and **layout**: one of the words of its key, or the words said;
* an **unknown motif** ("giraffe figures"): the word itself.

:func:`decide` first takes a candidate whose name is the request's material word when the best
candidate's words lack it and the request does not name the best one too ("worn flagstones,
dirt packed in the cracks": ``flagstone``, not ``soil``). Then it walks the best candidates:
the first that covers the named material and the class is taken (a lower one is promoted past better-scored entries that only share words;
past the best ``TOP``, one scoring at least ``DEEP`` of the best); when none does, the request
is composed from its parts (when the composer can build its base). A
taken entry missing a requested motif or layout gives way to a candidate that shows it too, or
else to a composed program of the entry's own class that shows it. Nothing composable: the best
candidate, with what it misses reported. A plain entry (:func:`patterned`) that lacks only a
motif the composer draws keeps its place and gets the motif drawn on top (:mod:`.motif`).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

from matloom.library.entry import Entry
from matloom.library.index import Library
from matloom.library.parts import Parts, Pattern
from matloom.library.parts_words import class_words, composer_tables, parts_words, words_for
from matloom.library.retrieval import Candidate

#: how many of the best candidates may be promoted past the first
TOP = 5
#: a candidate that shows a requested motif or layout the first lacks takes its place only
#: when it scores at least this share of it (else sharing a word, "cardboard box" for "rows of
#: boxes", would win over the request's material)
PROMOTE = 0.6
#: past the best ``TOP``, a candidate that covers the named material and the class is taken
#: (before composing) when it scores at least this share of the best
DEEP = 0.2


@dataclass(frozen=True)
class Coverage:
    """What one entry misses of the request: ``essential`` (named material, class) and the
    pattern parts (motifs, layouts), as short phrases for the explanation."""

    name: str
    essential: tuple[str, ...] = ()
    pattern: tuple[str, ...] = ()
    #: the pattern parts the composer can show (keys of its tables)
    composable: tuple[str, ...] = ()

    @property
    def missing(self) -> tuple[str, ...]:
        return self.essential + self.pattern


@dataclass(frozen=True)
class Verdict:
    """The cover pass's decision: the candidate taken (its index; None for none), or the base
    to compose on, and why."""

    index: int | None
    compose: str | None = None
    #: what each of the best candidates misses
    coverage: tuple[Coverage, ...] = ()
    #: what the candidate taken misses (None when composing or when nothing was taken)
    taken: Coverage | None = None
    notes: tuple[str, ...] = ()
    #: motifs (composer keys) drawn onto the taken candidate, which shows the request's
    #: material but not them
    motifs: tuple[str, ...] = ()

    def missing(self) -> tuple[str, ...]:
        """What the taken candidate misses (nothing when composing: the composer reports),
        less the motifs drawn onto it."""
        if self.taken is None or self.compose is not None:
            return ()
        drawn = {f"motif {key}" for key in self.motifs}
        return tuple(m for m in self.taken.missing if m.split(" (")[0] not in drawn)


def composer_keys() -> tuple[frozenset[str], frozenset[str], frozenset[str]] | None:
    """(bases, layouts, motifs) the composer can build; None when there is no composer."""
    found = composer_tables()
    if found is None:
        return None
    bases, layouts, motifs = found
    return frozenset(bases), frozenset(layouts), frozenset(motifs)


class _Cover:
    def __init__(self, parts: Parts, lib: Library) -> None:
        self.parts = parts
        self.lib = lib
        self.idx = lib.index
        self.pw = parts_words()
        self.keys = composer_keys()

    def stems(self, words: Sequence[str]) -> set[str]:
        return {self.idx.stem(w) for phrase in words for w in phrase.replace("-", " ").split()}

    def shows(self, name: str, key: str, said: str, table: str) -> bool:
        terms = self.idx.terms.get(name, frozenset())
        return bool(self.stems([*words_for(table, key), said]) & terms)

    def main(self, index: int) -> bool:
        """Is token ``index`` in the request's first sentence (where what it asks for is said;
        later sentences describe)?"""
        req = self.parts.request
        return index < (req.sentence_end or len(req.tokens))

    def says_material(self, entry: Entry) -> bool:
        """Do the entry's words hold the material words the request said (its class word or
        named material), when it said any? A candidate promoted for a motif must be the
        request's material, not an object that shares the motif's word ("cardboard box" for
        "rows of boxes wallpaper")."""
        said = [self.parts.class_words, self.parts.named_words or ""]
        stems = self.stems([w for w in said if w])
        return not stems or bool(stems & self.idx.terms.get(entry.name, frozenset()))

    def shows_class(self, entry: Entry, base: str, said: str) -> bool:
        """Does ``entry`` show the class ``base``? Its words hold the class word said or
        another word of the base ("PVC strips" netting, feathers "sealed under glass"), or its
        category is the base's (or one listed for it in ``[covers]``) and the base is that
        whole category ("fabric", "glass"; a narrower base, "knit" or "marble", needs its
        words)."""
        words = [w for w, k in class_words().items() if k == base] + [said]
        if self.stems(words) & self.idx.terms.get(entry.name, frozenset()):
            return True
        found = composer_tables()
        spec = found[0].get(base) if found is not None else None
        category = getattr(spec, "category", base)
        same = entry.category == category or entry.category in self.pw.covers.get(category, ())
        return same and base == category

    def coverage(self, entry: Entry) -> Coverage:
        p, terms = self.parts, self.idx.terms.get(entry.name, frozenset())
        essential: list[str] = []
        imitation = self.pw.imitation
        if p.named and not any(
            self.stems([w for w in said.split() if w not in self.idx.stop and w not in imitation])
            <= terms
            for said in {p.named, p.named_words}
        ):
            essential.append(f"named material {p.named}")
        if p.material_class and not self.shows_class(entry, p.material_class, p.class_words):
            essential.append(f"class {p.material_class} ({p.class_words})")
        pattern: list[str] = []
        composable: list[str] = []
        for table, items in (("motifs", p.motifs), ("layouts", p.layouts)):
            for part in items:
                weak = table == "layouts" and self.pw.weak(part.words)
                if weak or self.shows(entry.name, part.key, part.words, table):
                    continue
                kind = table[:-1]
                pattern.append(f"{kind} {part.key} ({part.words})")
                known = self.keys is not None and part.key in self.keys[2 if kind == "motif" else 1]
                if known and part.explicit and self.main(part.index):
                    composable.append(f"{kind} {part.key}")
        for part in p.unknown_motifs:
            if not self.stems(part.words.split()[:1]) & terms:
                pattern.append(f"motif {part.words} (no such motif)")
        return Coverage(entry.name, tuple(essential), tuple(pattern), tuple(composable))

    def base_for(self, entry: Entry | None) -> str | None:
        """The base to compose on: the request's, else the entry's class, else the default
        for a motif with no material; None when the composer cannot build it."""
        if self.keys is None:
            return None
        base = self.parts.base
        if base is None and entry is not None:
            base = self.pw.category_bases.get(entry.category)
        if base is None and (self.parts.motifs or self.parts.layouts):
            base = self.pw.motif_base
        return base if base in self.keys[0] else None


def cover(entry: Entry, parts: Parts, lib: Library) -> Coverage:
    """What ``entry`` misses of ``parts``."""
    return _Cover(parts, lib).coverage(entry)


def decide(cands: Sequence[Candidate], lib: Library, parts: Parts) -> Verdict:
    """Take a candidate or compose (see the module docstring)."""
    c = _Cover(parts, lib)
    top = [lib.entry(x.name) for x in cands[:TOP]]
    covs = tuple(c.coverage(e) for e in top)
    named = _entry_named(c, cands, covs)
    if named is not None:
        k = named
        cov = covs[k] if k < len(covs) else c.coverage(lib.entry(cands[k].name))
        why = f"took candidate {k + 1}: the request's material word is its name"
        return Verdict(k, coverage=covs, taken=cov, notes=(why,))
    if cands and cands[0].score >= c.pw.strong_score:
        return _strong(c, cands, covs, top, lib)
    full = [k for k, cov in enumerate(covs) if not cov.essential]
    if not full:
        deep = _deeper(c, cands, lib)
        if deep is not None:
            k, cov = deep
            why = f"took candidate {k + 1}: the better ones miss {', '.join(covs[0].essential)}"
            return Verdict(k, coverage=covs, taken=cov, notes=(why,))
        asked = parts.named or parts.material_class or (not top and (parts.motifs or parts.layouts))
        base = c.base_for(None) if asked else None
        if base is not None:
            why = f"no entry shows {', '.join(covs[0].essential)}" if covs else "no entry matched"
            return Verdict(None, base, covs, notes=(f"composed: {why}",))
        return Verdict(0 if top else None, coverage=covs, taken=covs[0] if covs else None)
    k = full[0]
    notes: list[str] = []
    if k > 0:
        notes.append(f"took candidate {k + 1}: the better ones miss {', '.join(covs[0].essential)}")
    return _pattern(c, cands, covs, top, full, k, notes)


def _pattern(
    c: _Cover,
    cands: Sequence[Candidate],
    covs: tuple[Coverage, ...],
    top: list[Entry],
    full: list[int],
    k: int,
    notes: list[str],
) -> Verdict:
    """Candidate ``k`` is taken unless it lacks a requested motif or layout the composer can
    show: then a candidate of ``full`` that shows it too; else, when all it lacks are motifs
    the composer draws, it is taken with them drawn on top (:mod:`.motif`: the request's
    material with its print); else a program composed on its base."""
    if covs[k].composable:
        floor = PROMOTE * cands[k].score
        shows = [
            j
            for j in full
            if not covs[j].composable and cands[j].score >= floor and c.says_material(top[j])
        ]
        if shows:
            j = shows[0]
            notes.append(f"took candidate {j + 1}: it shows {', '.join(covs[k].composable)}")
            return Verdict(j, coverage=covs, taken=covs[j], notes=tuple(notes))
        drawn = _drawable(covs[k]) if not patterned(top[k]) else ()
        if drawn:
            notes.append(f"drew {', '.join(drawn)} onto {top[k].name}")
            return Verdict(k, coverage=covs, taken=covs[k], notes=tuple(notes), motifs=drawn)
        base = c.base_for(top[k])
        if base is not None:
            notes.append(f"composed: {top[k].name} does not show {', '.join(covs[k].composable)}")
            return Verdict(None, base, covs, notes=tuple(notes))
    return Verdict(k, coverage=covs, taken=covs[k], notes=tuple(notes))


def _strong(
    c: _Cover,
    cands: Sequence[Candidate],
    covs: tuple[Coverage, ...],
    top: list[Entry],
    lib: Library,
) -> Verdict:
    """A strong best match (``[choice] strong_score``) is kept, with what it misses reported,
    unless it lacks the named material (a candidate that says it takes its place, "malachite
    tiles": the malachite entry, else a program composed of it when the composer knows it,
    "peat moss ground") or a motif the request explicitly asks for (then as :func:`_pattern`).
    A missing class or layout alone does not move it: judged on held-out requests, those
    readings overrode strong matches wrongly far more often than rightly."""
    if not _misses_named(covs[0]):
        if any(x.startswith("motif ") for x in covs[0].composable):
            full = [j for j, cov in enumerate(covs) if not _misses_named(cov)]
            return _pattern(c, cands, covs, top, full, 0, [])
        return Verdict(0, coverage=covs, taken=covs[0])
    named = [k for k, cov in enumerate(covs) if not _misses_named(cov)]
    if named:
        k = named[0]
    else:
        deep = _deeper(c, cands, lib, named_only=True)
        if deep is None:
            base = c.base_for(None)
            if base is not None:
                why = f"composed: no entry shows {', '.join(covs[0].essential)}"
                return Verdict(None, base, covs, notes=(why,))
            return Verdict(0, coverage=covs, taken=covs[0])
        k = deep[0]
    cov = covs[k] if k < len(covs) else c.coverage(lib.entry(cands[k].name))
    why = f"took candidate {k + 1}: the better ones miss {', '.join(covs[0].essential)}"
    return Verdict(k, coverage=covs, taken=cov, notes=(why,))


def _entry_named(c: _Cover, cands: Sequence[Candidate], covs: tuple[Coverage, ...]) -> int | None:
    """The candidate whose name is the request's material word ("worn flagstones": the
    ``flagstone`` entry) when the best candidate's words lack that word (``soil``, on "dirt
    packed in the cracks"), it is among the candidates scoring at least ``DEEP`` of the best,
    and the request names no other material."""
    said = c.parts.class_words
    if not said or c.parts.named or not cands:
        return None
    stems = c.stems([said])
    if stems <= c.idx.terms.get(cands[0].name, frozenset()):
        return None  # the best candidate says the word itself
    if c.stems([cands[0].name]) & c.stems([c.parts.prompt]):
        return None  # the request names the best candidate too ("vinyl ... crocodile")
    name = "-".join(sorted(stems))
    floor = DEEP * cands[0].score
    for k, cand in enumerate(cands[1:], start=1):
        if cand.score < floor:
            break
        if "-".join(sorted(c.stems([cand.name]))) == name:
            # not at the cost of a pattern the best shows ("vinyl ... with a crocodile
            # embossed pattern", "hazard stripes on worn concrete")
            mine = covs[k] if k < len(covs) else c.coverage(c.lib.entry(cand.name))
            return k if len(mine.pattern) <= len(covs[0].pattern) else None
    return None


def _shape(key: str) -> bool:
    """Does the composer draw motif ``key`` as a shape (a lattice pattern, a maze or a wave,
    replaces the surface: composed instead)?"""
    from matloom.library.compose.motifs import MOTIFS

    return key in MOTIFS and MOTIFS[key].kind == "shape"


def _drawable(cov: Coverage) -> tuple[str, ...]:
    """The motif to draw onto an entry that lacks only motifs the composer draws as shapes;
    () when it lacks a layout or another kind of motif too. One motif, as a composed program."""
    keys = [part.split(" ", 1)[1] for part in cov.composable]
    if any(not part.startswith("motif ") for part in cov.composable):
        return ()
    return tuple(keys[:1]) if all(_shape(key) for key in keys) else ()


@functools.cache
def _described_pattern(description: str) -> bool:
    from matloom.library.parts import read_parts

    said = read_parts(description)
    pw = parts_words()
    if said.motifs or any(not pw.weak(p.words) for p in said.layouts):
        return True
    return bool(pw.pattern_words & set(said.request.tokens))


def patterned(entry: Entry) -> bool:
    """Does ``entry`` show a pattern of its own (its description names a motif or a layout:
    argyle diamonds, a plaid's checks, a floral print)? A requested motif is drawn onto a plain
    entry; a patterned one gives way to a composed program, whose only pattern is the one
    asked for."""
    return _described_pattern(entry.description)


def drawable_missing(cov: Coverage, parts: Parts) -> tuple[str, ...]:
    """The motif the request asks for explicitly ("with white stars", in any sentence) that
    the entry of ``cov`` does not show and the composer draws as a shape: drawn onto it (one,
    as :func:`_drawable`)."""
    missing = {m.split(" (")[0] for m in cov.pattern}
    if any(m.startswith("layout ") for m in missing):
        return ()  # "a quilted diamond pattern": the layout is the point, not a motif on top
    keys = [
        p.key
        for p in parts.motifs
        if (p.explicit or _depicted(p, parts)) and f"motif {p.key}" in missing and _shape(p.key)
    ]
    return tuple(keys[:1])


#: how far (tokens) a ``[motif_depicted]`` word may stand from the motif's words
_DEPICTED_REACH = 4


def _depicted(p: Pattern, parts: Parts) -> bool:
    """Is motif ``p``, said in passing, depicted on the surface ("tiny dots scattered across
    it", "cats ... printed all over"; ``[motif_depicted] after``)? "There are some faded spots
    where the colour has worn" is wear, not a motif."""
    pw = parts_words()
    tokens = parts.request.tokens
    end = p.index + len(p.words.split())
    after = tokens[end : end + _DEPICTED_REACH]
    return bool(pw.depicted_after & set(after))


def _misses_named(cov: Coverage) -> bool:
    return any(e.startswith("named material") for e in cov.essential)


def _deeper(
    c: _Cover, cands: Sequence[Candidate], lib: Library, named_only: bool = False
) -> tuple[int, Coverage] | None:
    """The first candidate past the best ``TOP`` that covers the named material and the class,
    among those scoring at least ``DEEP`` of the best ("malachite tiles": the tile entries
    rank first, the malachite entry further down)."""
    floor = DEEP * cands[0].score if cands else 0.0
    for k in range(TOP, len(cands)):
        if cands[k].score < floor:
            break
        cov = c.coverage(lib.entry(cands[k].name))
        if not (_misses_named(cov) if named_only else cov.essential):
            return k, cov
    return None
