"""Lexical retrieval: BM25 (``rank_bm25``) over each entry's words, with Snowball stemming
(``PyStemmer``), a synonym table in data and a bonus for whole phrases.

An entry's document is its name (twice), description, tags (twice), synonyms, preset words
("walnut", "copper") and category. A request's terms carry weights: a plain word counts 1
(1.3 in the head clause, before the first "with" or comma), an overlay word 0.35 (so that
"rusty corrugated metal" finds corrugated metal and adds rust, while "rusty metal" still finds
rusted metal), a finish word 0.6, a form noun ("plate", "sheet") 0.3, colour 0.1, scale and size
words 0.25. A repeated word counts once, at its largest weight; so does a repeated synonym
phrase. An entry is a candidate only when a material, object or condition word matched it
(``REASONS``): colour and finish words alone ("glossy teal") pick nothing. Synonyms
(``data/synonyms.toml``) add their expansion terms at 0.6 of the source word's weight. An entry
whose synonym or multi-word tag appears in the prompt as a phrase gains ``PHRASE_BONUS`` per
word. The term of a "term: definition" request weighs 2.5 and words after the first sentence
0.75; material nouns (``[materials]``) weigh ``MATERIAL_WEIGHT`` times more, and entries with
none of the request's materials rank ``MATERIAL_PENALTY`` lower; a motif the request names
(``[motifs]``) ranks the entries that show it ``MOTIF_BOOST`` higher and the others
``MOTIF_PENALTY`` lower. Scores are deterministic; ties go to the name in alphabetical order.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import Stemmer
from rank_bm25 import BM25Okapi

from matloom.library.data import Words
from matloom.library.entry import Entry
from matloom.library.query import Request

#: the first item of a comma list ("snow over rocky ground, patchy, some grass poking through")
#: names the material; the other items describe it
LEAD_WEIGHT = 2.0
WEIGHTS = {
    "plain": 1.0,
    "head": 1.3,
    "lead": LEAD_WEIGHT,
    "overlay": 0.35,
    "finish": 0.6,
    "colour": 0.1,
    "scale": 0.25,
    "size": 0.25,
    "count": 0.25,
    "tone": 0.5,
    "form": 0.3,
    "term": 2.5,
    "later": 0.75,
    "amount": 0.0,
    "negation": 0.0,
    "percent": 0.0,
}
SYNONYM_WEIGHT = 0.6
PHRASE_BONUS = 1.5
B = 0.3
NAME_BONUS = 1.5
CATEGORY_BOOST = 1.3
DEFAULT_BOOST = 1.25
#: entries that show a condition (rusted metal, peeling paint) rank lower unless it is asked for
CONDITION_PENALTY = 0.75
#: entries in an art style (tagged "stylized", "cartoon" ...: ``[styles]`` of words.toml) rank
#: this much lower unless the request asks for a style ("painted wooden door" is no
#: hand-painted texture)
STYLE_PENALTY = 0.3
#: a material noun ("leather", "cobblestone") weighs this many times its word's weight; when the
#: request names materials, entries with none of them (nor their category) rank lower
MATERIAL_WEIGHT = 1.25
MATERIAL_PENALTY = 0.5
#: entries that show some of the request's material nouns but miss one that is no category word
#: ("grey slate floor tiles": a tile entry that is not slate)
PART_MATERIAL_PENALTY = 0.75
#: a motif the request names ("hexagonal", "circles", "camo"): entries showing it rank higher,
#: the others lower, so the motif wins over incidental words
MOTIF_BOOST = 1.35
MOTIF_PENALTY = 0.6
#: when the request names no motif, entries whose name states one rank lower ("black shiny ceramic
#: floor tiles" are plain tiles, not a checkerboard)
UNASKED_MOTIF = 0.85
#: the word rules that can be a reason to pick an entry: material, object and condition words.
#: An entry matched only by colour, finish, tone, scale or size words ("glossy teal gizmo") is
#: no candidate; with no candidate the author falls back to its generic entry.
REASONS = frozenset({"plain", "head", "lead", "overlay", "form", "term", "later"})
_WORD_RE = re.compile(r"[a-z0-9]+")


def _style_said(tokens: list[str], styles: frozenset[str]) -> bool:
    """Do ``tokens`` name an art style ("stylized", "hand painted", "hand-painted")?"""
    if any(t in styles for t in tokens):
        return True
    return any(f"{a}{b}" in styles for a, b in zip(tokens, tokens[1:], strict=False))


@dataclass(frozen=True)
class Candidate:
    """An entry with its retrieval score and the request words that matched it."""

    name: str
    score: float
    matched: tuple[str, ...] = ()


class Index:
    """The BM25 index of a set of entries (built once per library)."""

    def __init__(self, entries: Iterable[Entry], presets: dict[str, Iterable[str]], words: Words):
        self.stemmer = Stemmer.Stemmer("english")
        self.stop = words.stop_words
        self.form_nouns = words.form_nouns
        self.materials = words.materials
        self.motif_of = {w: m for m, ws in sorted(words.motifs.items()) for w in ws}
        self.motif_stems = {
            m: frozenset(self.stemmer.stemWords(sorted(ws))) for m, ws in words.motifs.items()
        }
        self.names: list[str] = []
        self.category_words = words.category_words
        self.category_stems = {self.stem(w) for ws in words.category_words.values() for w in ws}
        self.defaults = words.defaults
        self.categories: dict[str, str] = {}
        self.absorbs: dict[str, frozenset[str]] = {}
        self.styled: dict[str, bool] = {}
        self.style_words = words.styles
        self.name_stems: dict[str, frozenset[str]] = {}
        docs: list[list[str]] = []
        self.terms: dict[str, frozenset[str]] = {}
        self.phrases: dict[tuple[str, ...], set[str]] = {}
        for e in sorted(entries, key=lambda e: e.name):
            self.names.append(e.name)
            self.categories[e.name] = e.category
            self.absorbs[e.name] = frozenset(e.absorbs)
            self.styled[e.name] = any(_style_said(t.lower().split(), words.styles) for t in e.tags)
            self.name_stems[e.name] = frozenset(self.stems(e.name.replace("-", " ")))
            parts = [
                e.name.replace("-", " "),
                e.name.replace("-", " "),
                e.description,
                *e.tags,
                *e.tags,
                # each synonym word once: a word repeated over many phrasings ("laser cut
                # fabric", "cutwork fabric" ...) is no more the entry's than a tag
                " ".join(dict.fromkeys(" ".join(e.synonyms).replace("-", " ").lower().split())),
                *presets.get(e.name, ()),
                e.category,
            ]
            doc = self.stems(" ".join(parts))
            docs.append(doc)
            self.terms[e.name] = frozenset(doc)
            for phrase in (*e.synonyms, *(t for t in e.tags if " " in t), e.name.replace("-", " ")):
                key = tuple(self.stems(phrase))
                if len(key) > 1:
                    self.phrases.setdefault(key, set()).add(e.name)
        self.bm25 = BM25Okapi(docs, k1=1.2, b=B) if docs else None
        #: the motifs each entry shows (a motif word among its terms)
        self.motifs = {
            n: frozenset(m for m, st in self.motif_stems.items() if st & self.terms[n])
            for n in self.names
        }
        #: the motifs an entry's name states ("checker-tiles")
        self.named_motifs = {
            n: frozenset(m for m, st in self.motif_stems.items() if st & self.name_stems[n])
            for n in self.names
        }
        self.synonyms = {
            tuple(self.stems(k, keep_stop=True)): [s for v in vals for s in self.stems(v)]
            for k, vals in words.synonyms.items()
        }

    def stems(self, text: str, *, keep_stop: bool = False) -> list[str]:
        """Lower-case word stems of ``text`` (stop words dropped unless ``keep_stop``)."""
        words = _WORD_RE.findall(text.lower())
        if not keep_stop:
            words = [w for w in words if w not in self.stop]
        return self.stemmer.stemWords(words)

    def stem(self, word: str) -> str:
        return self.stemmer.stemWord(word)

    def rule(self, req: Request, i: int) -> str:
        """The weight rule of request token ``i`` (see ``WEIGHTS``)."""
        rule = req.used.get(i)
        if rule is not None and i not in req.lone_materials:
            return rule
        if req.tokens[i] in self.form_nouns:
            return "form"
        if i < req.term_end:
            return "term"
        if i > req.sentence_end:
            return "later"
        if i < req.head_end:
            return "lead" if req.listed else "head"
        return "plain"

    def material_words(self, req: Request) -> list[set[str]]:
        """For each material noun of the request (not a colour, overlay ...): the stems that
        carry it (its stem and its synonyms' stems)."""
        out: list[set[str]] = []
        for i, word in req.words_at():
            if word in self.materials and (i not in req.used or i in req.lone_materials):
                key = (self.stem(word),)
                out.append({key[0], *self.synonyms.get(key, ())})
        return out

    def motif_words(self, req: Request) -> set[str]:
        """The motifs the request names (a motif word that no overlay or colour took)."""
        words = [(i, w) for i, w in req.words_at() if i not in req.used]
        out = {self.motif_of[w] for _, w in words if w in self.motif_of}
        for (i, a), (j, b) in zip(words, words[1:]):
            if j == i + 1 and a + b in self.motif_of:
                out.add(self.motif_of[a + b])
        return out

    def query(self, req: Request) -> tuple[dict[str, float], dict[str, set[int]], list[str]]:
        """(weight per stem, token indices per stem, request stems in order) of a request."""
        weights: dict[str, float] = {}
        sources: dict[str, set[int]] = {}
        order: list[str] = []
        for i, word in req.words_at():
            if word in self.stop or len(word) < 2:
                continue
            rule = self.rule(req, i)
            w = WEIGHTS.get(rule, 1.0)
            if w <= 0:
                continue
            if word in self.materials and rule in REASONS and rule != "overlay":
                w *= MATERIAL_WEIGHT
            s = self.stem(word)
            weights[s] = max(weights.get(s, 0.0), w)  # a repeated word counts once
            sources.setdefault(s, set()).add(i)
            order.append(s)
        words = req.words_at()
        for (i, a), (j, b) in zip(words, words[1:]):
            joined = self.stem(a + b)  # "honey comb" -> honeycomb, "zig zag" -> zigzag
            if j == i + 1 and self.bm25 is not None and joined in self.bm25.idf:
                w = max(WEIGHTS.get(self.rule(req, k), 1.0) for k in (i, j))
                weights[joined] = max(weights.get(joined, 0.0), w)
                sources.setdefault(joined, set()).update((i, j))
                order.append(joined)
        self.add_synonyms(words, weights, sources)
        return weights, sources, order

    def add_synonyms(
        self, words: list[tuple[int, str]], weights: dict[str, float], sources: dict[str, set[int]]
    ) -> None:
        """Add the expansion terms of every synonym phrase of ``words`` to ``weights``.

        Each distinct phrase adds once, however often it is said: a synonym that expands to
        its own stem ("bricks" -> "brick") would otherwise grow its weight geometrically with
        every repeat (infinite at about 1,500).
        """
        stems = [(i, self.stem(w)) for i, w in words]
        seen: set[tuple[str, ...]] = set()
        for n in (3, 2, 1):
            for k in range(len(stems) - n + 1):
                chunk = stems[k : k + n]
                if chunk[-1][0] - chunk[0][0] != n - 1:
                    continue
                key = tuple(s for _, s in chunk)
                if key not in self.synonyms:
                    continue
                for s in self.synonyms[key]:
                    sources.setdefault(s, set()).update(i for i, _ in chunk)
                if key in seen:
                    continue
                seen.add(key)
                base = max(weights.get(s, 0.25) for s in key)
                for s in self.synonyms[key]:
                    weights[s] = weights.get(s, 0.0) + SYNONYM_WEIGHT * base

    def rank(self, req: Request) -> list[Candidate]:
        """Every entry with a positive score, best first."""
        if self.bm25 is None:
            return []
        weights, sources, order = self.query(req)
        reasons = {
            s for s, idx in sources.items() if any(self.rule(req, i) in REASONS for i in idx)
        }
        scores = np.zeros(len(self.names))
        matched: dict[int, set[str]] = {}
        reason: set[int] = set()
        for stem, w in sorted(weights.items()):
            if stem not in self.bm25.idf:
                continue
            s = self.bm25.get_scores([stem])
            scores += w * s
            for k in np.nonzero(s > 0)[0]:
                matched.setdefault(int(k), set()).add(stem)
                if stem in reasons:
                    reason.add(int(k))
        grams = {tuple(order[k : k + n]) for n in (2, 3, 4) for k in range(len(order) - n + 1)}
        position = {n: k for k, n in enumerate(self.names)}
        for gram in grams:
            for name in self.phrases.get(gram, ()):
                scores[position[name]] += PHRASE_BONUS * len(gram)
                matched.setdefault(position[name], set()).update(gram)
                reason.add(position[name])
        present = set(order)
        words_in = {w for _, w in req.words_at()}
        hit = {c for c, ws in self.category_words.items() if ws & words_in}
        asked = {m.name for m in req.overlays}
        styled = _style_said(list(req.tokens), self.style_words)
        finish_stems = {self.stem(word) for _, word in req.finishes}
        materials = self.material_words(req)
        specific = [st for st in materials if not st & self.category_stems]
        motifs = self.motif_words(req)
        motifs = {m for m in motifs if any(m in self.motifs[n] for n in self.names)}
        for k, name in enumerate(self.names):
            terms = self.terms[name]
            cat_ok = self.categories[name] in hit
            if materials and not cat_ok and not any(st & terms for st in materials):
                scores[k] *= MATERIAL_PENALTY
            elif any(not st & terms for st in specific):
                scores[k] *= PART_MATERIAL_PENALTY  # "slate floor tiles": tiles, but not slate
            for motif in motifs:
                scores[k] *= MOTIF_BOOST if motif in self.motifs[name] else MOTIF_PENALTY
            if not motifs and self.named_motifs[name]:
                scores[k] *= UNASKED_MOTIF
            stems = self.name_stems[name]
            if stems and stems <= present:
                scores[k] += NAME_BONUS * len(stems)
                matched.setdefault(k, set()).update(stems)
                reason.add(k)
            elif stems & finish_stems and k in reason:  # "brushed aluminium": brushed-metal
                scores[k] += NAME_BONUS
            if self.categories[name] in hit:
                scores[k] *= CATEGORY_BOOST
            if name in self.defaults:
                scores[k] *= DEFAULT_BOOST
            if self.absorbs[name] and not self.absorbs[name] & asked:
                scores[k] *= CONDITION_PENALTY
            if self.styled[name] and not styled:
                scores[k] *= STYLE_PENALTY
        out = [
            Candidate(self.names[k], round(float(scores[k]), 4), tuple(sorted(matched.get(k, ()))))
            for k in range(len(self.names))
            if scores[k] > 0 and k in reason
        ]
        out.sort(key=lambda c: (-c.score, c.name))
        return out

    def understood(self, req: Request, name: str) -> set[int]:
        """Token indices whose stem (or synonym expansion) is a term of entry ``name``."""
        terms = self.terms.get(name, frozenset())
        _, sources, _ = self.query(req)
        out: set[int] = set()
        for stem, idx in sources.items():
            if stem in terms:
                out |= idx
        return out
