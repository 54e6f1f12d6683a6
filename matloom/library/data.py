"""The library's word data: colours, request words, synonyms and shared presets (TOML files in
``matloom/library/data/``), read once per process.

``colours.toml``  named colours, multi-word colour phrases, ``-ish`` forms, tone modifiers and
                  the colour names that are usually materials ("slate", "copper");
``words.toml``    negations, stop words, finishes, scale, amount, unit and number words, the
                  nouns that give a colour its role ("grout", "veins", "background"), material
                  nouns, motif words and extra overlay words;
``synonyms.toml`` request words or phrases -> extra retrieval terms ("desert" -> "arid dry sand");
``presets.toml``  word presets shared by several entries ("walnut" -> the ``wood`` colour).
"""

from __future__ import annotations

import functools
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.library.colour import RGB
from matloom.library.entry import LibraryError, PresetValue, read_presets

DATA_DIR = Path(__file__).resolve().parent / "data"


@dataclass(frozen=True)
class Words:
    """Everything the request reader and the adapter look words up in."""

    named: dict[str, RGB]
    phrases: dict[str, RGB]
    ish: dict[str, str]
    tones: dict[str, tuple[float, float]]
    materialish: frozenset[str]
    negations: frozenset[str]
    stop_words: frozenset[str]
    finishes: dict[str, str]
    finish_roughness: dict[str, float]
    finish_relief: dict[str, float]
    scale: dict[str, float]
    amounts: dict[str, float]
    units: dict[str, float]
    numbers: dict[str, int]
    roles: dict[str, str]
    category_words: dict[str, frozenset[str]]
    carriers: frozenset[str]
    form_nouns: frozenset[str]
    defaults: frozenset[str]
    #: material nouns ("leather", "cobblestone"): they weigh more in retrieval
    materials: frozenset[str]
    #: motif -> the words that name it ("hexagon": hexagonal, honeycomb ...)
    motifs: dict[str, frozenset[str]]
    #: extra overlay words (data): word or phrase -> overlay name ("rain" -> wet)
    overlay_words: dict[str, str]
    #: colour names that are metals ("silver"): colours unless the entry is that metal
    metal_colours: frozenset[str]
    synonyms: dict[str, tuple[str, ...]]
    preset_sets: dict[str, dict[str, dict[str, PresetValue]]]

    def colour(self, name: str) -> RGB | None:
        """The colour of a single word or phrase, or None."""
        key = name.lower().strip()
        if key in self.phrases:
            return self.phrases[key]
        if key in self.named:
            return self.named[key]
        if key in self.ish:
            return self.named.get(self.ish[key])
        return None


def _load(name: str) -> dict[str, Any]:
    path = DATA_DIR / name
    try:
        with path.open("rb") as f:
            return tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise LibraryError(f"{path}: {exc}") from None


def _rgb_table(data: dict[str, Any], file: str, key: str) -> dict[str, RGB]:
    out: dict[str, RGB] = {}
    for name, value in data.get(key, {}).items():
        if not (
            isinstance(value, list) and len(value) == 3 and all(isinstance(v, int) for v in value)
        ):
            raise LibraryError(f"{DATA_DIR / file}: [{key}] {name!r}: expected [r, g, b]")
        out[name.lower()] = (value[0], value[1], value[2])
    return out


def _fail_in(file: str):  # noqa: ANN202 - a small error factory for read_presets
    def fail(key: str, problem: str) -> LibraryError:
        return LibraryError(f"{DATA_DIR / file}: key '{key}': {problem}")

    return fail


@functools.cache
def words() -> Words:
    """The word data (cached: read once per process)."""
    col = _load("colours.toml")
    w = _load("words.toml")
    syn = _load("synonyms.toml")
    pre = _load("presets.toml")
    synonyms: dict[str, tuple[str, ...]] = {}
    for key, value in syn.get("synonyms", {}).items():
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise LibraryError(f"{DATA_DIR / 'synonyms.toml'}: {key!r}: expected a list of words")
        synonyms[key.lower()] = tuple(v.lower() for v in value)
    sets = {
        name: read_presets(table, _fail_in("presets.toml"))
        for name, table in pre.items()
        if isinstance(table, dict)
    }
    return Words(
        named=_rgb_table(col, "colours.toml", "named"),
        phrases=_rgb_table(col, "colours.toml", "phrases"),
        ish={k.lower(): v for k, v in col.get("ish", {}).items()},
        tones={k: (float(v[0]), float(v[1])) for k, v in col.get("tones", {}).items()},
        materialish=frozenset(col.get("materialish", {}).get("words", [])),
        negations=frozenset(w.get("negations", [])),
        stop_words=frozenset(w.get("stop_words", [])),
        finishes=dict(w.get("finishes", {})),
        finish_roughness={k: float(v) for k, v in w.get("finish_roughness", {}).items()},
        finish_relief={k: float(v) for k, v in w.get("finish_relief", {}).items()},
        scale={k: float(v) for k, v in w.get("scale", {}).items()},
        amounts={k: float(v) for k, v in w.get("amounts", {}).items()},
        units={k: float(v) for k, v in w.get("units", {}).items()},
        numbers={k: int(v) for k, v in w.get("numbers", {}).items()},
        roles=dict(w.get("roles", {})),
        category_words={k: frozenset(v) for k, v in w.get("category_words", {}).items()},
        carriers=frozenset(w.get("carriers", [])),
        form_nouns=frozenset(w.get("form_nouns", [])),
        defaults=frozenset(w.get("defaults", {}).values()),
        materials=frozenset(w.get("materials", {}).get("words", [])),
        motifs={k: frozenset(v) for k, v in w.get("motifs", {}).items()},
        overlay_words={k.lower(): v for k, v in w.get("overlay_words", {}).items()},
        metal_colours=frozenset(col.get("metal_colours", {}).get("words", [])),
        synonyms=synonyms,
        preset_sets=sets,
    )
