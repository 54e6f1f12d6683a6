"""Reading a request: what the words of a prompt ask for, before any entry is chosen.

:func:`read` tokenises the prompt and finds negations, colours (with tone modifiers and the
role a nearby noun gives them: "white grout", "gold veins"), finish words, overlay words
("mossy", "rusty", with an amount and an optional colour), scale words, explicit sizes
("30 cm tiles"), counts ("8 planks"), percentages and tone words before other nouns ("dark
wood"). Colour names that are usually materials ("copper", "charcoal") count as colours in
colour context ("in charcoal", "the colour is silver", "gold velvet"); a scale word before an
overlay sizes the overlay ("small cracks"). Every rule records the tokens it used, so the
author can report the words nothing used. The reader's grammar words (clause ends, list joins,
colour nouns ...) are data: ``[grammar]`` of ``data/words.toml``.

The :class:`Request` is a frozen value: the passes after :func:`read` annotate it, they never
change it. Retrieval then reads the remaining words (see :mod:`matloom.library.retrieval`).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence, Set
from dataclasses import dataclass, field, fields, replace
from types import MappingProxyType

from matloom.library import colour as C
from matloom.library.data import Words

_TOKEN_RE = re.compile(r"\d+/\d+|\d+(?:\.\d+)?|[a-z]+(?:'[a-z]+)?|[\",.;:!?()/&%]")
#: the longest head term a "term: definition" request may have
_TERM_MAX = 5


@dataclass(frozen=True)
class ColourMention:
    """A colour the prompt names, the words it came from and the role a nearby noun gives it."""

    rgb: C.RGB
    words: str
    index: int
    role: str | None = None
    #: the colour slot it must go to (the author's fit pass sets it for the colour of an overlay
    #: the entry already shows: "orange painted metal" colours the entry's paint)
    slot: str | None = None


#: The least size (metres) at which "tile" after it is the repeat: floor tiles are smaller.
_REPEAT_MIN_M = 1.0
#: a compound colour ("blue grey") is this far from its first word toward its head
COMPOUND_HEAD = 0.65
#: a compound's word under this saturation is a grey or a brown that takes any tint
COMPOUND_NEUTRAL = 0.35
#: two saturated basic colours form one colour only this close in hue ("yellow green", "blue green")
COMPOUND_HUES = 105.0


@dataclass(frozen=True)
class OverlayMention:
    """A request for an overlay ("mossy"): its name, the word, an amount and a colour."""

    name: str
    word: str
    index: int
    amount: float = 0.5
    colour: C.RGB | None = None
    #: the token index of the ColourMention that gave ``colour`` ("orange" in "orange painted")
    colour_at: int | None = None
    #: feature-size factor of the overlay itself ("small cracks" 0.65, "hairline cracks" 0.45)
    scale: float = 1.0
    #: its patches drawn as streaks running down ("rust streaks", "streaked with grime")
    streaks: bool = False


@dataclass(frozen=True)
class Size:
    """An explicit size ("30 cm tiles"): metres and the noun it measures (may be empty)."""

    metres: float
    noun: str
    words: str
    #: the extent the whole texture covers ("2x2m", "a 4 m texture": a metre or more said as
    #: an area or of a repeat word), not the size of one of its features
    extent: bool = False


@dataclass(frozen=True)
class Count:
    """A stated count ("8 planks")."""

    value: int
    noun: str


def _words_at(tokens: Sequence[str], negated: Set[int]) -> list[tuple[int, str]]:
    return [(i, t) for i, t in enumerate(tokens) if t[:1].isalpha() and i not in negated]


@dataclass(frozen=True)
class Request:
    """Everything :func:`read` recognised in one prompt; ``used`` maps token index -> rule."""

    prompt: str
    tokens: tuple[str, ...]
    head_end: int = 0
    #: end of the term of a "term: definition" request (0 when there is none)
    term_end: int = 0
    #: end of the first sentence (later sentences weigh less in retrieval)
    sentence_end: int = 0
    #: overlay words that are material nouns when the request names no other material ("fresh
    #: powder snow", "green moss"): they name the material, not an overlay on another one
    lone_materials: frozenset[int] = frozenset()
    negated: frozenset[int] = frozenset()
    colours: tuple[ColourMention, ...] = ()
    finishes: tuple[tuple[str, str], ...] = ()
    overlays: tuple[OverlayMention, ...] = ()
    scale: float = 1.0
    scale_words: tuple[str, ...] = ()
    sizes: tuple[Size, ...] = ()
    counts: tuple[Count, ...] = ()
    percents: tuple[float, ...] = ()
    tones: tuple[tuple[str, str, int], ...] = ()
    used: Mapping[int, str] = field(default_factory=lambda: MappingProxyType({}))

    def words_at(self) -> list[tuple[int, str]]:
        """(index, word) of every non-negated word token."""
        return _words_at(self.tokens, self.negated)

    @property
    def listed(self) -> bool:
        """Is the request a comma list whose first item names the material ("snow over rocky
        ground, patchy, some grass poking through, 4x4m"), as game artists write? Two commas
        or more, the first one ending the head clause, and one sentence."""
        t = self.tokens
        head_is_item = 0 < self.head_end < len(t) and t[self.head_end] == ","
        return head_is_item and t.count(",") >= 2 and self.sentence_end >= len(t) - 1


@dataclass
class _Draft:
    """The request while :class:`_Reader` fills it in (frozen into a :class:`Request`)."""

    prompt: str
    tokens: list[str]
    head_end: int = 0
    term_end: int = 0
    sentence_end: int = 0
    lone_materials: set[int] = field(default_factory=set)
    negated: set[int] = field(default_factory=set)
    colours: list[ColourMention] = field(default_factory=list)
    finishes: list[tuple[str, str]] = field(default_factory=list)
    overlays: list[OverlayMention] = field(default_factory=list)
    scale: float = 1.0
    scale_words: list[str] = field(default_factory=list)
    sizes: list[Size] = field(default_factory=list)
    counts: list[Count] = field(default_factory=list)
    percents: list[float] = field(default_factory=list)
    tones: list[tuple[str, str, int]] = field(default_factory=list)
    used: dict[int, str] = field(default_factory=dict)

    def words_at(self) -> list[tuple[int, str]]:
        return _words_at(self.tokens, self.negated)

    def freeze(self) -> Request:
        return Request(**{f.name: _frozen(getattr(self, f.name)) for f in fields(self)})


def _frozen(value: object) -> object:
    if isinstance(value, list):
        return tuple(value)
    if isinstance(value, set):
        return frozenset(value)
    if isinstance(value, dict):
        return MappingProxyType(dict(value))
    return value


def tokenize(prompt: str) -> list[str]:
    """Lower-case tokens: words (hyphens split), numbers, fractions and punctuation."""
    text = prompt.lower().replace("\u2019", "'").replace("-", " ")
    return [m.group(0) for m in _TOKEN_RE.finditer(text)]


def plural_stem(word: str) -> str:
    """A light plural stemmer for nouns: tiles -> tile, leaves -> leaf, patches -> patch."""
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


class _Reader:
    def __init__(self, prompt: str, words: Words, triggers: dict[str, str], weak: set[str]):
        self.w = words
        self.triggers = triggers
        self.weak = weak
        self.t = tokenize(prompt)
        self.out = _Draft(prompt=prompt, tokens=self.t)

    def at(self, i: int) -> str:
        return self.t[i] if 0 <= i < len(self.t) else ""

    def use(self, rule: str, *idx: int) -> None:
        for i in idx:
            self.out.used.setdefault(i, rule)

    def free(self, i: int) -> bool:
        return i not in self.out.used and i not in self.out.negated

    def run(self) -> Request:
        end = next((i for i, w in enumerate(self.t) if w in self.w.head_end and i > 0), len(self.t))
        self.out.head_end = end
        if self.at(end) == ":" and end <= _TERM_MAX:
            self.out.term_end = end
        self.out.sentence_end = next(
            (i for i, w in enumerate(self.t) if w in {".", "!", "?"} and i > 0), len(self.t)
        )
        self.negations()
        self.colours()
        self.overlays()
        self.finishes()
        self.scale()
        self.numbers()
        self.tones()
        self.lone_materials()
        return self.out.freeze()

    def is_material(self, word: str) -> bool:
        """Is ``word`` (or its singular) a material noun ("rocks", "tiles")?"""
        return word in self.w.materials or plural_stem(word) in self.w.materials

    def lone_materials(self) -> None:
        used, words = self.out.used, self.out.words_at()
        overlay = [i for i, w in words if used.get(i) == "overlay" and self.is_material(w)]
        others = any(self.is_material(w) and used.get(j) != "overlay" for j, w in words)
        if not others:
            self.out.lone_materials = set(overlay)

    # ------------------------------------------------------------------ negations
    def negations(self) -> None:
        for i, w in enumerate(self.t):
            if w not in self.w.negations:
                continue
            self.use("negation", i)
            for j in range(i + 1, min(i + 4, len(self.t))):
                if self.t[j] in self.w.clause_end or self.t[j] in {",", "but", "and"}:
                    break
                self.out.negated.add(j)

    # ------------------------------------------------------------------ colours
    def colour_word_at(self, i: int) -> bool:
        w = self.at(i)
        return (w in self.w.named or w in self.w.ish) and w not in self.w.materialish

    def colours(self) -> None:
        i = 0
        colours = self.out.colours
        found: dict[str, int] = {}  # words -> position in ``colours``
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
            self.use("colour", *range(start, end))
            alternative = self.at(start - 1) in {"or", "like"}
            if alternative and colours:
                prev = colours[-1]
                colours[-1] = replace(
                    prev, rgb=C.mix(prev.rgb, rgb, 0.5), words=f"{prev.words} ~ {words}"
                )
            elif words in found:
                k = found[words]
                colours[k] = replace(colours[k], role=colours[k].role or role)
            else:
                found[words] = len(colours)
                colours.append(ColourMention(rgb, words, start, role))
            i = end

    def colour_at(self, i: int) -> tuple[int, int, C.RGB, str] | None:
        for n in (3, 2):
            phrase = " ".join(self.t[i : i + n])
            if len(self.t[i : i + n]) == n and phrase in self.w.phrases:
                return i, i + n, self.w.phrases[phrase], phrase
        mods: list[str] = []
        j = i
        strength = 1.0
        if self.at(j) in self.w.intensity and self.at(j + 1) in self.w.tones:
            strength = self.w.intensity[self.at(j)]
            mods.append(self.at(j))
            j += 1
        while self.at(j) in self.w.tones and len(mods) < 3:
            mods.append(self.at(j))
            j += 1
        tonal = [m for m in mods if m not in self.w.condition_tones]
        base = self.base_colour_at(j, modified=bool(tonal))
        if base is None:
            return None
        end, rgb, name = base
        if self.compound(name, j, end):
            head = self.at(end)  # "blue grey", "blue-grey": a grey leaning to blue
            rgb, name, end = (
                C.mix(rgb, self.w.named[head], COMPOUND_HEAD),
                f"{name} {head}",
                end + 1,
            )
        for m in reversed(mods):
            if m in self.w.tones:
                light, sat = self.w.tones[m]
                tone = (1 + (light - 1) * strength, 1 + (sat - 1) * strength)
                rgb = C.apply_tone(rgb, m, tone)
        if self.same_colour(name, self.at(end)):
            name, end = f"{name} {self.at(end)}", end + 1  # "cornflower blue": one colour
        words = " ".join([*mods, name])
        if self.at(end) == "/" and self.base_colour_at(end + 1) is not None:
            end2, rgb2, name2 = self.base_colour_at(end + 1)  # type: ignore[misc]
            return i, end2, C.mix(rgb, rgb2, 0.5), f"{words}/{name2}"
        return i, end, rgb, words

    def base_colour_at(self, j: int, modified: bool = False) -> tuple[int, C.RGB, str] | None:
        for n in (3, 2):
            phrase = " ".join(self.t[j : j + n])
            if len(self.t[j : j + n]) == n and phrase in self.w.phrases:
                return j + n, self.w.phrases[phrase], phrase
        w = self.at(j)
        if w in self.w.ish and self.colour_word_at(j + 1):
            nxt = self.at(j + 1)  # a colour, an -ish one or a plural ("reddish browns")
            rgb = C.mix(self.w.named[self.w.ish[w]], self.w.named[self.w.ish.get(nxt, nxt)], 0.65)
            return j + 2, rgb, f"{w} {nxt}"
        if w in self.w.tones and w not in self.w.named:
            return None
        rgb = self.w.colour(w)
        if rgb is None and w.endswith("s") and self.w.colour(w[:-1]) is not None:
            near = [self.at(k) for k in (j - 2, j + 2)]
            listed = any(self.w.colour(x) or self.w.colour(x[:-1] or "-") for x in near if x)
            join = self.w.list_join
            if listed and (self.at(j - 1) in join or self.at(j + 1) in join):
                return j + 1, self.w.colour(w[:-1]), w[:-1]  # type: ignore[return-value]
        if rgb is None or w in self.w.tone_only:
            return None
        if w in self.w.materialish and not modified and not self.colour_context(j):
            return None
        return j + 1, rgb, w

    def same_colour(self, name: str, nxt: str) -> bool:
        """Is ``nxt`` a basic colour word that only names the family of the specific colour
        ``name`` ("cornflower blue", "pearl white"), not a second colour ("gold black")?"""
        families = self.w.families
        if name in families or nxt not in families or nxt == name:
            return False
        a, b = self.w.colour(name), self.w.colour(nxt)
        if a is None or b is None:
            return False
        if C.saturation(b) < 0.15:
            return C.saturation(a) < 0.25 and abs(C.luminance(a) - C.luminance(b)) < 0.35
        return C.saturation(a) >= 0.15 and C.hue_distance(a, b) <= 40

    def compound(self, name: str, start: int, end: int) -> bool:
        """Do the basic colour ``name`` and the basic colour word at ``end`` name one colour
        ("blue grey", "grey-green", "red brown", "yellow green"), the second its head? Not
        black or white ("black white" is two), not hues far apart ("red blue"), and not the
        start of a list ("red green and blue", "red green blue yellow")."""
        nxt = self.at(end)
        if self.colour_word_at(start - 1) or self.colour_word_at(end + 1):
            return False
        basic = self.w.families
        if name not in basic or nxt not in basic or nxt == name or {name, nxt} & self.w.contrasting:
            return False
        if self.at(end + 1) in self.w.list_join and self.colour_word_at(end + 2):
            return False
        a, b = self.w.named[name], self.w.named[nxt]
        if min(C.saturation(a), C.saturation(b)) < COMPOUND_NEUTRAL:
            return True  # a grey or a brown takes a tint
        return C.hue_distance(a, b) <= COMPOUND_HUES

    def colour_context(self, j: int) -> bool:
        """Is the material-ish word at ``j`` used as a colour ("slate grey", "copper colour")?"""
        w = self.w
        nxt, prev = self.at(j + 1), self.at(j - 1)
        if f"{self.at(j)} {nxt}" in self.triggers:
            return False  # "oil spill", "oil stains": a condition's own phrase
        if nxt in w.colour_suffix or self.colour_word_at(j + 1):
            return True
        if w.roles.get(nxt, "none") != "none" and nxt not in w.plain_roles:
            return True
        if nxt in w.carriers or (nxt in self.triggers and nxt not in w.materials):
            return True
        if prev in w.list_join and (self.colour_word_at(j - 2) or self.at(j - 2) in w.materialish):
            return True
        if nxt in {",", "and", "or", "/"} and self.colour_word_at(j + 2):
            return True
        word = self.at(j)
        if word in w.metal_colours and nxt in w.materials and nxt not in w.metals:
            return True  # "gold velvet", "silver fabric": a metal's colour on another material
        if prev == "in" and (word in w.metal_colours or word not in w.materials):
            return True  # "in charcoal and cream", "fish scales in copper"; not "in slate"
        if prev in w.colour_suffix or prev in w.colour_nouns:
            return True  # "coloured silver", "shade gold"
        if prev == ":" and self.at(j - 2) in w.colour_nouns:
            return True  # "colour: gold"
        if prev == "of" and self.at(j - 2) in w.colour_nouns:
            return True  # "a shade of gold"
        if prev in w.copulas:  # "the color of it is silver"
            for k in range(j - 2, max(j - 8, -1), -1):
                if self.at(k) in w.clause_end or self.at(k) == ",":
                    break
                if self.at(k) in w.colour_nouns:
                    return True
        return nxt == "in" and self.at(j + 2) in w.colour_suffix

    def role_near(self, start: int, end: int) -> str | None:
        k = end  # the forward window is 4 words, not counting a list of colours after this one
        while k < len(self.t) and k < end + 4:
            if k == end and self.t[k] in {"and", "or", ","} and self.colour_word_at(k + 1):
                end, k = end + 2, k + 2  # "black and gray line patterns": both are the lines'
            else:  # ("black marble, white veins": the white is the veins', the black not)
                k += 1
        forward = range(end, min(end + 4, len(self.t)))
        for span in (forward, range(start - 1, max(start - 7, -1), -1)):
            for k in span:
                w = self.t[k]
                if (
                    w in self.w.clause_end
                    or w == ","
                    or (span is forward and w in self.w.role_stop)
                ):
                    break
                if w in self.w.roles:
                    role = self.w.roles[w]
                    return None if role == "none" else role
        return None

    # ------------------------------------------------------------------ overlays
    def overlays(self) -> None:
        for i in range(len(self.t)):
            if i > 0 and f"{self.t[i - 1]}{self.t[i]}" in self.w.styles:
                continue  # "hand painted": an art style, not a coat of paint
            if not self.free(i) or self.split_trigger(i):
                continue
            for n in (3, 2, 1):
                phrase = " ".join(self.t[i : i + n])
                name = self.triggers.get(phrase)
                if name is None or any(not self.free(k) for k in range(i, i + n)):
                    continue
                if phrase in self.weak and i >= self.out.head_end:
                    break
                self.add_overlay(name, phrase, i, n)
                break

    def split_trigger(self, i: int) -> bool:
        """A two-word trigger with its colour between the words ("painted white line",
        "painted yellow lines"): the overlay, in that colour."""
        colours = self.out.colours
        k = next((k for k, c in enumerate(colours) if c.index == i + 1), None)
        if k is None:
            return False
        end = i + 1 + len(colours[k].words.split())
        phrase = f"{self.t[i]} {self.at(end)}"
        name = self.triggers.get(phrase)
        if name is None or not self.free(end) or name in {o.name for o in self.out.overlays}:
            return False
        self.add_overlay(name, phrase, i, end + 1 - i, colour=k)
        return True

    def add_overlay(
        self, name: str, phrase: str, i: int, n: int, colour: int | None = None
    ) -> None:
        """Add overlay ``name`` read from tokens ``i`` .. ``i + n``; its colour is the colour
        mention just before them, or mention number ``colour`` (one inside the phrase)."""
        amount = 0.5
        for k in range(max(0, i - 3), i):
            w = self.t[k]
            if w in self.w.amounts and w not in self.w.scale and self.free(k):
                amount = self.w.amounts[w]
                self.use("amount", k)
        colours, mention = self.out.colours, None
        before = (k for k in range(len(colours) - 1, -1, -1) if i - 2 <= colours[k].index < i)
        k = next(before, None) if colour is None else colour
        if k is not None:
            mention = colours[k] = replace(colours[k], role="overlay")
        rgb = mention.rgb if mention else None
        at = mention.index if mention else None
        self.use("overlay", *range(i, i + n))
        near = self.t[max(0, i - 3) : i + n + 3]
        streaks = bool(self.w.streaks & set(near))
        overlays = self.out.overlays
        for k, existing in enumerate(overlays):
            if existing.name == name:
                merged = replace(
                    existing,
                    amount=max(existing.amount, amount),
                    streaks=existing.streaks or streaks,
                )
                if existing.colour is None:
                    merged = replace(merged, colour=rgb, colour_at=at)
                overlays[k] = merged
                return
        overlays.append(OverlayMention(name, phrase, i, amount, rgb, at, streaks=streaks))

    # ------------------------------------------------------------------ finishes
    def finishes(self) -> None:
        for i, w in enumerate(self.t):
            if self.free(i) and w in self.w.finishes:
                self.out.finishes.append((self.w.finishes[w], w))
                self.use("finish", i)

    # ------------------------------------------------------------------ scale and numbers
    def scale(self) -> None:
        factors: list[float] = []
        #: (scale word, token it sizes): a word said again for the same noun counts once
        #: ("tiny tiny tiles"; 1,500 of them made the View 0 or infinite)
        seen: set[tuple[str, int]] = set()
        for i, w in enumerate(self.t):
            if w not in self.w.scale or not self.free(i):
                continue
            start = i + 1  # a run of scale words ("tiny tiny tiny tiles") sizes the same noun
            while self.at(start) in self.w.scale:
                start += 1
            target = next(
                (
                    self.t[k]
                    for k in range(start, min(start + 3, len(self.t)))
                    if self.t[k].isalpha() and self.t[k] not in self.w.scale
                ),
                "",
            )
            if not target or target in self.w.scale_skip or target in self.w.stop_words:
                continue
            sized = self.t.index(target, i + 1)
            if (w, sized) in seen:
                self.use("scale", i)
                continue
            seen.add((w, sized))
            k = self.overlay_at(sized)
            if k is not None:  # "small cracks": the overlay's features, not the View
                overlay = self.out.overlays[k]
                self.out.overlays[k] = replace(overlay, scale=overlay.scale * self.w.scale[w])
                self.use("scale", i)
                continue
            factors.append(self.w.scale[w])
            self.out.scale_words.append(w)
            self.use("scale", i)
        if factors:
            prod = 1.0
            for f in factors:
                prod *= f
            self.out.scale = prod ** (1.0 / len(factors))

    def overlay_at(self, k: int) -> int | None:
        """The position of the overlay mention whose words include token ``k``."""
        for n, m in enumerate(self.out.overlays):
            if m.index <= k < m.index + len(m.word.split()):
                return n
        return None

    def number(self, tok: str) -> float | None:
        if re.fullmatch(r"\d+/\d+", tok):
            num, den = tok.split("/")
            return int(num) / int(den) if int(den) else None
        if re.fullmatch(r"\d+(?:\.\d+)?", tok):
            return float(tok)
        return float(self.w.numbers[tok]) if tok in self.w.numbers else None

    def numbers(self) -> None:
        for i, w in enumerate(self.t):
            value = self.number(w)
            if value is None or i in self.out.negated:
                continue
            unit = self.at(i + 1)
            if unit in {"%", "percent"}:
                self.out.percents.append(value / 100.0)
                self.use("percent", i, i + 1)
            elif unit in self.w.units and value > 0:
                noun = self.noun_after(i + 2) or self.noun_before(i - 1)
                metres = value * self.w.units[unit]
                area = self.at(i - 1) == "x" and self.number(self.at(i - 2)) is not None
                repeat = self.at(i + 2) in self.w.repeat
                extent = metres >= _REPEAT_MIN_M and (area or repeat)
                self.out.sizes.append(Size(metres, noun, f"{w} {unit}", extent))
                self.use("size", i, i + 1)
                if metres >= _REPEAT_MIN_M and repeat:
                    # "4x4m tile", "2 m texture": the size of the texture's repeat, no
                    # ceramic tile (a tile a metre or more across is a game artist's repeat)
                    self.use("size", i + 2)
            elif value == int(value) and 1 <= value <= 64:
                noun = self.noun_after(i + 1)
                if noun:
                    self.out.counts.append(Count(int(value), noun))
                    self.use("count", i)

    def noun_after(self, k: int) -> str:
        words = [
            self.t[j]
            for j in range(k, min(k + 3, len(self.t)))
            if self.t[j].isalpha() and self.t[j] not in self.w.stop_words and len(self.t[j]) > 2
        ]
        plural = [w for w in words if plural_stem(w) != w]
        return plural_stem(plural[0]) if plural else (plural_stem(words[0]) if words else "")

    def noun_before(self, k: int) -> str:
        for j in range(k, max(k - 4, -1), -1):
            if self.t[j].isalpha() and self.t[j] not in self.w.stop_words:
                return plural_stem(self.t[j])
        return ""

    # ------------------------------------------------------------------ tones
    def tones(self) -> None:
        """Tone words before a non-colour noun ("pale mortar", "dark wood")."""
        for i, w in enumerate(self.t):
            if w in self.w.tones and self.free(i):
                nxt = self.at(i + 1)
                if nxt.isalpha() and nxt not in self.w.tones and nxt not in self.w.stop_words:
                    self.out.tones.append((w, plural_stem(nxt), i))
                    self.use("tone", i)


def read(
    prompt: str, words: Words, triggers: dict[str, str], weak: set[str] | None = None
) -> Request:
    """Read ``prompt``; ``triggers`` maps overlay words/phrases to overlay names, ``weak`` lists
    triggers that count only in the head clause ("old" in "old brick wall")."""
    return _Reader(prompt or "", words, triggers, weak or set()).run()
