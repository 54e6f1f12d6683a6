"""The library's word data: colours, request words, synonyms and shared presets (TOML files in
``matloom/library/data/``), read once per process.

``colours.toml``  named colours, multi-word colour phrases, ``-ish`` forms, tone modifiers, the
                  colour names that are usually materials ("slate", "copper") and the basic
                  colour words;
``words.toml``    negations, stop words, finishes, scale, amount, unit and number words, the
                  nouns that give a colour its role ("grout", "veins", "background"), material
                  nouns, motif words, extra overlay words, the adapter's category kinds and
                  the request reader's grammar words (``[grammar]``);
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
    #: the basic colour words ("red", "grey"): families, not specific shades
    basic: frozenset[str]
    #: the words a specific colour name may come before as its family ("cornflower blue")
    families: frozenset[str]
    #: basic colours that never join another into one colour ("black white" is two)
    contrasting: frozenset[str]
    #: finish key -> the gloss slot value it requests
    finish_gloss: dict[str, float]
    #: words before a tone that soften or strengthen it ("slightly darker") -> strength
    intensity: dict[str, float]
    #: the noun after a tone word -> the role of the slot it changes ("pale mortar": grout)
    tone_roles: dict[str, str]
    #: categories whose colours are natural material colours ("red brick" stays brick-like)
    natural: frozenset[str]
    #: categories whose other colours follow the request's palette
    patterned: frozenset[str]
    #: art-style words ("stylized", "cartoon"): entries tagged so are styles, asked for by name
    styles: frozenset[str]
    #: words that turn an overlay's patches into streaks running down ("rust streaks")
    streaks: frozenset[str]
    #: words after a metre-sized size that name the texture's repeat ("a 4x4m tile")
    repeat: frozenset[str]
    #: the reader's grammar words ([grammar] of words.toml; each list is described there)
    clause_end: frozenset[str]
    head_end: frozenset[str]
    list_join: frozenset[str]
    colour_suffix: frozenset[str]
    condition_tones: frozenset[str]
    tone_only: frozenset[str]
    role_stop: frozenset[str]
    plain_roles: frozenset[str]
    scale_skip: frozenset[str]
    colour_nouns: frozenset[str]
    copulas: frozenset[str]
    metals: frozenset[str]
    colour_join: frozenset[str]
    #: nouns after a colour that are no thing of their own (the colour nouns included)
    no_thing: frozenset[str]
    synonyms: dict[str, tuple[str, ...]]
    preset_sets: dict[str, dict[str, dict[str, PresetValue]]]

    def ish_base(self, word: str) -> str:
        """The colour word an ``-ish`` form is of ("reddish" -> "red"); any other word as it is."""
        return self.ish.get(word, word) if word.endswith("ish") else word

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


def _word_set(table: dict[str, Any], key: str) -> frozenset[str]:
    return frozenset(table.get(key, []))


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
    basic = col.get("basic", {})
    grammar = w.get("grammar", {})
    colour_nouns = _word_set(grammar, "colour_nouns")
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
        basic=_word_set(basic, "words"),
        families=_word_set(basic, "words") | _word_set(basic, "families"),
        contrasting=_word_set(basic, "contrasting"),
        finish_gloss={k: float(v) for k, v in w.get("finish_gloss", {}).items()},
        intensity={k: float(v) for k, v in w.get("intensity", {}).items()},
        tone_roles=dict(w.get("tone_roles", {})),
        natural=_word_set(w.get("categories", {}), "natural"),
        patterned=_word_set(w.get("categories", {}), "patterned"),
        styles=_word_set(w.get("styles", {}), "words"),
        streaks=_word_set(w.get("streaks", {}), "words"),
        repeat=_word_set(w.get("repeat", {}), "words"),
        clause_end=_word_set(grammar, "clause_end"),
        head_end=_word_set(grammar, "head_end"),
        list_join=_word_set(grammar, "list_join"),
        colour_suffix=_word_set(grammar, "colour_suffix"),
        condition_tones=_word_set(grammar, "condition_tones"),
        tone_only=_word_set(grammar, "tone_only"),
        role_stop=_word_set(grammar, "role_stop"),
        plain_roles=_word_set(grammar, "plain_roles"),
        scale_skip=_word_set(grammar, "scale_skip"),
        colour_nouns=colour_nouns,
        copulas=_word_set(grammar, "copulas"),
        metals=_word_set(grammar, "metals"),
        colour_join=_word_set(grammar, "colour_join"),
        no_thing=colour_nouns | _word_set(grammar, "no_thing"),
        synonyms=synonyms,
        preset_sets=sets,
    )
