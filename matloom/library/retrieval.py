"""Lexical retrieval: BM25 (``rank_bm25``) over each entry's words, with Snowball stemming
(``PyStemmer``), a synonym table in data and a bonus for whole phrases.

An entry's document is its name (twice), description, tags (twice), synonyms, preset words
("walnut", "copper") and category. A request's terms carry weights: a plain word counts 1
(1.3 in the head clause, before the first "with" or comma), an overlay word 0.35 (so that
"rusty corrugated metal" finds corrugated metal and adds rust, while "rusty metal" still finds
rusted metal), a finish word 0.6, a form noun ("plate", "sheet") 0.3, colour 0.1, scale and size
words 0.25. An entry is a candidate only when a material, object or condition word matched it
(``REASONS``): colour and finish words alone ("glossy teal") pick nothing. Synonyms
(``data/synonyms.toml``) add their expansion terms at 0.6 of the source word's weight. An entry
whose synonym or multi-word tag appears in the prompt as a phrase gains ``PHRASE_BONUS`` per
word. Scores are deterministic; ties go to the name in alphabetical order.
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

WEIGHTS = {
    "plain": 1.0,
    "head": 1.3,
    "overlay": 0.35,
    "finish": 0.6,
    "colour": 0.1,
    "scale": 0.25,
    "size": 0.25,
    "count": 0.25,
    "tone": 0.5,
    "form": 0.3,
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
#: the word rules that can be a reason to pick an entry: material, object and condition words.
#: An entry matched only by colour, finish, tone, scale or size words ("glossy teal gizmo") is
#: no candidate; with no candidate the author falls back to its generic entry.
REASONS = frozenset({"plain", "head", "overlay", "form"})
_WORD_RE = re.compile(r"[a-z0-9]+")


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
        self.names: list[str] = []
        self.category_words = words.category_words
        self.defaults = words.defaults
        self.categories: dict[str, str] = {}
        self.absorbs: dict[str, frozenset[str]] = {}
        self.name_stems: dict[str, frozenset[str]] = {}
        docs: list[list[str]] = []
        self.terms: dict[str, frozenset[str]] = {}
        self.phrases: dict[tuple[str, ...], set[str]] = {}
        for e in sorted(entries, key=lambda e: e.name):
            self.names.append(e.name)
            self.categories[e.name] = e.category
            self.absorbs[e.name] = frozenset(e.absorbs)
            self.name_stems[e.name] = frozenset(self.stems(e.name.replace("-", " ")))
            parts = [
                e.name.replace("-", " "),
                e.name.replace("-", " "),
                e.description,
                *e.tags,
                *e.tags,
                *e.synonyms,
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
        if rule is not None:
            return rule
        if req.tokens[i] in self.form_nouns:
            return "form"
        return "head" if i < req.head_end else "plain"

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
            s = self.stem(word)
            weights[s] = weights.get(s, 0.0) + w
            sources.setdefault(s, set()).add(i)
            order.append(s)
        stems = [(i, self.stem(w)) for i, w in req.words_at()]
        for n in (3, 2, 1):
            for k in range(len(stems) - n + 1):
                chunk = stems[k : k + n]
                if chunk[-1][0] - chunk[0][0] != n - 1:
                    continue
                key = tuple(s for _, s in chunk)
                if key not in self.synonyms:
                    continue
                base = max(weights.get(s, 0.25) for s in key)
                for s in self.synonyms[key]:
                    weights[s] = weights.get(s, 0.0) + SYNONYM_WEIGHT * base
                    sources.setdefault(s, set()).update(i for i, _ in chunk)
        return weights, sources, order

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
        for k, name in enumerate(self.names):
            stems = self.name_stems[name]
            if stems and stems <= present:
                scores[k] += NAME_BONUS * len(stems)
                matched.setdefault(k, set()).update(stems)
                reason.add(k)
            if self.categories[name] in hit:
                scores[k] *= CATEGORY_BOOST
            if name in self.defaults:
                scores[k] *= DEFAULT_BOOST
            if self.absorbs[name] and not self.absorbs[name] & asked:
                scores[k] *= CONDITION_PENALTY
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
