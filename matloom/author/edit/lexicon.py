"""The offline edit rules' words and steps (``words.toml`` beside this module), and the small
word helpers every rule uses: tokens, plural stems, and whether a word's sense is flipped by a
word before it ("less shiny", "too glossy")."""

from __future__ import annotations

import dataclasses
import functools
import re
import tomllib
from collections.abc import Sequence
from dataclasses import dataclass
from importlib.resources import files


@dataclass(frozen=True)
class EditWords:
    """The tables of ``words.toml`` (see the comments there)."""

    words: dict[str, frozenset[str]]
    joint_params: tuple[str, ...]
    nouns: dict[str, frozenset[str]]
    conditions: dict[str, tuple[str, ...]]
    finish: dict[str, tuple[int, str]]
    tactile: frozenset[str]
    channels: dict[str, frozenset[str]]
    relief: dict[str, int]
    relief_nouns: frozenset[str]
    comparative: dict[str, tuple[float, float, float]]
    towards: dict[str, str]
    factors: dict[str, float]
    #: named colours the library's colour table lacks ("olive drab"), or has too far from
    #: their usual value; these win over the library's
    colours: dict[str, tuple[float, float, float]] = dataclasses.field(default_factory=dict)
    #: the colour of a condition's overlay when its word names a look of its own ("lichen")
    condition_colours: dict[str, tuple[int, int, int]] = dataclasses.field(default_factory=dict)
    #: "too <adjective>" -> the comparative it asks for ("too big": smaller)
    too: dict[str, str] = dataclasses.field(default_factory=dict)
    #: a colour word as a verb -> the comparative it asks for ("yellow it with age": yellower)
    colour_verbs: dict[str, str] = dataclasses.field(default_factory=dict)
    #: look words read as what they change everywhere ("wet": "darker overall, glossier")
    looks: dict[str, str] = dataclasses.field(default_factory=dict)
    #: ... and what a flipped one changes ("less faded": "richer overall")
    unlooks: dict[str, str] = dataclasses.field(default_factory=dict)
    #: intensity words of edits beside the library's ("a slight tint", "heavily worn")
    intensity: dict[str, float] = dataclasses.field(default_factory=dict)
    #: number words of a stated factor ("three times bigger")
    counting: dict[str, float] = dataclasses.field(default_factory=dict)

    def __getitem__(self, key: str) -> frozenset[str]:
        return self.words[key]

    def f(self, key: str) -> float:
        return self.factors[key]

    def family(self, noun: str) -> frozenset[str]:
        """The noun's family words (the noun itself when it is in none)."""
        s = stem(noun)
        out = {s}
        for members in self.nouns.values():
            if s in members or noun in members:
                out |= members
        return frozenset(out)

    def channel_of(self, word: str) -> str | None:
        """The channel a word names ("sheen", "clearcoat" -> coat), or None."""
        for channel, ws in self.channels.items():
            if word in ws:
                return channel
        return None


@functools.cache
def edit_words() -> EditWords:
    """The tables of ``words.toml`` (read once)."""
    raw = tomllib.loads(files("matloom.author.edit").joinpath("words.toml").read_text("utf-8"))
    w = raw["words"]
    relief = dict(raw["relief"])
    relief_nouns = frozenset(relief.pop("nouns"))
    finish = dict(raw["finish"])
    tactile = frozenset(finish.pop("tactile"))
    return EditWords(
        words={k: frozenset(v) for k, v in w.items() if k != "joint_params"},
        joint_params=tuple(w["joint_params"]),
        nouns={k: frozenset(v) for k, v in raw["nouns"].items()},
        # an age word is the condition wear ("older": the worn overlay)
        conditions={k: tuple(v) for k, v in raw["conditions"].items()}
        | {k: ("wear", "worn") for k in w["age"] if k not in raw["conditions"]},
        finish={k: (int(v[0]), str(v[1])) for k, v in finish.items()},
        tactile=tactile,
        channels={k: frozenset(v) for k, v in raw["channels"].items()},
        relief={k: int(v) for k, v in relief.items()},
        relief_nouns=relief_nouns,
        comparative={
            k: (float(v[0]), float(v[1]), float(v[2])) for k, v in raw["comparative"].items()
        },
        towards={k: str(v) for k, v in raw["towards"].items()},
        factors={k: float(v) for k, v in raw["factors"].items()},
        colours={
            k: (float(v[0]), float(v[1]), float(v[2])) for k, v in raw.get("colours", {}).items()
        },
        intensity={k: float(v) for k, v in raw.get("intensity", {}).items()},
        counting={k: float(v) for k, v in raw.get("counting", {}).items()},
        too={k: str(v) for k, v in raw.get("too", {}).items()},
        colour_verbs={k: str(v) for k, v in raw.get("colour_verbs", {}).items()},
        looks={w: str(look["as"]) for look in raw.get("looks", {}).values() for w in look["words"]},
        unlooks={
            w: str(look["opposite"])
            for look in raw.get("looks", {}).values()
            if "opposite" in look
            for w in look["words"]
        },
        condition_colours={
            k: (int(v[0]), int(v[1]), int(v[2]))
            for k, v in raw.get("condition_colours", {}).items()
        },
    )


def tokens(request: str) -> list[str]:
    """The request's words, lower case (hyphens and punctuation split words)."""
    return re.findall(r"[a-z0-9]+(?:\.[0-9]+)?", request.lower())


#: A stated factor is used within these bounds (a larger one is a typo or a unit).
FACTOR_RANGE = (1.1, 5.0)
_NUMBER = r"[0-9]+(?:\.[0-9]+)?"


def stated_factor(words: Sequence[str], ew: EditWords) -> float | None:
    """A factor the request states for a size ("scale it up about 2x", "x3", "3 times
    bigger", "three times as big": the ``[counting]`` words), within
    :data:`FACTOR_RANGE`; None when it states none ("twice" and "half" are read by the size
    rule itself). "2 x 3 m" is a size, not a factor."""
    counting = ew.counting
    for i, w in enumerate(words):
        after = words[i + 1] if i + 1 < len(words) else ""
        following = words[i + 2] if i + 2 < len(words) else ""
        found = None
        if m := re.fullmatch(rf"({_NUMBER})x|x({_NUMBER})", w):
            found = float(m.group(1) or m.group(2))
        elif re.fullmatch(_NUMBER, w) and after == "x" and not re.match(r"[0-9]", following):
            found = float(w)
        elif after == "times" and (w in counting or re.fullmatch(_NUMBER, w)):
            found = counting.get(w) or float(w)
        if found is not None and FACTOR_RANGE[0] <= found <= FACTOR_RANGE[1]:
            return found
    return None


def too_strong(words: Sequence[str], ew: EditWords) -> bool:
    """Whether the request says something shows too much ("too strong", "too heavy": the
    ``too_strong`` words; not after a negation, "not too strong")."""
    return any(
        b == "too" and c in ew["too_strong"] and a not in ew["negation"]
        for a, b, c in zip(["", *words], words, words[1:], strict=False)
    )


#: Plurals in -ves whose singular ends in -f ("leaves", not "grooves").
_F_PLURALS = {"leaves": "leaf", "halves": "half", "shelves": "shelf", "loaves": "loaf"}


def stem(word: str) -> str:
    """A plural's singular, roughly: ``tiles`` -> ``tile``, ``patches`` -> ``patch``."""
    if len(word) <= 3 or not word.endswith("s") or word.endswith("ss"):
        return word
    if word in _F_PLURALS:
        return _F_PLURALS[word]
    if word.endswith("ies"):
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "sses", "xes")):
        return word[:-2]
    return word[:-1]


def flipped(words: Sequence[str], i: int, flips: frozenset[str]) -> bool:
    """Whether the word at ``i`` is flipped by one of ``flips`` at most two words before it
    ("less shiny", "not so glossy", "too rough")."""
    return any(w in flips for w in words[max(0, i - 2) : i])


def split_words(name: str) -> set[str]:
    """The stemmed words of an identifier or label (``stone_warm`` -> stone, warm;
    ``tileMask`` -> tile, mask)."""
    spaced = re.sub(r"([a-z])([A-Z])", r"\1 \2", name)
    return {stem(w) for w in re.findall(r"[a-z]+", spaced.lower())}
