"""Organic family: raw meat, citrus peel, carrot skin, coral, beeswax honeycomb, ivy on a wall,
foliage, dry leaves and feathers.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.snippets import HEX

recipe(
    "raw-meat",
    "organic",
    "raw marbled meat: deep red muscle with streaks of white fat",
    """
View(0, 0, {view}, {view})
Define(warp, fBm(octaves=5, base_freq=1.2, seed={seed:warp}))
Define(fat, Threshold(((0.08 - Abs(Sin((((X() * 2) + (Y() * 0.7)) + (warp * 5))))) * 12), below_at=0, above_at=1))
Define(fibre, fBm(octaves=4, base_freq_x={mf:8}, base_freq_y={mf:60}, to_01=True, seed={seed:fibre}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.35,base,fibre})
    .roughness(0.35)
    .subsurface(0.5)
    .coat(0.4)
    .height((fibre * {hv:0.004})),
  Layer(fat)
    .basecolor({rgb:fat_col})
    .roughness(0.4)
    .subsurface(0.4)
    .height((fat * {h:0.004}))
)""",
    tags={
        "meat": 7,
        "steak": 7,
        "beef": 7,
        "raw": 2,
        "marbled": 3,
        "flesh": 5,
        "pork": 6,
        "bacon": 6,
        "wagyu": 8,
        "butcher": 3,
        "muscle": 4,
        "lamb": 4,
    },
    colours=roles(("base", (170, 40, 44)), ("fat_col", (236, 218, 206), "accent")),
    slots={"view": 2, "rough": 0.35},
    unit_m=0.1,
)

recipe(
    "citrus-peel",
    "organic",
    "citrus peel: glossy dimpled skin with oil-gland pores",
    """
View(0, 0, {view}, {view})
Define(dimple, Worley(base_freq={mf:26}, to_01=True, seed={seed:dimple}))
Define(tone, fBm(octaves=4, base_freq=1.2, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.25,base,((dimple * 0.6) + (tone * 0.4))})
    .roughness(({rough} + (dimple * 0.15)))
    .subsurface(0.3)
    .coat(0.5)
    .height((dimple * {hv:0.012}))
)""",
    tags={
        "orange peel": 9,
        "citrus": 7,
        "peel": 4,
        "rind": 5,
        "zest": 5,
        "lemon": 5,
        "orange": 2,
        "lime": 3,
        "grapefruit": 6,
        "fruit skin": 5,
        "fruit": 2,
        "tangerine": 4,
    },
    colours=roles(("base", (236, 130, 30))),
    slots={"view": 1, "rough": 0.3},
    presets={
        "lemon": {"base": (240, 210, 50)},
        "lime": {"base": (120, 180, 50)},
        "grapefruit": {"base": (236, 150, 90)},
    },
    unit_m=0.05,
)

recipe(
    "carrot-skin",
    "organic",
    "carrot skin: orange root with fine rings and lengthwise streaks",
    """
View(0, 0, {view}, {view})
Define(ring, fBm(octaves=4, base_freq_x={mf:2}, base_freq_y={mf:26}, to_01=True, seed={seed:ring}))
Define(groove, Threshold(((0.38 - ring) * 20), below_at=0, above_at=1))
Define(streak, fBm(octaves=4, base_freq_x={mf:40}, base_freq_y={mf:3}, to_01=True, seed={seed:streak}))
Define(spot, Worley(base_freq={mf:8}, to_01=True, seed={seed:spot}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.2,base~0.1,((streak * 0.6) + (ring * 0.4))})
    .roughness(0.55)
    .subsurface(0.4)
    .height(((ring * {hv:0.006}) + (streak * {hv:0.002}))),
  Layer((groove * 0.8))
    .basecolor({rgb:base~-0.45})
    .roughness(0.8),
  Layer(Threshold(((0.05 - spot) * 40), below_at=0, above_at=0.7))
    .basecolor({rgb:base~-0.5})
    .roughness(0.9)
)""",
    tags={
        "carrot": 10,
        "carrots": 10,
        "parsnip": 8,
        "root vegetable": 7,
        "vegetable": 3,
        "sweet potato": 7,
        "skin": 1.5,
        "radish": 6,
    },
    colours=roles(("base", (236, 120, 30))),
    slots={"view": 1, "rough": 0.55},
    presets={"parsnip": {"base": (230, 214, 170)}, "sweet potato": {"base": (170, 90, 60)}},
    unit_m=0.03,
)

recipe(
    "coral",
    "organic",
    "brain coral: meandering ridges and valleys",
    """
View(0, 0, {view}, {view})
Define(meander, fBm(octaves=4, base_freq=2, seed={seed:meander}))
Define(ridge, Abs(Sin((meander * 24))))
Define(pore, fBm(octaves=3, base_freq={mf:80}, to_01=True, seed={seed:pore}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.4,base,((ridge * 0.8) + (pore * 0.2))})
    .roughness(0.85)
    .subsurface(0.2)
    .height(((ridge * {h:0.03}) + (pore * {hv:0.003})))
)""",
    tags={
        "coral": 8,
        "brain coral": 10,
        "reef": 5,
        "polyp": 6,
        "polyps": 6,
        "anemone": 5,
        "marine": 2,
        "sea": 1,
    },
    colours=roles(("base", (230, 170, 140))),
    slots={"view": 2, "rough": 0.85},
    unit_m=0.1,
)

recipe(
    "honeycomb-wax",
    "organic",
    "beeswax honeycomb: hexagonal wax cells filled with honey",
    "View(0, 0, {view}, {view})\n"
    + HEX
    + """
Define(wall, Threshold(((hexD - 0.43) * 40), below_at=0, above_at=1))
Define(fill, fBm(octaves=3, base_freq=1.5, to_01=True, seed={seed:fill}))
Material(
  Layer(1)
    .basecolor({mix:honey~-0.4,honey,(hexD * 2)})
    .roughness(0.1)
    .subsurface(0.5)
    .coat(1)
    .height((hexD * {h:0.04})),
  Layer(wall)
    .basecolor({mix:wax~-0.2,wax,fill})
    .roughness(0.5)
    .subsurface(0.4)
    .height((wall * {h:0.05}))
)""",
    tags={
        "honeycomb": 5,
        "beeswax": 6,
        "bee": 3,
        "bees": 3,
        "hive": 6,
        "wax": 3,
        "honey": 4,
        "comb": 3,
        "apiary": 6,
    },
    colours=roles(("honey", (214, 140, 30)), ("wax", (236, 200, 110), "accent")),
    slots={"view": 4, "rough": 0.3},
    patterns=("hexagon",),
    unit_m=0.006,
)

recipe(
    "ivy-wall",
    "organic",
    "ivy climbing over a rough wall: overlapping leaves, wall showing through",
    """
View(0, 0, {view}, {view})
Define(wall, fBm(octaves=5, base_freq=2, to_01=True, seed={seed:wall}))
Define(grit, fBm(octaves=3, base_freq={mf:80}, to_01=True, seed={seed:grit}))
Define(leafA, Rotate(Worley(distance="manhattan", base_freq_x={mf:9}, base_freq_y={mf:5}, to_01=True, seed={seed:leafA}), 25))
Define(leafB, Rotate(Worley(distance="manhattan", base_freq_x={mf:10}, base_freq_y={mf:6}, to_01=True, seed={seed:leafB}), -40))
Define(cover, fBm(octaves=4, base_freq=1.2, to_01=True, seed={seed:cover}))
Define(zone, Threshold(((cover - (0.6 - ({cover_amt} * 0.4))) * 10), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:wall_col~-0.3,wall_col,((wall * 0.6) + (grit * 0.4))})
    .roughness(0.95)
    .height(((wall * {h:0.03}) + (grit * {hv:0.005}))),
  Layer((zone * Threshold(((0.2 - leafA) * 40), below_at=0, above_at=1)))
    .basecolor({mix:leaf~0.15,leaf~-0.35,(leafA * 5)})
    .roughness(0.45)
    .sheen(0.3)
    .height(({h:0.04} + ((0.2 - leafA) * {hv:0.1}))),
  Layer((zone * Threshold(((0.18 - leafB) * 40), below_at=0, above_at=1)))
    .basecolor({mix:leaf~0.25,leaf~-0.2,(leafB * 5)})
    .roughness(0.45)
    .sheen(0.3)
    .height(({h:0.05} + ((0.18 - leafB) * {hv:0.1})))
)""",
    tags={
        "ivy": 9,
        "climbing": 3,
        "vine": 5,
        "vines": 5,
        "creeper": 6,
        "overgrown": 3,
        "wall": 1,
        "foliage": 2,
    },
    colours=roles(("leaf", (60, 110, 40)), ("wall_col", (170, 160, 146), "base")),
    slots={"view": 2, "rough": 0.6, "cover_amt": 0.6},
    unit_m=0.5,
)

recipe(
    "foliage",
    "organic",
    "dense foliage: layered leaves in varied greens",
    """
View(0, 0, {view}, {view})
Define(leafA, Rotate(Worley(distance="manhattan", base_freq_x={mf:9}, base_freq_y={mf:5}, to_01=True, seed={seed:leafA}), 20))
Define(leafB, Rotate(Worley(distance="manhattan", base_freq_x={mf:10}, base_freq_y={mf:6}, to_01=True, seed={seed:leafB}), -50))
Define(leafC, Rotate(Worley(distance="manhattan", base_freq_x={mf:12}, base_freq_y={mf:7}, to_01=True, seed={seed:leafC}), 95))
Material(
  Layer(1)
    .basecolor({rgb:leaf~-0.7})
    .roughness(0.9),
  Layer(Threshold(((0.26 - leafA) * 40), below_at=0, above_at=1))
    .basecolor({mix:leaf~0.1,leaf~-0.4,(leafA * 4)})
    .roughness(0.6)
    .height(({h:0.02} + ((0.26 - leafA) * {hv:0.08}))),
  Layer(Threshold(((0.24 - leafB) * 40), below_at=0, above_at=1))
    .basecolor({mix:leaf2~0.1,leaf2~-0.35,(leafB * 4)})
    .roughness(0.6)
    .height(({h:0.03} + ((0.24 - leafB) * {hv:0.08}))),
  Layer(Threshold(((0.2 - leafC) * 40), below_at=0, above_at=1))
    .basecolor({mix:leaf~0.2,leaf2~-0.2,(leafC * 5)})
    .roughness(0.6)
    .height(({h:0.04} + ((0.2 - leafC) * {hv:0.08})))
)""",
    tags={
        "foliage": 6,
        "leaves": 5,
        "leaf": 4,
        "leafy": 5,
        "hedge": 6,
        "bush": 5,
        "shrub": 5,
        "neem": 5,
        "herbs": 3,
        "plant": 3,
        "plants": 3,
        "tree": 1.5,
        "medicinal": 1,
        "jungle": 3,
        "canopy": 4,
        "dry leaves": 3,
        "autumn": 3,
        "fallen leaves": 6,
    },
    colours=roles(("leaf", (70, 120, 50)), ("leaf2", (110, 150, 60), "accent", ("leaf", 0.2))),
    slots={"view": 1, "rough": 0.6},
    presets={
        "autumn": {"leaf": (180, 90, 30), "leaf2": (210, 150, 50)},
        "dry": {"leaf": (150, 100, 50), "leaf2": (180, 140, 80)},
        "fallen": {"leaf": (160, 90, 40), "leaf2": (190, 140, 60)},
    },
    unit_m=0.3,
)

recipe(
    "feathers",
    "organic",
    "overlapping feathers: rows of vaned plumes with central shafts",
    """
View(0, 0, {view}, {view})
Define(row, Floor((Y() / 0.7)))
Define(fx, ((((X() / 0.5) + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor(((X() / 0.5) + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(fy, ((Y() / 0.7) - row))
Define(vane, Threshold((((0.5 * Sqrt(Sin((fy * 3.1416)))) - Abs(fx)) * 30), below_at=0, above_at=1))
Define(barb, Abs(Sin((((Abs(fx) * 24) - (fy * 14)) * 3.1416))))
Define(shaft, Threshold(((0.03 - Abs(fx)) * 60), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.6})
    .roughness(0.8),
  Layer(vane)
    .basecolor({mix:base~-0.3,base,((barb * 0.4) + (fy * 0.6))})
    .roughness(0.6)
    .sheen(0.6)
    .height((vane * ((fy * {h:0.03}) + (barb * {h:0.004})))),
  Layer((vane * Threshold(((fy - 0.7) * 10), below_at=0, above_at=1)))
    .basecolor({rgb:tip})
    .roughness(0.5)
    .sheen(0.6),
  Layer((shaft * vane))
    .basecolor({rgb:base~0.5})
    .roughness(0.4)
)""",
    tags={
        "feather": 8,
        "feathers": 8,
        "plumage": 8,
        "plume": 6,
        "quill": 5,
        "bird": 3,
        "down": 1,
        "inlays": 1,
    },
    colours=roles(("base", (90, 110, 150)), ("tip", (40, 140, 130), "accent")),
    slots={"view": 3, "rough": 0.6},
    patterns=("scales",),
    unit_m=0.05,
)
