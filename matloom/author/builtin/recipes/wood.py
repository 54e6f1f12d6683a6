"""Wood family: planks, panels, parquet, herringbone, plywood, bark, end grain, spalted wood,
bamboo, OSB, cork and wicker.

Shared idioms: per-board colour from the Floor-cell sin hash (``cell`` -> ``tone``), grain from
an fBm stretched along the board (anisotropic striation), figure lines from a noise-warped
``Sin`` band, and a dark gap layer under the boards whose coverage is the board mask.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.snippets import HERRINGBONE

#: species and finish words -> wood colours (light tone; the dark tone derives from it).
WOOD_PRESETS = {
    "oak": {"wood": (178, 132, 84)},
    "pine": {"wood": (216, 178, 122)},
    "birch": {"wood": (224, 198, 154)},
    "maple": {"wood": (222, 184, 134)},
    "cherry": {"wood": (166, 90, 56)},
    "mahogany": {"wood": (128, 56, 36)},
    "walnut": {"wood": (112, 74, 48)},
    "ebony": {"wood": (52, 40, 34)},
    "teak": {"wood": (168, 116, 64)},
    "ash": {"wood": (206, 182, 146)},
    "cedar": {"wood": (176, 104, 64)},
    "beech": {"wood": (212, 164, 114)},
    "rosewood": {"wood": (110, 46, 32)},
    "redwood": {"wood": (158, 76, 50)},
    "spruce": {"wood": (222, 194, 146)},
    "driftwood": {"wood": (176, 166, 150)},
    "reclaimed": {"wood": (150, 118, 88)},
    "bleached": {"wood": (214, 200, 178)},
    "wenge": {"wood": (70, 50, 40)},
    "acacia": {"wood": (170, 110, 60)},
    "elm": {"wood": (176, 130, 90)},
    "hickory": {"wood": (190, 150, 106)},
}
WOOD_WORDS = {w: 2.5 for w in WOOD_PRESETS} | {
    "wood": 2.0,
    "wooden": 2.0,
    "timber": 2.0,
    "hardwood": 2.5,
    "lumber": 2.0,
}
WOOD_ROLES = roles(
    ("wood", (176, 126, 80)),
    ("wood_dark", (110, 72, 44), "base", ("wood", -0.42)),
    ("gap", (38, 27, 20), "grout", ("wood", -0.8)),
)

recipe(
    "wood-planks",
    "wood",
    "horizontal floor planks with staggered joints, grain and figure",
    """
View(0, 0, {view}, {view})
Define(plank, Bricks(brick_width=2.6, brick_height=0.42, offset=0.38, mortar={gap}, feather=0.01))
Define(row, Floor((Y() / 0.42)))
Define(cell, (Sin(((Floor(((X() - (row * 0.988)) / 2.6)) * 12.9898) + (row * 78.233))) * 43758.5453))
Define(tone, (cell - Floor(cell)))
Define(grain, fBm(octaves=5, base_freq_x=0.5, base_freq_y=16, to_01=True, seed={seed:grain}))
Define(figure, Abs(Sin(((((Y() * 7) + (grain * 5)) + (tone * 9)) * 3.1416))))
Define(woodTone, (((grain * 0.45) + (figure * 0.2)) + (tone * 0.45)))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(plank)
    .basecolor({mix:wood,wood_dark,woodTone})
    .roughness(({rough} + (grain * 0.12)))
    .coat({coat})
    .height((plank * ({h:0.012} + (grain * {h:0.003}))))
)""",
    tags={
        "plank": 3,
        "planks": 3,
        "floor": 1.5,
        "flooring": 1.5,
        "floorboard": 3,
        "board": 2,
        "deck": 2,
        "decking": 2.5,
        "parquet": 0.5,
        "tile": 0.5,
        **WOOD_WORDS,
    },
    colours=WOOD_ROLES,
    slots={"view": 4, "rough": 0.55, "gap": 0.025, "coat": 0.2},
    presets=WOOD_PRESETS,
    count_nouns=("plank", "board", "row"),
    repeat=0.42,
    unit_m=0.33,
)

recipe(
    "wood-panels",
    "wood",
    "vertical wall panelling boards with V-grooves",
    """
View(0, 0, {view}, {view})
Define(board, Translate(Bricks(brick_width=0.62, brick_height=100, offset=0, mortar={gap}, feather=0.012), 0, 50))
Define(cell, (Sin((Floor((X() / 0.62)) * 12.9898)) * 43758.5453))
Define(tone, (cell - Floor(cell)))
Define(grain, fBm(octaves=5, base_freq_x=14, base_freq_y=0.45, to_01=True, seed={seed:grain}))
Define(figure, Abs(Sin(((((X() * 6) + (grain * 5)) + (tone * 7)) * 3.1416))))
Define(woodTone, (((grain * 0.45) + (figure * 0.2)) + (tone * 0.4)))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(board)
    .basecolor({mix:wood,wood_dark,woodTone})
    .roughness(({rough} + (grain * 0.1)))
    .height((board * ({h:0.012} + (grain * {h:0.003}))))
)""",
    tags={
        "panel": 3,
        "panels": 3,
        "paneling": 3,
        "panelling": 3,
        "wall": 1,
        "cladding": 2.5,
        "wainscot": 3,
        "siding": 2.5,
        "slat": 2,
        "wainscoting": 3,
        **WOOD_WORDS,
    },
    colours=WOOD_ROLES,
    slots={"view": 3, "rough": 0.5, "gap": 0.03},
    presets=WOOD_PRESETS,
    count_nouns=("panel", "board", "slat"),
    repeat=0.62,
    unit_m=0.25,
)

recipe(
    "wood-parquet",
    "wood",
    "basket-weave parquet: square blocks of four slats alternating",
    """
View(0, 0, {view}, {view})
Define(checker, Threshold((Sin((X() * 3.1416)) * Sin((Y() * 3.1416))), below_at=0, above_at=0, above_to=1))
Define(slats, ((checker * Bricks(brick_width=1, brick_height=0.25, offset=0, mortar={gap}, feather=0.01)) + ((1 - checker) * Bricks(brick_width=0.25, brick_height=1, offset=0, mortar={gap}, feather=0.01))))
Define(cellH, (Sin(((Floor(X()) * 12.9898) + (Floor((Y() * 4)) * 78.233))) * 43758.5453))
Define(cellV, (Sin(((Floor((X() * 4)) * 12.9898) + (Floor(Y()) * 78.233))) * 43758.5453))
Define(tone, ((checker * (cellH - Floor(cellH))) + ((1 - checker) * (cellV - Floor(cellV)))))
Define(grainH, fBm(octaves=4, base_freq_x=1, base_freq_y=24, to_01=True, seed={seed:grainH}))
Define(grainV, fBm(octaves=4, base_freq_x=24, base_freq_y=1, to_01=True, seed={seed:grainV}))
Define(woodTone, ((((checker * grainH) + ((1 - checker) * grainV)) * 0.55) + (tone * 0.45)))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(slats)
    .basecolor({mix:wood,wood_dark,woodTone})
    .roughness(({rough} + (woodTone * 0.1)))
    .coat({coat})
    .height((slats * {h:0.01}))
)""",
    tags={
        "parquet": 4,
        "parquetry": 4,
        "basketweave": 1.5,
        "block": 1,
        "floor": 1.5,
        "flooring": 1.5,
        **WOOD_WORDS,
    },
    colours=WOOD_ROLES,
    slots={"view": 3, "rough": 0.45, "gap": 0.02, "coat": 0.3},
    patterns=("checker", "basketweave", "squares"),
    presets=WOOD_PRESETS,
    count_nouns=("block",),
    repeat=1.0,
    unit_m=0.3,
)

recipe(
    "wood-herringbone",
    "wood",
    "herringbone parquet: columns of planks at alternating 45 degrees",
    """
View(0, 0, {view}, {view})
"""
    + HERRINGBONE
    + """
Define(plank, Threshold(((hbEdge - {gap}) * 60), below_at=0, above_at=1))
Define(grainU, Rotate(fBm(octaves=4, base_freq_x=1, base_freq_y=22, to_01=True, seed={seed:grainU}), 45))
Define(grainV, Rotate(fBm(octaves=4, base_freq_x=1, base_freq_y=22, to_01=True, seed={seed:grainV}), -45))
Define(woodTone, ((((hbHoriz * grainU) + ((1 - hbHoriz) * grainV)) * 0.55) + (hbTone * 0.45)))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(plank)
    .basecolor({mix:wood,wood_dark,woodTone})
    .roughness(({rough} + (woodTone * 0.1)))
    .coat({coat})
    .height((plank * {h:0.01}))
)""",
    tags={"floor": 1.5, "flooring": 1.5, "parquet": 2, **WOOD_WORDS},
    colours=WOOD_ROLES,
    slots={"view": 4, "rough": 0.45, "gap": 0.035, "coat": 0.3, "hb_w": 0.3},
    patterns=("herringbone", "zigzag"),
    presets=WOOD_PRESETS,
    unit_m=0.3,
)

recipe(
    "plywood",
    "wood",
    "rotary-cut plywood sheet: broad wavy figure, fine grain, sheet seams",
    """
View(0, 0, {view}, {view})
Define(sheet, Translate(Bricks(brick_width=2.4, brick_height=1.2, offset=0.5, mortar=0.012, feather=0.004), 0.3, 0.2))
Define(warp, fBm(octaves=4, base_freq_x=0.4, base_freq_y=1.5, seed={seed:warp}))
Define(figure, Abs(Sin((((Y() * 3) + (warp * 3)) * 3.1416))))
Define(grain, fBm(octaves=5, base_freq_x=0.6, base_freq_y=30, to_01=True, seed={seed:grain}))
Define(woodTone, ((figure * 0.5) + (grain * 0.5)))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(sheet)
    .basecolor({mix:wood,wood_dark,woodTone})
    .roughness(({rough} + (grain * 0.1)))
    .height((sheet * ({h:0.004} + (grain * {h:0.002}))))
)""",
    tags={"plywood": 5, "ply": 3, "veneer": 3, "sheet": 1, **WOOD_WORDS},
    colours=roles(
        ("wood", (222, 188, 140)),
        ("wood_dark", (170, 128, 84), "base", ("wood", -0.3)),
        ("gap", (70, 52, 36), "grout", ("wood", -0.7)),
    ),
    slots={"view": 2.4, "rough": 0.7},
    presets=WOOD_PRESETS,
    unit_m=0.5,
)

recipe(
    "tree-bark",
    "wood",
    "rugged tree bark: vertical ridged plates split by deep furrows",
    """
View(0, 0, {view}, {view})
Define(plates, Worley(combination="F2-F1", base_freq_x=3.5, base_freq_y=0.9, to_01=True, seed={seed:plates}))
Define(ridge, fBm(octaves=6, base_freq_x=10, base_freq_y=2, to_01=True, seed={seed:ridge}))
Define(furrow, Threshold((plates * 5), above_at=1))
Define(fine, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:fine}))
Material(
  Layer(1)
    .basecolor({mix:furrow_col,wood,((furrow * 0.7) + (ridge * 0.3))})
    .roughness((0.85 + (fine * 0.12)))
    .height((((furrow * {h:0.08}) + (ridge * {h:0.05})) + (fine * {hv:0.006})))
)""",
    tags={"bark": 5, "tree": 1.5, "trunk": 2.5, "birch bark": 2, "pine bark": 2},
    colours=roles(("wood", (120, 100, 80)), ("furrow_col", (40, 32, 26), "base", ("wood", -0.7))),
    slots={"view": 2, "rough": 0.9},
    presets={
        "birch": {"wood": (200, 194, 184)},
        "pine": {"wood": (120, 80, 56)},
        "oak": {"wood": (110, 96, 80)},
    },
    unit_m=0.2,
)

recipe(
    "wood-end-grain",
    "wood",
    "end-grain cross section: warped concentric growth rings",
    """
View(-{view*0.5}, -{view*0.5}, {view*0.5}, {view*0.5})
Define(warp, fBm(octaves=4, base_freq=1.2, seed={seed:warp}))
Define(rings, Abs(Sin((((Sqrt(((X() * X()) + (Y() * Y()))) * 9) + (warp * 1.5)) * 3.1416))))
Define(pores, fBm(octaves=3, base_freq={mf:60}, to_01=True, seed={seed:pores}))
Material(
  Layer(1)
    .basecolor({mix:wood,wood_dark,((rings * 0.7) + (pores * 0.3))})
    .roughness(({rough} + (pores * 0.1)))
    .height(((rings * {h:0.006}) + (pores * {hv:0.002})))
)""",
    tags={
        "end grain": 5,
        "rings": 2.5,
        "tree rings": 4,
        "growth rings": 4,
        "stump": 3.5,
        "log": 3,
        "cross section": 3.5,
        "slice": 2,
        "butcher block": 3,
        **WOOD_WORDS,
    },
    colours=roles(("wood", (206, 160, 108)), ("wood_dark", (140, 92, 56), "base", ("wood", -0.4))),
    slots={"view": 2, "rough": 0.7},
    presets=WOOD_PRESETS,
    unit_m=0.25,
)

recipe(
    "spalted-wood",
    "wood",
    "spalted wood: pale timber with black zone lines and grey decay blotches",
    """
View(0, 0, {view}, {view})
Define(grain, fBm(octaves=5, base_freq_x=0.8, base_freq_y=14, to_01=True, seed={seed:grain}))
Define(zones, fBm(octaves=5, base_freq=0.9, to_01=True, seed={seed:zones}))
Define(zoneLine, Threshold(((0.14 - Abs(Sin((zones * 34)))) * 10), below_at=0, above_at=1))
Define(decay, Threshold(((fBm(octaves=5, base_freq=1.3, to_01=True, seed={seed:decay}) - 0.46) * 5), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:wood,wood_dark,grain})
    .roughness(({rough} + (grain * 0.1)))
    .height((grain * {h:0.003})),
  Layer((decay * 0.6))
    .basecolor({rgb:decay_col})
    .roughness(0.8),
  Layer(zoneLine)
    .basecolor({rgb:line})
    .roughness(0.8)
)""",
    tags={"spalted": 6, "spalting": 6, "decay": 1.5, "zone lines": 3, "decayed": 1.5, **WOOD_WORDS},
    colours=roles(
        ("wood", (226, 206, 170)),
        ("line", (24, 20, 18), "accent"),
        ("decay_col", (150, 140, 128), "accent"),
        ("wood_dark", (190, 160, 120), "base", ("wood", -0.18)),
    ),
    slots={"view": 2.5, "rough": 0.55},
    presets=WOOD_PRESETS,
    unit_m=0.2,
)

recipe(
    "bamboo",
    "wood",
    "bamboo culms side by side with raised node rings",
    """
View(0, 0, {view}, {view})
Define(culm, Translate(Bricks(brick_width=0.7, brick_height=100, offset=0, mortar=0.04, feather=0.03), 0, 50))
Define(round, Abs(Sin(((X() / 0.7) * 3.1416))))
Define(nodeRow, ((Y() + (Floor((X() / 0.7)) * 0.77)) / 1.9))
Define(node, Threshold(((0.05 - Abs(((nodeRow - Floor(nodeRow)) - 0.5))) * 40), below_at=0, above_at=1))
Define(streak, fBm(octaves=4, base_freq_x=30, base_freq_y=1, to_01=True, seed={seed:streak}))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(culm)
    .basecolor({mix:wood_dark,wood,((round * 0.7) + (streak * 0.3))})
    .roughness(({rough} + (node * 0.2)))
    .coat(0.4)
    .height((culm * (((round * {h:0.05}) + (node * {h:0.012})) + 0.01))),
  Layer((node * culm))
    .basecolor({rgb:wood_dark})
    .roughness(0.6)
)""",
    tags={"bamboo": 5, "cane": 2.5, "culm": 4, "stalk": 2},
    colours=roles(
        ("wood", (206, 180, 110)),
        ("wood_dark", (150, 120, 64), "base", ("wood", -0.3)),
        ("gap", (46, 38, 24), "grout", ("wood", -0.8)),
    ),
    slots={"view": 3.5, "rough": 0.4},
    count_nouns=("culm", "stalk", "pole"),
    repeat=0.7,
    unit_m=0.05,
)

recipe(
    "osb-board",
    "wood",
    "oriented strand board: overlapping flat wood flakes in random directions",
    """
View(0, 0, {view}, {view})
Define(flakeA, Rotate(fBm(octaves=2, base_freq_x=2.5, base_freq_y=9, to_01=True, seed={seed:flakeA}), 20))
Define(flakeB, Rotate(fBm(octaves=2, base_freq_x=2.5, base_freq_y=9, to_01=True, seed={seed:flakeB}), -35))
Define(flakeC, Rotate(fBm(octaves=2, base_freq_x=2.5, base_freq_y=9, to_01=True, seed={seed:flakeC}), 80))
Define(grain, fBm(octaves=4, base_freq_x={mf:10}, base_freq_y={mf:60}, to_01=True, seed={seed:grain}))
Material(
  Layer(1)
    .basecolor({mix:wood_dark,wood,grain})
    .roughness(0.8)
    .height((grain * {hv:0.002})),
  Layer(Threshold(((flakeA - 0.55) * 30), below_at=0, above_at=1))
    .basecolor({mix:wood~0.15,wood_dark,grain})
    .roughness(0.75)
    .height({h:0.004}),
  Layer(Threshold(((flakeB - 0.55) * 30), below_at=0, above_at=1))
    .basecolor({mix:wood,wood_dark~-0.1,grain})
    .roughness(0.75)
    .height({h:0.006}),
  Layer(Threshold(((flakeC - 0.56) * 30), below_at=0, above_at=1))
    .basecolor({mix:wood~0.08,wood_dark,grain})
    .roughness(0.75)
    .height({h:0.008})
)""",
    tags={
        "osb": 6,
        "oriented strand": 6,
        "chipboard": 5,
        "particle board": 5,
        "particleboard": 5,
        "strand board": 6,
        "chip": 1.5,
        "chips": 1.5,
        "flake": 1.5,
    },
    colours=roles(
        ("wood", (214, 172, 112)), ("wood_dark", (150, 110, 66), "base", ("wood", -0.35))
    ),
    slots={"view": 1.5, "rough": 0.8},
    unit_m=0.2,
)

recipe(
    "cork",
    "wood",
    "cork board: packed tan granules with dark pores",
    """
View(0, 0, {view}, {view})
Define(granule, Worley(base_freq={mf:14}, to_01=True, seed={seed:granule}))
Define(mottle, fBm(octaves=5, base_freq={mf:10}, to_01=True, seed={seed:mottle}))
Define(pore, Threshold(((fBm(octaves=3, base_freq={mf:40}, to_01=True, seed={seed:pore}) - 0.66) * 20), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:wood,wood_dark,((granule * 0.3) + (mottle * 0.7))})
    .roughness(0.9)
    .height(((1 - granule) * {hv:0.004})),
  Layer((pore * 0.8))
    .basecolor({rgb:wood_dark~-0.4})
    .roughness(1)
)""",
    tags={"cork": 6, "corkboard": 6, "bulletin": 2, "pinboard": 3},
    colours=roles(("wood", (196, 146, 96)), ("wood_dark", (130, 86, 52), "base", ("wood", -0.35))),
    slots={"view": 1, "rough": 0.9},
    unit_m=0.1,
)

recipe(
    "wicker",
    "wood",
    "woven wicker / rattan: broad cane strips over and under",
    """
View(0, 0, {view}, {view})
Define(weave, Weave(base_freq=4, warp_width=0.82, feather=0.25))
Define(grain, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:grain}))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(weave)
    .basecolor({mix:wood_dark,wood,((weave * 0.7) + (grain * 0.3))})
    .roughness(({rough} + (grain * 0.1)))
    .height((weave * ({h:0.03} + (grain * {hv:0.004}))))
)""",
    tags={
        "wicker": 6,
        "rattan": 6,
        "basket": 2.5,
        "cane": 2,
        "woven": 1,
        "seagrass": 4,
        "straw": 2,
        "willow": 3,
    },
    colours=roles(
        ("wood", (206, 168, 110)),
        ("wood_dark", (150, 110, 64), "base", ("wood", -0.35)),
        ("gap", (40, 30, 20), "grout", ("wood", -0.8)),
    ),
    slots={"view": 2, "rough": 0.6},
    patterns=("basketweave", "weave"),
    unit_m=0.1,
)
