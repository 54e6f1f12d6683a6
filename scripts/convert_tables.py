"""Tables of the one-off recipe conversion (scripts/convert_recipes.py): the library category of
each built-in recipe family (with per-recipe exceptions) and extra tags and synonyms that the
built-in author matched through Python rules rather than tags."""

from __future__ import annotations

from matloom.author.builtin.recipes import Recipe

CATEGORY = {
    "wood": "wood",
    "stone": "stone",
    "masonry": "masonry",
    "concrete": "concrete",
    "metal": "metal",
    "fabric": "fabric",
    "leather": "leather",
    "ground": "ground",
    "glass": "glass",
    "plastic": "plastic",
    "paper": "paper",
    "organic": "organic",
    "emissive": "scifi",
    "scifi": "scifi",
}

#: recipe -> category where the family's default is not the one artists would look in.
EXCEPTIONS = {
    "tree-bark": "organic",
    "square-tiles": "tiles",
    "subway-tiles": "tiles",
    "hexagon-tiles": "tiles",
    "triangle-tiles": "tiles",
    "checker-tiles": "tiles",
    "mosaic-tiles": "tiles",
    "fish-scale-tiles": "tiles",
    "sand": "natural",
    "kinetic-sand": "natural",
    "snow": "natural",
    "salt-flat": "natural",
    "water-surface": "natural",
    "lava": "natural",
    "moss": "organic",
    "carved-ornament": "ornament",
    "wallpaper": "ornament",
    "fur": "organic",
    "generic-surface": "plastic",
}

EXTRA_TAGS: dict[str, tuple[str, ...]] = {
    "cracked-earth": ("cracked", "desert", "mud", "clay", "earth", "dried", "crackle"),
    "mud": ("wet", "puddles"),
    "sand": ("dune", "grains"),
    "rusted-metal": ("rust", "orange"),
    "corrugated-metal": ("sheet", "roof", "wave"),
    "cobblestone": ("cobbles", "street", "old"),
    "marble": ("veins", "veined", "white"),
    "brick-wall": ("red", "wall"),
    "concrete": ("grey", "cement", "wall", "floor"),
    "wood-planks": ("wooden", "timber", "hardwood", "planks"),
    "leather": ("grain", "hide"),
    "grass": ("green", "lawn"),
    "snow": ("white", "winter"),
    "generic-surface": ("plain", "solid", "surface", "smooth", "coloured", "generic"),
}

EXTRA_SYNONYMS: dict[str, tuple[str, ...]] = {
    "cracked-earth": ("cracked desert mud", "dry cracked earth", "cracked dry ground"),
    "mud": ("wet mud", "muddy ground"),
    "corrugated-metal": ("corrugated iron", "tin roof"),
    "rusted-metal": ("rusty steel", "rusty metal", "rusted iron"),
    "wood-planks": ("wooden floor", "timber floor", "floorboards"),
    "cobblestone": ("cobblestone street", "cobbled road"),
}


def category_of(recipe: Recipe) -> str:
    """The library category of a built-in recipe."""
    return EXCEPTIONS.get(recipe.name, CATEGORY[recipe.family])


#: recipe -> template text replacements that make its pattern divide the View (so it tiles):
#: brick sizes rounded to whole courses per View, with the expressions that repeat them.
FIXUPS: dict[str, tuple[tuple[str, str], ...]] = {
    "wood-planks": (
        (
            "brick_width=2.6, brick_height=0.42, offset=0.38",
            "brick_width=2, brick_height=0.4, offset=0.4",
        ),
        ("(Y() / 0.42)", "(Y() / 0.4)"),
        ("(row * 0.988)) / 2.6)", "(row * 0.8)) / 2)"),
    ),
    "wood-panels": (
        (
            "Translate(Bricks(brick_width=0.62, brick_height=100, offset=0, mortar={gap}, "
            "feather=0.012), 0, 50)",
            "Smoothstep(({gap} * 0.5), (({gap} * 0.5) + 0.012), "
            "(Min(Fract((X() / 0.6)), (1 - Fract((X() / 0.6)))) * 0.6))",
        ),
        ("Floor((X() / 0.62))", "Floor((X() / 0.6))"),
    ),
    "stone-block-wall": (
        (
            "brick_width=1.3, brick_height=0.55, offset=0.37",
            "brick_width=(4 / 3), brick_height=(4 / 7), offset=(3 / 7)",
        ),
        ("(Y() / 0.55)", "((Y() * 7) / 4)"),
        ("(row * 0.481)) / 1.3)", "(row * (4 / 7))) * 0.75)"),
    ),
    "slate": (
        (
            "brick_width=1.2, brick_height=0.8, offset=0.5",
            "brick_width=1.5, brick_height=0.75, offset=0.5",
        ),
        ("(Y() / 0.8)", "(Y() / 0.75)"),
        ("(row * 0.6)) / 1.2)", "(row * 0.75)) / 1.5)"),
    ),
    "brick-wall": (
        ("brick_height=0.34", "brick_height=(1 / 3)"),
        ("(Y() / 0.34)", "(Y() * 3)"),
    ),
    "concrete": (
        (
            "Translate(Bricks(brick_width=100, brick_height=1.5, offset=0, mortar=0.012, "
            "feather=0.01), 50, 0.4)",
            "Smoothstep(0.006, 0.016, Min(Fract((Y() + 0.1)), (1 - Fract((Y() + 0.1)))))",
        ),
    ),
}


def fix_template(recipe: Recipe) -> Recipe:
    """``recipe`` with ``pi`` for 3.1416 (whole cycles stay whole, so Sin bands tile) and its
    :data:`FIXUPS` applied (each must match exactly once)."""
    from dataclasses import replace

    text = recipe.template.replace("3.1416", "pi")
    for old, new in FIXUPS.get(recipe.name, ()):
        if text.count(old) != 1:
            raise ValueError(f"{recipe.name}: fixup {old!r} matches {text.count(old)} times")
        text = text.replace(old, new)
    return replace(recipe, template=text)
