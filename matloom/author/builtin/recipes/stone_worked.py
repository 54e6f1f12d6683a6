"""Worked and special stone: runestone with carved glyphs, carved ornament (jade) and porous
stone (pumice, lava rock, charcoal) (split from ``stone`` to keep modules short)."""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.stone import STONE_WORDS

recipe(
    "runestone",
    "stone",
    "weathered standing stone with carved runic glyph grooves",
    """
View(0, 0, {view}, {view})
Define(mass, fBm(octaves=6, base_freq=1.5, to_01=True, seed={seed:mass}))
Define(grit, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:grit}))
Define(runes, Max(Max(Stroke(Path(0.3, 1.6, LineTo(0.3, 2.4), LineTo(0.6, 2.1), LineTo(0.3, 1.9)), 0.07, feather=0.02), Stroke(Path(0.9, 1.6, LineTo(0.9, 2.4), LineTo(1.2, 2), LineTo(1.5, 2.4), LineTo(1.5, 1.6)), 0.07, feather=0.02)), Max(Stroke(Path(1.9, 1.6, LineTo(2.3, 2.4), LineTo(2.7, 1.6)), 0.07, feather=0.02), Max(Stroke(Path(0.5, 0.4, LineTo(0.5, 1.2), LineTo(0.9, 0.8), LineTo(1.3, 1.2), LineTo(1.3, 0.4)), 0.07, feather=0.02), Stroke(Path(1.8, 0.4, LineTo(2.2, 0.8), LineTo(1.8, 1.2), LineTo(2.6, 1.2)), 0.07, feather=0.02)))))
Material(
  Layer(1)
    .basecolor({mix:base_dark,base,((mass * 0.6) + (grit * 0.4))})
    .roughness(({rough} + (grit * 0.08)))
    .height((((mass * {h:0.06}) + (grit * {hv:0.006})) - (runes * {h:0.04}))),
  Layer((runes * 0.9))
    .basecolor({rgb:rune})
    .roughness(1)
)""",
    tags={
        "runestone": 8,
        "runes": 6,
        "rune": 6,
        "runic": 6,
        "carved": 2,
        "inscription": 4,
        "glyphs": 4,
        "engraved": 2,
        "standing stone": 5,
        "megalith": 5,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (150, 146, 136)),
        ("base_dark", (98, 94, 88), "base", ("base", -0.35)),
        ("rune", (52, 46, 42), "accent", ("base", -0.65)),
    ),
    slots={"view": 3, "rough": 0.9},
    unit_m=0.3,
)

recipe(
    "carved-ornament",
    "stone",
    "smooth stone carved with a repeating ornamental relief motif",
    """
View(0, 0, {view}, {view})
Define(motif, (Abs(Sin((X() * 3.1416))) * Abs(Sin((Y() * 3.1416)))))
Define(rosette, Abs(Sin(((Sqrt((((X() - (Floor(X()) + 0.5)) * (X() - (Floor(X()) + 0.5))) + ((Y() - (Floor(Y()) + 0.5)) * (Y() - (Floor(Y()) + 0.5))))) * 12) * 3.1416))))
Define(carve, Threshold((((motif * rosette) - 0.25) * 8), below_at=0, above_at=1))
Define(cloud, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:cloud}))
Material(
  Layer(1)
    .basecolor({mix:base,base_dark,((cloud * 0.6) + ((1 - carve) * 0.4))})
    .roughness({rough})
    .subsurface({sss})
    .height((carve * {h:0.03}))
)""",
    tags={
        "carved": 3,
        "carving": 4,
        "carvings": 4,
        "ornament": 3,
        "ornamental": 3,
        "relief": 2,
        "bas relief": 4,
        "intricately": 1.5,
        "jade": 4,
        "sculpted": 2,
        "engraved": 2,
        "figures": 1,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (214, 208, 196)), ("base_dark", (150, 144, 134), "base", ("base", -0.3))
    ),
    slots={"view": 3, "rough": 0.45, "sss": 0.0},
    presets={"jade": {"base": (96, 168, 120), "sss": 0.5, "rough": 0.2}},
    unit_m=0.1,
)

recipe(
    "porous-stone",
    "stone",
    "porous block (pumice, lava rock, charcoal): dark open pores",
    """
View(0, 0, {view}, {view})
Define(pore, Worley(base_freq={mf:18}, to_01=True, seed={seed:pore}))
Define(poreSmall, Worley(base_freq={mf:45}, to_01=True, seed={seed:poreSmall}))
Define(holes, Max(Threshold(((0.22 - pore) * 30), below_at=0, above_at=1), Threshold(((0.2 - poreSmall) * 30), below_at=0, above_at=1)))
Define(mass, fBm(octaves=4, base_freq=2, to_01=True, seed={seed:mass}))
Material(
  Layer(1)
    .basecolor({mix:base,base~-0.2,mass})
    .roughness({rough})
    .height((((1 - holes) * {hv:0.01}) + (mass * {h:0.01}))),
  Layer((holes * 0.9))
    .basecolor({rgb:base~-0.65})
    .roughness(1)
)""",
    tags={
        "porous": 3,
        "pumice": 6,
        "lava rock": 6,
        "lava stone": 6,
        "volcanic": 4,
        "charcoal": 4,
        "briquette": 5,
        "scoria": 6,
        "tuff": 4,
        "pores": 2,
        "filtration": 1.5,
        "compressed": 1,
        "brick": 0.5,
        "sponge": 2,
    },
    colours=roles(("base", (150, 146, 140))),
    slots={"view": 1, "rough": 0.95},
    presets={
        "charcoal": {"base": (44, 42, 42)},
        "lava": {"base": (70, 60, 58)},
        "volcanic": {"base": (70, 62, 60)},
        "pumice": {"base": (196, 192, 182)},
    },
    unit_m=0.1,
)
