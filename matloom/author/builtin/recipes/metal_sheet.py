"""Sheet-metal and special metals: grids / gratings, perforated sheet, riveted panels, foil,
cast iron and iridescent ore (split from ``metal`` to keep modules short)."""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.metal import METAL_PRESETS, METAL_WORDS

recipe(
    "metal-grid",
    "metal",
    "metal grid / grating: crossing bars over a dark open background",
    """
View(0, 0, {view}, {view})
Define(bars, (1 - Bricks(brick_width=1, brick_height=1, offset=0, mortar={gap}, feather=0.04)))
Define(scuff, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:scuff}))
Material(
  Layer(1)
    .basecolor({rgb:back})
    .roughness(0.9),
  Layer(bars)
    .basecolor({mix:metal~-0.35,metal,scuff})
    .metallic(0.85)
    .roughness(({rough} + (scuff * 0.15)))
    .height((bars * {h:0.08}))
)""",
    tags={
        "grid": 2.5,
        "grating": 5,
        "grate": 5,
        "mesh": 2,
        "wire mesh": 4,
        "lattice": 2,
        "fence": 2.5,
        "cage": 3,
        "bars": 2,
        **METAL_WORDS,
    },
    colours=roles(("metal", (160, 162, 166)), ("back", (26, 26, 28), "base")),
    slots={"view": 6, "rough": 0.4, "gap": 0.18},
    patterns=("grid", "mesh", "squares"),
    presets=METAL_PRESETS,
    count_nouns=("square", "cell", "opening"),
    repeat=1.0,
    unit_m=0.05,
)

recipe(
    "perforated-metal",
    "metal",
    "perforated sheet: round holes punched in a staggered pattern",
    """
View(0, 0, {view}, {view})
Define(row, Floor((Y() / 0.866)))
Define(cx, (((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(cy, (((Y() / 0.866) - row) - 0.5))
Define(hole, Threshold((({radius} - Sqrt(((cx * cx) + ((cy * 0.866) * (cy * 0.866))))) * 60), below_at=0, above_at=1))
Define(scuff, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:scuff}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.3,metal,scuff})
    .metallic(0.85)
    .roughness(({rough} + (scuff * 0.1)))
    .height({h:0.01}),
  Layer(hole)
    .basecolor({rgb:back})
    .roughness(1)
    .height(0)
)""",
    tags={
        "perforated": 6,
        "punched": 3,
        "holes": 2,
        "speaker": 3,
        "grille": 4,
        "grill": 3,
        **METAL_WORDS,
    },
    colours=roles(("metal", (176, 178, 182)), ("back", (20, 20, 22), "base")),
    slots={"view": 8, "rough": 0.4, "radius": 0.3},
    patterns=("dots", "perforated", "circles"),
    presets=METAL_PRESETS,
    unit_m=0.01,
)

recipe(
    "riveted-panels",
    "metal",
    "riveted sheet-metal panels with seams and rows of rivets",
    """
View(0, 0, {view}, {view})
Define(panel, Bricks(brick_width=2, brick_height=1.4, offset=0.5, mortar=0.03, feather=0.02))
Define(rx, ((X() * 5) - Floor((X() * 5))))
Define(ry, ((Y() / 1.4) - Floor((Y() / 1.4))))
Define(rivet, Threshold(((0.05 - Sqrt(((((rx - 0.5) * 0.2) * ((rx - 0.5) * 0.2)) + (Min(ry, (1 - ry)) - 0.06) * (Min(ry, (1 - ry)) - 0.06)))) * 200), below_at=0, above_at=1))
Define(stain, fBm(octaves=5, base_freq=1.5, to_01=True, seed={seed:stain}))
Material(
  Layer(1)
    .basecolor({rgb:metal~-0.6})
    .roughness(0.8),
  Layer(panel)
    .basecolor({mix:metal~-0.3,metal,stain})
    .metallic(0.85)
    .roughness(({rough} + (stain * 0.2)))
    .height((panel * {h:0.02})),
  Layer(rivet)
    .basecolor({rgb:metal~0.1})
    .metallic(0.9)
    .roughness(0.3)
    .height((rivet * {h:0.04}))
)""",
    tags={
        "riveted": 6,
        "rivets": 6,
        "rivet": 6,
        "hull": 3,
        "steampunk": 3,
        "sheet metal": 4,
        "panels": 1.5,
        "plates": 2,
        "armor": 2,
        **METAL_WORDS,
    },
    colours=roles(("metal", (150, 152, 156))),
    slots={"view": 4, "rough": 0.4},
    presets=METAL_PRESETS,
    unit_m=0.3,
)

recipe(
    "metal-foil",
    "metal",
    "crinkled metal foil / gold leaf with sharp crease facets",
    """
View(0, 0, {view}, {view})
Define(crease, Worley(combination="F2-F1", base_freq={mf:6}, to_01=True, seed={seed:crease}))
Define(facet, Worley(base_freq={mf:6}, to_01=True, seed={seed:crease}))
Define(fine, Worley(combination="F2-F1", base_freq={mf:16}, to_01=True, seed={seed:fine}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.4,metal~0.15,((facet * 0.6) + (fine * 0.4))})
    .metallic(0.95)
    .roughness({rough})
    .height(((crease * {hv:0.04}) + (fine * {hv:0.015})))
)""",
    tags={
        "foil": 6,
        "tinfoil": 6,
        "gold leaf": 7,
        "gilded": 5,
        "gilt": 5,
        "leaf": 1,
        "crinkled": 4,
        "crumpled": 2,
        "mylar": 5,
        "wrapper": 2,
        **METAL_WORDS,
    },
    colours=roles(("metal", (214, 214, 218))),
    slots={"view": 1, "rough": 0.25},
    presets=METAL_PRESETS,
    unit_m=0.2,
)

recipe(
    "cast-iron",
    "metal",
    "cast iron: dark, sandy-grained matte metal",
    """
View(0, 0, {view}, {view})
Define(sand, fBm(octaves=4, base_freq={mf:80}, to_01=True, seed={seed:sand}))
Define(tone, fBm(octaves=4, base_freq=1.2, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:metal~-0.35,metal,((sand * 0.6) + (tone * 0.4))})
    .metallic(0.7)
    .roughness(({rough} + (sand * 0.15)))
    .height(((sand * {hv:0.004}) + (tone * {h:0.004})))
)""",
    tags={
        "cast iron": 7,
        "iron": 3,
        "wrought": 3,
        "skillet": 4,
        "pan": 1.5,
        "forged": 2,
        "blackened": 2,
        **METAL_WORDS,
    },
    colours=roles(("metal", (84, 84, 86))),
    slots={"view": 1, "rough": 0.7},
    unit_m=0.3,
)

recipe(
    "iridescent-ore",
    "metal",
    "iridescent metallic ore (peacock ore, bornite): blue-purple-green tarnish",
    """
View(0, 0, {view}, {view})
Define(lump, Worley(base_freq=2.2, to_01=True, seed={seed:lump}))
Define(film, fBm(octaves=5, base_freq=1.8, to_01=True, seed={seed:film}))
Define(fine, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:fine}))
Material(
  Layer(1)
    .basecolor({mix:tint_a,tint_b,film})
    .metallic(0.85)
    .roughness(({rough} + (fine * 0.15)))
    .height((((1 - lump) * {h:0.06}) + (fine * {hv:0.004}))),
  Layer(Threshold(((film - 0.55) * 8), below_at=0, above_at=1))
    .basecolor({mix:tint_c,tint_d,fine})
    .metallic(0.85)
    .roughness({rough}),
  Layer(Threshold(((0.35 - film) * 8), below_at=0, above_at=1))
    .basecolor({rgb:metal})
    .metallic(0.9)
    .roughness({rough})
)""",
    tags={
        "peacock ore": 9,
        "bornite": 8,
        "peacock": 3,
        "ore": 3,
        "iridescent": 2.5,
        "chalcopyrite": 7,
        "tarnish": 3,
        "mineral": 1.5,
        "jewelry": 0.5,
    },
    colours=roles(
        ("tint_a", (40, 70, 170)),
        ("tint_b", (120, 50, 150), "accent"),
        ("tint_c", (40, 150, 120), "accent"),
        ("tint_d", (200, 160, 60), "accent"),
        ("metal", (170, 130, 90), "accent"),
    ),
    slots={"view": 2, "rough": 0.3},
    patterns=("iridescent",),
    unit_m=0.1,
)
