"""The parts reader's vocabulary: the tables of ``data/parts.toml`` and the composer's own words.

The composer's tables (:mod:`matloom.library.compose.tables`: ``BASES``, ``LAYOUTS``,
``MOTIFS``) hold each key with the request words that name it; ``data/parts.toml`` adds the
words they lack (synonyms, phrases) and the reader's own tables (constructions, figure nouns,
translucency, which library categories show which class). :func:`vocabulary` merges the two:
one vocabulary, no second copy of the keys.
"""

from __future__ import annotations

import functools
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from matloom.library.data import DATA_DIR
from matloom.library.entry import LibraryError
from matloom.library.query import plural_stem

PARTS_FILE = DATA_DIR / "parts.toml"


@dataclass(frozen=True)
class PartsWords:
    """The tables of ``data/parts.toml`` (see the comments there)."""

    bases: dict[str, str]
    covers: dict[str, frozenset[str]]
    category_bases: dict[str, str]
    constructions: dict[str, str]
    construction_bases: dict[str, str]
    layouts: dict[str, str]
    motifs: dict[str, str]
    figures: frozenset[str]
    motif_adjectives: frozenset[str]
    motif_intro: frozenset[str]
    translucency: dict[str, float]
    #: layouts that never make the author compose (a scatter is how most natural materials lie)
    weak_layouts: frozenset[str]
    #: the base of a request that names a motif and no material, when no entry shows it
    motif_base: str
    #: layout -> the role a colour said before it takes ("red and white stripes": stripe)
    colour_layouts: dict[str, str]
    #: words after a motif word that make it a technique ("cross stitch"), not a motif
    techniques: frozenset[str] = frozenset()
    #: words that make a motif drawn on an entry a relief, not a print ("embossed stars")
    motif_relief: frozenset[str] = frozenset()
    #: plant parts a named material's word may only qualify ("oak leaves": not oak wood)
    named_parts: frozenset[str] = frozenset()
    #: words of an entry's description that say it shows a pattern of its own
    pattern_words: frozenset[str] = frozenset()
    #: words just before / after a motif said in passing that make it depicted (drawn)
    depicted_after: frozenset[str] = frozenset()
    #: words that make a named material a look-alike ("faux leather" looks like leather)
    imitation: frozenset[str] = frozenset()
    #: a best candidate scoring at least this is kept whatever class or pattern it misses
    strong_score: float = 20.0

    def weak(self, said: str) -> bool:
        """Is ``said`` a weak layout word (``[choice] weak_layouts``)?"""
        return said in self.weak_layouts or plural_stem(said) in self.weak_layouts


def _table(data: dict[str, Any], key: str) -> dict[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise LibraryError(f"{PARTS_FILE}: [{key}] must be a table")
    return value


@functools.cache
def parts_words() -> PartsWords:
    """The parts reader's word tables (read once per process)."""
    try:
        with PARTS_FILE.open("rb") as f:
            data = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise LibraryError(f"{PARTS_FILE}: {exc}") from None

    def strings(key: str) -> dict[str, str]:
        out = {}
        for word, value in _table(data, key).items():
            if not isinstance(value, str) or not value:
                raise LibraryError(f"{PARTS_FILE}: [{key}] {word!r}: expected a key name")
            out[word.lower().replace("-", " ")] = value
        return out

    return PartsWords(
        bases=strings("bases"),
        covers={k: frozenset(v) for k, v in _table(data, "covers").items()},
        category_bases=strings("category_bases"),
        constructions=strings("constructions"),
        construction_bases=strings("construction_bases"),
        layouts=strings("layouts"),
        motifs=strings("motifs"),
        figures=frozenset(_table(data, "figures").get("words", [])),
        techniques=frozenset(_table(data, "techniques").get("words", [])),
        motif_relief=frozenset(_table(data, "motif_relief").get("words", [])),
        named_parts=frozenset(_table(data, "named_parts").get("words", [])),
        pattern_words=frozenset(_table(data, "motif_depicted").get("patterned", [])),
        imitation=frozenset(_table(data, "imitation").get("words", [])),
        depicted_after=frozenset(_table(data, "motif_depicted").get("after", [])),
        motif_adjectives=frozenset(_table(data, "motif_adjectives").get("words", [])),
        motif_intro=frozenset(_table(data, "motif_intro").get("words", [])),
        translucency={
            k.lower().replace("-", " "): float(v) for k, v in _table(data, "translucency").items()
        },
        weak_layouts=frozenset(_table(data, "choice").get("weak_layouts", [])),
        motif_base=str(_table(data, "choice").get("motif_base", "fabric")),
        strong_score=float(_table(data, "choice").get("strong_score", 20.0)),
        colour_layouts=strings("colour_layouts"),
    )


def composer_tables() -> tuple[Mapping[str, Any], Mapping[str, Any], Mapping[str, Any]] | None:
    """The composer's (BASES, LAYOUTS, MOTIFS); None when there is no composer."""
    try:
        from matloom.library.compose import tables
    except ImportError:
        return None
    return tables.BASES, tables.LAYOUTS, tables.MOTIFS


_TABLES = ("bases", "layouts", "motifs")


@functools.cache
def vocabulary(table: str) -> dict[str, str]:
    """Word or phrase -> key of the composer's ``table`` ("bases", "layouts", "motifs"): every
    spec's name and own words (``words`` of its spec), then the extra words of the same table
    in ``data/parts.toml``."""
    out: dict[str, str] = {}
    found = composer_tables()
    if found is not None:
        for key, spec in found[_TABLES.index(table)].items():
            for word in (key, *getattr(spec, "words", ())):
                out.setdefault(word.lower().replace("-", " ").replace("_", " "), key)
    for word, key in getattr(parts_words(), table).items():
        out.setdefault(word, key)
    return out


def class_words() -> dict[str, str]:
    """Class word -> base key (:func:`vocabulary` of the bases)."""
    return vocabulary("bases")


def words_for(table: str, key: str) -> tuple[str, ...]:
    """Every word of :func:`vocabulary` ``table`` that names ``key``."""
    return tuple(sorted(w for w, k in vocabulary(table).items() if k == key))


def named_lookup(phrase: str) -> object | None:
    """The composer's named material for ``phrase`` (None when it has none, or no table yet)."""
    try:
        from matloom.library.compose.named import named_material
    except ImportError:
        return None
    return named_material(phrase)
