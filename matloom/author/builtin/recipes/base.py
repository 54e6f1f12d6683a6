"""Recipe data model and registry.

A recipe is a hand-written MatLoom program with ``{...}`` slots (see ``template.py`` for the slot
syntax), plus what the author needs to choose and fill it: tags with weights (for the
transparent score), the patterns it realises, named colour roles with defaults, scalar slots
with defaults (``view``, ``rough``, ``relief``, ``wear`` ...) and word presets (e.g. "walnut"
sets the wood colours). Recipes register themselves in :data:`REGISTRY` at import time.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from matloom.author.builtin.colours import RGB

Preset = Mapping[str, "RGB | float | str"]


@dataclass(frozen=True)
class ColourRole:
    """A named colour slot. ``derive=(source, amount)`` makes it follow another role when the
    prompt does not set it: amount > 0 lightens toward white, < 0 darkens toward black. A third
    element ``"contrast"`` flips darkening to lightening when the source is dark (veins on black
    marble must be light)."""

    name: str
    default: RGB
    kind: str = "base"
    derive: tuple[str, float] | tuple[str, float, str] | None = None


@dataclass(frozen=True)
class Recipe:
    """One parameterised program of the library."""

    name: str
    family: str
    summary: str
    template: str
    tags: Mapping[str, float]
    colours: tuple[ColourRole, ...]
    slots: Mapping[str, float | str]
    patterns: tuple[str, ...] = ()
    micro: str | None = None
    presets: Mapping[str, Preset] = field(default_factory=dict)
    count_nouns: frozenset[str] = frozenset()
    repeat: float = 1.0
    unit_m: float = 0.0
    absorbs: frozenset[str] = frozenset()

    def role(self, name: str) -> ColourRole:
        """The colour role called ``name`` (KeyError when the recipe has none)."""
        for r in self.colours:
            if r.name == name:
                return r
        raise KeyError(name)


REGISTRY: dict[str, Recipe] = {}

FAMILIES: tuple[str, ...] = (
    "wood",
    "stone",
    "masonry",
    "concrete",
    "metal",
    "fabric",
    "leather",
    "ground",
    "glass",
    "plastic",
    "paper",
    "organic",
    "emissive",
    "scifi",
)


def roles(*specs: tuple) -> tuple[ColourRole, ...]:
    """Build colour roles from compact tuples: (name, rgb[, kind[, (source, amount)]])."""
    out = []
    for s in specs:
        name, rgb = s[0], s[1]
        kind = s[2] if len(s) > 2 else "base"
        derive = s[3] if len(s) > 3 else None
        out.append(ColourRole(name, rgb, kind, derive))
    return tuple(out)


def recipe(
    name: str,
    family: str,
    summary: str,
    template: str,
    *,
    tags: Mapping[str, float],
    colours: tuple[ColourRole, ...],
    slots: Mapping[str, float | str],
    patterns: tuple[str, ...] = (),
    micro: str | None = None,
    presets: Mapping[str, Preset] | None = None,
    count_nouns: tuple[str, ...] = (),
    repeat: float = 1.0,
    unit_m: float = 0.0,
    absorbs: tuple[str, ...] = (),
) -> Recipe:
    """Create a recipe and add it to :data:`REGISTRY` (names must be unique)."""
    if name in REGISTRY:
        raise ValueError(f"duplicate recipe name {name!r}")
    if family not in FAMILIES:
        raise ValueError(f"unknown family {family!r} for recipe {name!r}")
    full_slots = {"rough": 0.6, "relief": 1.0, **slots}
    r = Recipe(
        name=name,
        family=family,
        summary=summary,
        template=template.strip("\n"),
        tags=dict(tags),
        colours=colours,
        slots=full_slots,
        patterns=tuple(patterns),
        micro=micro,
        presets=dict(presets or {}),
        count_nouns=frozenset(count_nouns),
        repeat=repeat,
        unit_m=unit_m,
        absorbs=frozenset(absorbs),
    )
    REGISTRY[name] = r
    return r
