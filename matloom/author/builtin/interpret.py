"""Prompt interpretation: turn a free-text material request into structured, explainable facts.

The interpreter knows nothing about recipes. It finds colours (with tone modifiers and the role a
colour plays, e.g. "background" or "stripes"), patterns, finishes, condition modifiers (with an
amount, a colour and a size when stated), scale words, explicit sizes, counts and percentages.
Every rule records which tokens it consumed, so the author can report which words it did not
understand. Long descriptive prompts are handled token by token, so sentence length does not
matter; negations ("no", "not", "without") switch off the next few words.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from matloom.author.builtin import colours as C
from matloom.author.builtin import words as W

_TOKEN_RE = re.compile(r"\d+/\d+|\d+(?:\.\d+)?|[a-z]+(?:'[a-z]+)?|[\",.;:!?()/&%]")
_CLAUSE_END = frozenset({".", ";", ":", "!", "?", "("})
_LIST_JOIN = frozenset({",", "and", "or", "/", "&", "with"})
_CONDITION_NOUNS = frozenset(
    {"holes", "hole", "cracks", "crack", "gashes", "scratches", "puddles", "chips", "flakes"}
)
_CONDITION_TONES = frozenset({"faded", "dirty", "dusty", "burnt", "washed", "earthy"})
_WEAK_CONDITIONS = frozenset({"old", "ancient", "antique", "vintage", "aged", "used"})
_COLOUR_SUFFIX = frozenset({"color", "colour", "colored", "coloured", "tone", "toned", "hue"})

#: colour names that are more often material nouns; they count as colours only in colour context.
MATERIALISH: frozenset[str] = frozenset(
    """slate stone sand brick rust copper bronze gold golden silver brass steel jade amber moss
    pine walnut mahogany cherry ebony denim ice snow coral honey straw linen olive charcoal
    terracotta malachite onyx pearl jet ash smoke forest army hunter royal baby powder sky wine
    candy hot petrol hazel camel cognac chestnut grape lime emerald sapphire ruby cream butter
    bone stone caramel chocolate coffee mocha sepia cinnamon avocado pistachio mint sage orchid
    plum eggplant aubergine lemon peach apricot tangerine salmon teal rose ivory khaki tan
    sienna umber ochre saffron verdigris midnight graphite pewter denim oatmeal fawn""".split()
) - frozenset({"tan", "teal", "khaki", "ivory", "rose", "salmon"})

_ROLE_NOUNS: dict[str, str] = {
    "background": "base",
    "base": "base",
    "ground": "base",
    "backing": "base",
    "body": "base",
    "field": "base",
    "main": "base",
    "overall": "base",
    "fabric": "base",
    "grout": "grout",
    "mortar": "grout",
    "joints": "grout",
    "joint": "grout",
    "stripe": "accent",
    "stripes": "accent",
    "line": "accent",
    "lines": "accent",
    "dots": "accent",
    "dot": "accent",
    "spots": "accent",
    "flowers": "accent",
    "diamonds": "accent",
    "pattern": "accent",
    "print": "accent",
    "accent": "accent",
    "accents": "accent",
    "leaves": "accent",
    "trim": "accent",
    "motif": "accent",
    "veins": "accent",
    "vein": "accent",
    "checks": "accent",
    "splattered": "accent",
    "stitching": "accent",
    "thread": "accent",
    "threads": "accent",
    "embellishment": "accent",
    "squares": "accent",
    "frame": "frame",
    "mixed": "none",
}


@dataclass(frozen=True)
class Token:
    """One lower-case token of the prompt with its position."""

    text: str
    index: int

    @property
    def is_word(self) -> bool:
        return self.text[:1].isalpha()


@dataclass
class ColourMention:
    """A colour the prompt names, with the words it came from and the role it seems to play."""

    rgb: C.RGB
    words: str
    index: int
    role: str | None = None


@dataclass
class Condition:
    """A condition modifier (rusty, mossy, cracked ...) with amount, size factor and colour."""

    kind: str
    word: str
    amount: float = 0.5
    scale: float = 1.0
    colour: C.RGB | None = None


@dataclass(frozen=True)
class Size:
    """An explicit size ("10 cm tiles"): metres and the noun it measures (may be empty)."""

    metres: float
    noun: str


@dataclass(frozen=True)
class Count:
    """A stated count ("3 yarns", "eight planks")."""

    value: int
    noun: str


@dataclass
class Interpretation:
    """Everything the interpreter recognised in one prompt."""

    prompt: str
    tokens: list[Token]
    stems: list[str]
    colours: list[ColourMention] = field(default_factory=list)
    patterns: list[str] = field(default_factory=list)
    head_patterns: set[str] = field(default_factory=set)
    finishes: list[str] = field(default_factory=list)
    conditions: list[Condition] = field(default_factory=list)
    scale: float = 1.0
    scale_words: list[str] = field(default_factory=list)
    sizes: list[Size] = field(default_factory=list)
    counts: list[Count] = field(default_factory=list)
    percents: list[float] = field(default_factory=list)
    negated: set[int] = field(default_factory=set)
    colour_tokens: set[int] = field(default_factory=set)
    tones: list[tuple[str, str]] = field(default_factory=list)
    consumed: set[int] = field(default_factory=set)
    head_end: int = 0

    def words(self) -> set[str]:
        """All word tokens and their stems (for tag matching)."""
        out = {t.text for t in self.tokens if t.is_word and t.index not in self.negated}
        out |= {s for i, s in enumerate(self.stems) if i not in self.negated and s}
        return out

    def unknown_words(self) -> list[str]:
        """Content words no rule consumed, in prompt order, without duplicates."""
        seen: list[str] = []
        for t in self.tokens:
            if (
                t.is_word
                and len(t.text) > 2
                and t.index not in self.consumed
                and t.text not in W.STOP_WORDS
                and t.index not in self.negated
                and t.text not in seen
            ):
                seen.append(t.text)
        return seen


def stem(word: str) -> str:
    """A light plural stemmer: tiles -> tile, leaves -> leaf, patches -> patch, glass -> glass."""
    if len(word) <= 3 or not word.isalpha():
        return word
    if word.endswith("ies") and len(word) > 4:
        return word[:-3] + "y"
    if word.endswith("ves") and word not in {"waves", "grooves", "sleeves"}:
        return word[:-3] + "f"
    if word.endswith(("ches", "shes", "xes", "sses", "zes")):
        return word[:-2]
    if word.endswith("s") and not word.endswith(("ss", "us", "is", "ous")):
        return word[:-1]
    return word


def tokenize(prompt: str) -> list[Token]:
    """Lower-case tokens: words (hyphens split), numbers, fractions and punctuation."""
    text = prompt.lower().replace("’", "'").replace("-", " ")
    return [Token(m.group(0), i) for i, m in enumerate(_TOKEN_RE.finditer(text))]


def _number(tok: str) -> float | None:
    if re.fullmatch(r"\d+/\d+", tok):
        num, den = tok.split("/")
        return int(num) / int(den) if int(den) else None
    if re.fullmatch(r"\d+(?:\.\d+)?", tok):
        return float(tok)
    if tok in W.NUMBER_WORDS:
        return float(W.NUMBER_WORDS[tok])
    return None


class _Reader:
    """Runs the recognisers over a token list and fills an :class:`Interpretation`."""

    def __init__(self, prompt: str) -> None:
        toks = tokenize(prompt)
        self.t = [tok.text for tok in toks]
        self.out = Interpretation(prompt=prompt, tokens=toks, stems=[stem(x) for x in self.t])

    # ------------------------------------------------------------------ helpers
    def at(self, i: int) -> str:
        return self.t[i] if 0 <= i < len(self.t) else ""

    def take(self, *idx: int) -> None:
        self.out.consumed.update(idx)

    def colour_word_at(self, i: int) -> bool:
        w = self.at(i)
        return (w in C.NAMED_COLOURS or w in C.ISH_FORMS) and w not in MATERIALISH

    # ------------------------------------------------------------------ passes
    def run(self) -> Interpretation:
        self.find_head()
        self.find_negations()
        self.find_colours()
        self.find_patterns_and_finishes()
        self.find_conditions()
        self.find_scale()
        self.find_numbers()
        self.find_tones()
        return self.out

    def find_head(self) -> None:
        """The head clause: up to the first ':' / '.' / ' with ' - it names the material."""
        end = len(self.t)
        for i, w in enumerate(self.t):
            if w in {":", ".", ";", "(", "with", "featuring", ","} and i > 0:
                end = i
                break
        self.out.head_end = end

    def find_negations(self) -> None:
        for i, w in enumerate(self.t):
            if w in W.NEGATIONS:
                self.take(i)
                for j in range(i + 1, min(i + 4, len(self.t))):
                    if self.t[j] in _CLAUSE_END or self.t[j] in {",", "but", "and"}:
                        break
                    self.out.negated.add(j)
                    if self.t[j] in {"texture", "textured", "pattern"}:
                        self.out.finishes.append("smooth")

    def find_colours(self) -> None:
        i = 0
        found: dict[str, ColourMention] = {}
        while i < len(self.t):
            span = self.colour_at(i)
            if span is None:
                i += 1
                continue
            start, end, rgb, words = span
            if start in self.out.negated:
                i = end
                continue
            role = self.role_near(start, end)
            self.take(*range(start, end))
            self.out.colour_tokens.update(range(start, end))
            alternative = self.at(start - 1) in {"or", "like"} or (
                self.at(start - 1) == "to" and self.at(start - 2) == "similar"
            )
            if alternative and self.out.colours:
                prev = self.out.colours[-1]
                prev.rgb = C.mix(prev.rgb, rgb, 0.5)
                prev.words = f"{prev.words} ~ {words}"
                i = end
                continue
            if words in found:
                if role and not found[words].role:
                    found[words].role = role
            else:
                mention = ColourMention(rgb, words, start, role)
                found[words] = mention
                self.out.colours.append(mention)
            i = end

    def colour_at(self, i: int) -> tuple[int, int, C.RGB, str] | None:
        """Match a colour (with modifiers) starting at token ``i``: (start, end, rgb, words)."""
        for n in (3, 2):
            phrase = " ".join(self.t[i : i + n])
            if len(self.t[i : i + n]) == n and phrase in C.PHRASE_COLOURS:
                return i, i + n, C.PHRASE_COLOURS[phrase], phrase
        mods: list[str] = []
        j = i
        while self.at(j) in C.TONE_MODIFIERS and len(mods) < 2:
            mods.append(self.at(j))
            j += 1
        tonal = [m for m in mods if m not in _CONDITION_TONES]
        base = self.base_colour_at(j, modified=bool(tonal))
        if base is None:
            return None
        end, rgb, name = base
        for m in reversed(mods):
            rgb = C.apply_tone(rgb, m)
        words = " ".join(mods + [name])
        # "red/brown", "blue-green" style blends: a second colour right after a slash
        if self.at(end) == "/" and self.base_colour_at(end + 1) is not None:
            end2, rgb2, name2 = self.base_colour_at(end + 1)  # type: ignore[misc]
            return i, end2, C.mix(rgb, rgb2, 0.5), f"{words}/{name2}"
        return i, end, rgb, words

    def base_colour_at(self, j: int, modified: bool = False) -> tuple[int, C.RGB, str] | None:
        for n in (3, 2):
            phrase = " ".join(self.t[j : j + n])
            if len(self.t[j : j + n]) == n and phrase in C.PHRASE_COLOURS:
                return j + n, C.PHRASE_COLOURS[phrase], phrase
        w = self.at(j)
        if w in C.ISH_FORMS and self.colour_word_at(j + 1):
            nxt = self.at(j + 1)
            rgb = C.mix(C.NAMED_COLOURS[C.ISH_FORMS[w]], C.NAMED_COLOURS[nxt], 0.65)
            return j + 2, rgb, f"{w} {nxt}"
        rgb = C.lookup(w) if w not in C.TONE_MODIFIERS or w in C.NAMED_COLOURS else None
        if rgb is None and w.endswith("s") and C.lookup(w[:-1]) is not None:
            # plural colour nouns in colour lists: "blues, greens, and purples", "golds, tans"
            near = [self.at(k) for k in (j - 2, j + 2)]
            listed = any(
                C.lookup(x) is not None or C.lookup(x[:-1] or "-") is not None for x in near if x
            )
            if listed and (self.at(j - 1) in _LIST_JOIN or self.at(j + 1) in _LIST_JOIN):
                return j + 1, C.lookup(w[:-1]), w[:-1]  # type: ignore[return-value]
        if rgb is None or w in {"dark", "light", "pale", "deep"}:
            return None
        if w in MATERIALISH and not modified and not self.colour_context(j):
            return None
        return j + 1, rgb, w

    def colour_context(self, j: int) -> bool:
        """Is the material-ish word at ``j`` used as a colour (lists, 'X color', 'X stains')?"""
        nxt, prev = self.at(j + 1), self.at(j - 1)
        if nxt in _COLOUR_SUFFIX or nxt in W.CONDITION_CARRIERS:
            return True
        if self.colour_word_at(j + 1):
            return True
        if prev in _LIST_JOIN and (self.colour_word_at(j - 2) or self.at(j - 2) in MATERIALISH):
            return True
        if nxt in {",", "and", "or", "/"} and self.colour_word_at(j + 2):
            return True
        if nxt == "in" and self.at(j + 2) in _COLOUR_SUFFIX:
            return True
        back = {self.at(k) for k in range(j - 4, j)}
        return prev in {"is", "are"} and bool(back & {"color", "colour", "colors", "colours"})

    def role_near(self, start: int, end: int) -> str | None:
        for k in range(end, min(end + 4, len(self.t))):
            w = self.t[k]
            if w in _CLAUSE_END or w == ",":
                break
            if w in _ROLE_NOUNS:
                return None if _ROLE_NOUNS[w] == "none" else _ROLE_NOUNS[w]
        for k in range(start - 1, max(start - 7, -1), -1):
            w = self.t[k]
            if w in _CLAUSE_END or w == ",":
                break
            if w in _ROLE_NOUNS:
                return None if _ROLE_NOUNS[w] == "none" else _ROLE_NOUNS[w]
        return None

    def find_patterns_and_finishes(self) -> None:
        for i, w in enumerate(self.t):
            if i in self.out.negated:
                continue
            joined = w + self.at(i + 1)
            if joined in W.PATTERN_WORDS and w not in W.PATTERN_WORDS:
                w = joined
                self.take(i + 1)
            if w in W.PATTERN_WORDS:
                key = W.PATTERN_WORDS[w]
                if key == "dots" and self.at(i + 1) in {"hole", "holes"}:
                    key = "perforated"
                if key not in self.out.patterns:
                    self.out.patterns.append(key)
                if i < self.out.head_end:
                    self.out.head_patterns.add(key)
                self.take(i)
            if w in W.FINISH_WORDS:
                key = W.FINISH_WORDS[w]
                if key not in self.out.finishes:
                    self.out.finishes.append(key)
                self.take(i)

    def find_conditions(self) -> None:
        for i, w in enumerate(self.t):
            if i in self.out.negated or i in self.out.consumed:
                continue
            joined = f"{w}-{self.at(i + 1)}"
            kind = W.CONDITION_WORDS.get(joined) or W.CONDITION_WORDS.get(w)
            takes_colour = w in W.CONDITION_CARRIERS or kind == "stained"
            if kind is None and not takes_colour:
                continue
            colour = self.colour_before(i) if takes_colour else None
            if kind is None and colour is not None:
                kind = "stained"
            if kind is None:
                continue
            if kind == "holes" and "perforated" in self.out.patterns:
                continue
            if w in _WEAK_CONDITIONS and i >= self.out.head_end:
                continue
            amount, scale = self.amount_before(i, kind)
            self.take(i)
            existing = [c for c in self.out.conditions if c.kind == kind]
            if existing:
                cond = existing[0]
                cond.amount = max(cond.amount, amount)
                cond.colour = cond.colour or colour
                cond.scale = max(cond.scale, scale)
                continue
            self.out.conditions.append(Condition(kind, w, amount, scale, colour))

    def colour_before(self, i: int) -> C.RGB | None:
        for m in reversed(self.out.colours):
            if i - 3 <= m.index < i:
                m.role = "condition"
                return m.rgb
        for k in (i - 1, i - 2):
            w = self.at(k)
            if w in C.NAMED_COLOURS and self.at(i) in W.CONDITION_CARRIERS | {"stained"}:
                self.take(k)
                return C.NAMED_COLOURS[w]
        return None

    def amount_before(self, i: int, kind: str) -> tuple[float, float]:
        """Amount words before a condition; scale words only before condition *nouns*
        ("huge stains"), since "large weathered bricks" means large bricks."""
        amount = 0.35 if kind == "weathered" and self.at(i) == "old" else 0.5
        scale = 1.0
        is_noun = self.at(i) in W.CONDITION_CARRIERS | _CONDITION_NOUNS
        for k in range(max(0, i - 3), i):
            w = self.t[k]
            if w in W.AMOUNT_WORDS and not (w in W.SCALE_WORDS and not is_noun):
                amount = W.AMOUNT_WORDS[w]
                self.take(k)
            if w in W.SCALE_WORDS and is_noun:
                scale = W.SCALE_WORDS[w]
                self.take(k)
        return amount, scale

    def find_tones(self) -> None:
        """Tone words before a non-colour noun ("pale mortar", "dark wood") shade that part."""
        for i, w in enumerate(self.t):
            if w in C.TONE_MODIFIERS and i not in self.out.consumed:
                nxt = self.at(i + 1)
                if nxt.isalpha() and nxt not in C.TONE_MODIFIERS and nxt not in W.STOP_WORDS:
                    self.out.tones.append((w, stem(nxt)))
                    self.take(i)

    def find_scale(self) -> None:
        factors: list[float] = []
        for i, w in enumerate(self.t):
            if w not in W.SCALE_WORDS or i in self.out.negated or i in self.out.consumed:
                continue
            target = next(
                (
                    self.t[k]
                    for k in range(i + 1, min(i + 4, len(self.t)))
                    if self.t[k].isalpha() and self.t[k] not in W.SCALE_WORDS
                ),
                "",
            )
            if target in {"", "shirt", "dress", "weight", "weighted"} or target in W.STOP_WORDS:
                continue
            factors.append(W.SCALE_WORDS[w])
            self.out.scale_words.append(w)
            self.take(i)
        if factors:
            prod = 1.0
            for f in factors:
                prod *= f
            self.out.scale = prod ** (1.0 / len(factors)) if len(factors) > 1 else prod

    def find_numbers(self) -> None:
        for i, w in enumerate(self.t):
            value = _number(w)
            if value is None or i in self.out.negated:
                continue
            unit = self.at(i + 1)
            if unit in {"%", "percent"}:
                self.out.percents.append(value / 100.0)
                self.take(i, i + 1)
            elif unit in W.UNITS_M:
                noun = self.noun_near(i + 2, i - 1)
                self.out.sizes.append(Size(value * W.UNITS_M[unit], noun))
                self.take(i, i + 1)
            elif value == int(value) and 1 <= value <= 64:
                noun = self.noun_after(i + 1)
                if noun:
                    self.out.counts.append(Count(int(value), noun))
                    self.take(i)

    def noun_after(self, k: int) -> str:
        """The counted noun: the first plural word within three tokens, else the first word."""
        words = [
            self.t[j]
            for j in range(k, min(k + 3, len(self.t)))
            if self.t[j].isalpha() and self.t[j] not in W.STOP_WORDS and len(self.t[j]) > 2
        ]
        plural = [w for w in words if stem(w) != w]
        return stem(plural[0]) if plural else (stem(words[0]) if words else "")

    def noun_near(self, after: int, before: int) -> str:
        noun = self.noun_after(after)
        if noun:
            return noun
        for j in range(before, max(before - 4, -1), -1):
            if self.t[j].isalpha() and self.t[j] not in W.STOP_WORDS:
                return stem(self.t[j])
        return ""


def interpret(prompt: str) -> Interpretation:
    """Interpret ``prompt`` (any length, any wording); never raises."""
    return _Reader(prompt).run()
