"""Stone family: marble, granite, slate, sandstone, cobblestones, flagstone, terrazzo, rock,
banded stones (agate, onyx, tiger's eye, malachite), travertine, runestone, carved ornament and
porous stone (pumice, lava rock, charcoal).

Veins use the coordinate-domain warping idiom (noise added to X + Y inside ``Sin``), specks use
thresholded high-frequency noise layers over a mottled substrate, and stone lattices use Worley
F1 for rounded domes and F2-F1 for the joints between them.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

STONE_WORDS = {"stone": 1.5, "rock": 1.0}

recipe(
    "marble",
    "stone",
    "polished marble: soft cloudy base with warped dark veins",
    """
View(0, 0, {view}, {view})
Define(cloud, fBm(octaves=5, base_freq=1.2, to_01=True, seed={seed:cloud}))
Define(warp, fBm(octaves=7, base_freq=0.8, seed={seed:warp}))
Define(vein, Threshold((Abs(Sin(((((X() * 0.6) + Y()) * 1.4) + (warp * 2.6)))) * 14), above_at=1))
Define(minor, Threshold((Abs(Sin(((((X() - (Y() * 0.3)) * 3) + (warp * 4)) + (cloud * 2)))) * 6), above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base,cloud_col,cloud})
    .roughness(({rough} + (cloud * 0.05)))
    .coat(0.6)
    .height((cloud * {h:0.001})),
  Layer(((1 - minor) * 0.45))
    .basecolor({rgb:vein~0.35})
    .roughness({rough}),
  Layer((1 - vein))
    .basecolor({rgb:vein})
    .roughness({rough})
)""",
    tags={
        "marble": 5,
        "marbled": 3,
        "scagliola": 5,
        "carrara": 5,
        "calacatta": 5,
        "statuario": 5,
        "polished": 0.5,
        "countertop": 2,
        "mimic marble": 2,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (234, 232, 226)),
        ("vein", (96, 96, 102), "accent", ("base", -0.6, "c")),
        ("cloud_col", (214, 212, 208), "base", ("base", -0.09)),
    ),
    slots={"view": 2, "rough": 0.12},
    unit_m=0.5,
    presets={
        "nero": {"base": (26, 26, 28)},
        "verde": {"base": (40, 90, 64)},
        "scagliola": {"base": (196, 160, 120), "vein": (110, 60, 40)},
    },
)

recipe(
    "granite",
    "stone",
    "granite: dense multi-coloured mineral speckle",
    """
View(0, 0, {view}, {view})
Define(mottle, fBm(octaves=4, base_freq=2, to_01=True, seed={seed:mottle}))
Define(grainA, fBm(octaves=3, base_freq={mf:30}, to_01=True, seed={seed:grainA}))
Define(grainB, fBm(octaves=3, base_freq={mf:40}, to_01=True, seed={seed:grainB}))
Define(grainC, Worley(base_freq={mf:22}, to_01=True, seed={seed:grainC}))
Material(
  Layer(1)
    .basecolor({mix:base,base~-0.15,mottle})
    .roughness({rough})
    .height((grainA * {hv:0.002})),
  Layer(Threshold(((grainA - 0.61) * 25), below_at=0, above_at=1))
    .basecolor({rgb:dark})
    .roughness({rough}),
  Layer(Threshold(((grainB - 0.63) * 25), below_at=0, above_at=1))
    .basecolor({rgb:light})
    .roughness({rough}),
  Layer(Threshold(((0.1 - grainC) * 30), below_at=0, above_at=1))
    .basecolor({rgb:feldspar})
    .roughness({rough})
)""",
    tags={"granite": 6, "speckled": 1.5, "countertop": 1.5, "worktop": 1.5, **STONE_WORDS},
    colours=roles(
        ("base", (150, 144, 140)),
        ("dark", (34, 32, 34), "accent"),
        ("light", (226, 222, 216), "accent"),
        ("feldspar", (176, 132, 118), "accent"),
    ),
    slots={"view": 1, "rough": 0.35},
    patterns=("speckle",),
    unit_m=0.3,
)

recipe(
    "slate",
    "stone",
    "slate floor: rectangular cleft slabs, layered flaky relief, dark mottle",
    """
View(0, 0, {view}, {view})
Define(slab, Bricks(brick_width=1.2, brick_height=0.8, offset=0.5, mortar={gap}, feather=0.01))
Define(cleft, fBm(octaves=6, base_freq_x=1.5, base_freq_y=5, to_01=True, seed={seed:cleft}))
Define(tint, fBm(octaves=3, base_freq=1.2, to_01=True, seed={seed:tint}))
Define(row, Floor((Y() / 0.8)))
Define(cell, (Sin(((Floor(((X() - (row * 0.6)) / 1.2)) * 12.9898) + (row * 78.233))) * 43758.5453))
Define(tone, (cell - Floor(cell)))
Material(
  Layer(1)
    .basecolor({rgb:grout})
    .roughness(0.95),
  Layer(slab)
    .basecolor({mix:base,tint_col,((tint * 0.5) + (tone * 0.5))})
    .roughness(({rough} + (cleft * 0.15)))
    .height((slab * (({h:0.02} + (Threshold(((cleft - 0.5) * 6), below_at=0, above_at=1) * {h:0.008})) + (cleft * {h:0.004}))))
)""",
    tags={
        "slate": 6,
        "flagstone": 1,
        "flooring": 1,
        "floor": 1,
        "tile": 1,
        "tiles": 1,
        "shale": 4,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (62, 66, 72)),
        ("tint_col", (84, 86, 90), "base", ("base", 0.12)),
        ("grout", (30, 30, 32), "grout", ("base", -0.6)),
    ),
    slots={"view": 3, "rough": 0.7, "gap": 0.03},
    unit_m=0.4,
    count_nouns=("slab", "tile"),
    repeat=1.2,
)

recipe(
    "sandstone",
    "stone",
    "sandstone: warm sedimentary strata with sandy grain",
    """
View(0, 0, {view}, {view})
Define(warp, fBm(octaves=4, base_freq=0.8, seed={seed:warp}))
Define(strata, Abs(Sin((((Y() * 3.5) + (warp * 2.5)) * 3.1416))))
Define(sand, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:sand}))
Define(erode, fBm(octaves=5, base_freq=2, to_01=True, seed={seed:erode}))
Material(
  Layer(1)
    .basecolor({mix:base,band,((strata * 0.6) + (sand * 0.4))})
    .roughness(({rough} + (sand * 0.1)))
    .height((((strata * {h:0.015}) + (erode * {h:0.03})) + (sand * {hv:0.003})))
)""",
    tags={
        "sandstone": 6,
        "sedimentary": 3,
        "strata": 3,
        "layered rock": 3,
        "canyon": 2,
        "limestone": 2,
        **STONE_WORDS,
    },
    colours=roles(("base", (214, 170, 118)), ("band", (176, 112, 70), "accent", ("base", -0.25))),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.5,
)

recipe(
    "cobblestone",
    "stone",
    "cobblestones: rounded domed stones set in dark joints",
    """
View(0, 0, {view}, {view})
Define(stone, Worley(base_freq=1.6, to_01=True, seed={seed:cells}))
Define(joint, Worley(combination="F2-F1", base_freq=1.6, to_01=True, seed={seed:cells}))
Define(setMask, Threshold(((joint - {gap}) * 25), below_at=0, above_at=1))
Define(tone, fBm(octaves=3, base_freq=2.2, to_01=True, seed={seed:tone}))
Define(grit, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({mix:grout,grout~-0.2,grit})
    .roughness(0.95)
    .height((grit * {hv:0.003})),
  Layer(setMask)
    .basecolor({mix:base,base_dark,((tone * 0.7) + (grit * 0.3))})
    .roughness(({rough} + (grit * 0.1)))
    .height((setMask * (({h:0.05} + ((1 - stone) * {h:0.07})) + (grit * {hv:0.004}))))
)""",
    tags={
        "cobblestone": 6,
        "cobblestones": 6,
        "cobble": 6,
        "cobbled": 6,
        "setts": 5,
        "pavement": 1.5,
        "street": 1.5,
        "road": 1,
        "paving": 1.5,
        "stones": 1.5,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (140, 134, 126)),
        ("base_dark", (96, 90, 84), "base", ("base", -0.35)),
        ("grout", (64, 58, 50), "grout", ("base", -0.6)),
    ),
    slots={"view": 4, "rough": 0.7, "gap": 0.08},
    unit_m=0.15,
    count_nouns=("stone", "cobble"),
    repeat=0.62,
)

recipe(
    "flagstone",
    "stone",
    "irregular flagstone paving: flat polygonal slabs in mortar",
    """
View(0, 0, {view}, {view})
Define(joint, Worley(combination="F2-F1", base_freq=1.3, to_01=True, seed={seed:cells}))
Define(slab, Threshold(((joint - {gap}) * 40), below_at=0, above_at=1))
Define(tone, fBm(octaves=2, base_freq=1.8, to_01=True, seed={seed:tone}))
Define(cleft, fBm(octaves=5, base_freq={mf:12}, to_01=True, seed={seed:cleft}))
Material(
  Layer(1)
    .basecolor({rgb:grout})
    .roughness(0.95),
  Layer(slab)
    .basecolor({mix:base,base_alt,((tone * 0.75) + (cleft * 0.25))})
    .roughness(({rough} + (cleft * 0.1)))
    .height((slab * ({h:0.03} + (cleft * {hv:0.012}))))
)""",
    tags={
        "flagstone": 6,
        "crazy paving": 6,
        "patio": 2,
        "paving": 2,
        "pavement": 1.5,
        "irregular": 1.5,
        "polygonal": 1.5,
        "stepping": 2,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (168, 150, 126)),
        ("base_alt", (126, 116, 104), "base", ("base", -0.28)),
        ("grout", (96, 90, 82), "grout", ("base", -0.45)),
    ),
    slots={"view": 3, "rough": 0.8, "gap": 0.05},
    unit_m=0.3,
)

recipe(
    "terrazzo",
    "stone",
    "terrazzo: coloured stone chips set in a polished cement matrix",
    """
View(0, 0, {view}, {view})
Define(chipA, fBm(octaves=2, base_freq={mf:10}, to_01=True, seed={seed:chipA}))
Define(chipB, fBm(octaves=2, base_freq={mf:16}, to_01=True, seed={seed:chipB}))
Define(chipC, fBm(octaves=2, base_freq={mf:24}, to_01=True, seed={seed:chipC}))
Define(matrix, fBm(octaves=3, base_freq={mf:20}, to_01=True, seed={seed:matrix}))
Material(
  Layer(1)
    .basecolor({mix:base,base~-0.08,matrix})
    .roughness({rough}),
  Layer(Threshold(((chipA - 0.7) * 60), below_at=0, above_at=1))
    .basecolor({rgb:chip_a})
    .roughness({rough}),
  Layer(Threshold(((chipB - 0.7) * 60), below_at=0, above_at=1))
    .basecolor({rgb:chip_b})
    .roughness({rough}),
  Layer(Threshold(((chipC - 0.68) * 60), below_at=0, above_at=1))
    .basecolor({rgb:chip_c})
    .roughness({rough})
)""",
    tags={"terrazzo": 6, "chips": 1.5, "venetian": 2, "confetti": 2, "speckled": 1},
    colours=roles(
        ("base", (230, 226, 218)),
        ("chip_a", (60, 60, 62), "accent"),
        ("chip_b", (190, 110, 90), "accent"),
        ("chip_c", (150, 160, 170), "accent"),
    ),
    slots={"view": 1, "rough": 0.2},
    patterns=("speckle",),
    unit_m=0.3,
)

recipe(
    "rock-face",
    "stone",
    "natural rock face: rugged fractured relief with grey mineral mottle",
    """
View(0, 0, {view}, {view})
Define(mass, fBm(octaves=7, base_freq=1.2, to_01=True, seed={seed:mass}))
Define(fracture, Worley(combination="F2-F1", base_freq=2, to_01=True, seed={seed:fracture}))
Define(grit, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:grit}))
Define(crevice, Threshold(((0.06 - fracture) * 20), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base_dark,base,((mass * 0.6) + (grit * 0.4))})
    .roughness(({rough} + (grit * 0.1)))
    .height((((mass * {h:0.12}) + (Min((fracture * 4), 1) * {h:0.04})) + (grit * {hv:0.006}))),
  Layer((crevice * 0.8))
    .basecolor({rgb:base_dark~-0.5})
    .roughness(1)
)""",
    tags={
        "rock": 4,
        "rocky": 4,
        "cliff": 4,
        "boulder": 4,
        "basalt": 4,
        "mountain": 2,
        "quarry": 2,
        "stone wall": 1,
        "rough stone": 3,
        "granite rock": 2,
        "stone": 2,
    },
    colours=roles(("base", (150, 146, 140)), ("base_dark", (90, 86, 82), "base", ("base", -0.4))),
    slots={"view": 2, "rough": 0.85},
    presets={"basalt": {"base": (76, 76, 80)}},
    unit_m=0.5,
)

recipe(
    "banded-stone",
    "stone",
    "polished banded mineral (agate, onyx, tiger's eye, malachite)",
    """
View(0, 0, {view}, {view})
Define(warp, fBm(octaves=5, base_freq=0.7, seed={seed:warp}))
Define(band, Abs(Sin(((((Y() * 2.2) + (X() * 0.4)) + (warp * {warp})) * 3.1416))))
Define(fineBand, Abs(Sin(((((Y() * 9) + (X() * 1.6)) + (warp * {warp*4})) * 3.1416))))
Define(silk, fBm(octaves=3, base_freq_x=40, base_freq_y=3, to_01=True, seed={seed:silk}))
Material(
  Layer(1)
    .basecolor({mix:base,band_col,((band * 0.7) + (fineBand * 0.3))})
    .roughness({rough})
    .coat(0.7)
    .anisotropy({aniso})
    .height((silk * {h:0.001})),
  Layer((fineBand * silk * {chatoy}))
    .basecolor({rgb:base~0.35})
    .roughness({rough})
)""",
    tags={
        "agate": 6,
        "onyx": 6,
        "tiger's eye": 7,
        "tiger": 2,
        "eye": 1,
        "malachite": 6,
        "chatoyant": 4,
        "banded": 3,
        "gemstone": 2.5,
        "mineral": 1.5,
        "rhodochrosite": 6,
        "jasper": 5,
        "sardonyx": 6,
        "polished": 0.5,
        "stones": 1,
        "flooring": 0.5,
    },
    colours=roles(
        ("base", (196, 140, 60)), ("band_col", (90, 52, 24), "accent", ("base", -0.55, "c"))
    ),
    slots={"view": 2, "rough": 0.12, "aniso": 0.0, "chatoy": 0.0, "warp": 4},
    patterns=("marbled", "waves", "stripes"),
    presets={
        "tiger's eye": {
            "base": (214, 156, 50),
            "band_col": (74, 42, 16),
            "aniso": 0.6,
            "chatoy": 0.6,
            "warp": 1.2,
        },
        "tiger": {
            "base": (204, 150, 52),
            "band_col": (86, 50, 22),
            "aniso": 0.6,
            "chatoy": 0.6,
            "warp": 1.2,
        },
        "malachite": {"base": (40, 150, 90), "band_col": (10, 60, 36)},
        "onyx": {"base": (236, 222, 196), "band_col": (150, 104, 60)},
        "agate": {"base": (200, 170, 170), "band_col": (120, 70, 80)},
        "rhodochrosite": {"base": (230, 150, 160), "band_col": (170, 70, 90)},
    },
    unit_m=0.1,
)

recipe(
    "travertine",
    "stone",
    "travertine: beige stone with horizontal veining and small pits",
    """
View(0, 0, {view}, {view})
Define(warp, fBm(octaves=4, base_freq_x=0.5, base_freq_y=2, seed={seed:warp}))
Define(layers, Abs(Sin((((Y() * 6) + (warp * 3)) * 3.1416))))
Define(pitCell, Worley(base_freq_x={mf:14}, base_freq_y={mf:30}, to_01=True, seed={seed:pit}))
Define(pit, Threshold(((0.1 - pitCell) * 30), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base,base_dark,layers})
    .roughness({rough})
    .height(((1 - pit) * {h:0.004})),
  Layer((pit * 0.85))
    .basecolor({rgb:base_dark~-0.3})
    .roughness(0.95)
)""",
    tags={
        "travertine": 7,
        "limestone": 5,
        "tufa": 5,
        "coquina": 5,
        "beige stone": 3,
        **STONE_WORDS,
    },
    colours=roles(
        ("base", (222, 204, 170)), ("base_dark", (184, 160, 124), "base", ("base", -0.2))
    ),
    slots={"view": 2, "rough": 0.5},
    unit_m=0.3,
)
