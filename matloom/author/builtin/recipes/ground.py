"""Ground family: sand, gravel, pebbles, soil, grass, moss, forest floor, snow, mud, cracked
earth and salt flats.

Natural ground stacks a continuous substrate with scattered discrete elements (stones, leaves,
tufts) masked by thresholded Worley (islands) or fBm (blobs), each with its own colour range,
and keeps relief in the height of the elements so the fixed light picks them out.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

GROUND = {"ground": 1.5, "terrain": 1.5, "floor": 0.5, "outdoor": 1, "landscape": 1}

recipe(
    "sand",
    "ground",
    "sand: wind ripples over fine grains",
    """
View(0, 0, {view}, {view})
Define(warp, fBm(octaves=4, base_freq=0.7, seed={seed:warp}))
Define(ripple, Abs(Sin(((((Y() * 5) + (X() * 1.2)) + (warp * 3)) * 3.1416))))
Define(grain, fBm(octaves=3, base_freq={mf:120}, to_01=True, seed={seed:grain}))
Define(tone, fBm(octaves=3, base_freq=1.2, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.18,base,(((grain * 0.4) + (ripple * 0.3)) + (tone * 0.3))})
    .roughness(0.95)
    .height((((ripple * {h:0.02}) + (tone * {h:0.02})) + (grain * {hv:0.003})))
)""",
    tags={
        "sand": 6,
        "sandy": 4,
        "beach": 3,
        "desert": 3,
        "dune": 5,
        "dunes": 5,
        "kinetic": 2,
        "toy sand": 3,
        "sandbox": 4,
        **GROUND,
    },
    colours=roles(("base", (222, 196, 150))),
    slots={"view": 2, "rough": 0.95},
    presets={"black sand": {"base": (60, 58, 56)}},
    unit_m=0.5,
)

recipe(
    "kinetic-sand",
    "ground",
    "moulded sand: smooth sculpted clumps with sharp cut edges",
    """
View(0, 0, {view}, {view})
Define(clump, Worley(base_freq=1.6, to_01=True, seed={seed:clump}))
Define(cut, Worley(combination="F2-F1", base_freq=1.6, to_01=True, seed={seed:clump}))
Define(grain, fBm(octaves=3, base_freq={mf:110}, to_01=True, seed={seed:grain}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.25,base,((Min((cut * 4), 1) * 0.6) + (grain * 0.4))})
    .roughness(0.9)
    .height((((1 - clump) * {h:0.08}) + (grain * {hv:0.004})))
)""",
    tags={
        "kinetic sand": 9,
        "kinetic": 4,
        "moldable": 4,
        "sculpting": 3,
        "play sand": 5,
        "moon sand": 6,
        "sculpted": 2,
        "sand": 2,
    },
    colours=roles(("base", (214, 184, 140))),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.2,
)

recipe(
    "gravel",
    "ground",
    "gravel: densely packed small angular stones in mixed greys",
    """
View(0, 0, {view}, {view})
Define(stone, Worley(base_freq={mf:14}, to_01=True, seed={seed:stone}))
Define(gap, Worley(combination="F2-F1", base_freq={mf:14}, to_01=True, seed={seed:stone}))
Define(tone, fBm(octaves=2, base_freq={mf:14}, to_01=True, seed={seed:tone}))
Define(grit, fBm(octaves=3, base_freq={mf:80}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.6,base~-0.3,grit})
    .roughness(0.95),
  Layer(Threshold(((gap - 0.06) * 30), below_at=0, above_at=1))
    .basecolor({mix:base_dark,base,((tone * 0.7) + (grit * 0.3))})
    .roughness(({rough} + (grit * 0.1)))
    .height((((1 - stone) * {hv:0.02}) + (grit * {hv:0.003})))
)""",
    tags={
        "gravel": 7,
        "crushed stone": 6,
        "aggregate": 3,
        "shingle": 4,
        "driveway": 2,
        "chippings": 5,
        "ballast": 5,
        "scree": 5,
        **GROUND,
    },
    colours=roles(("base", (168, 162, 154)), ("base_dark", (104, 100, 96), "base", ("base", -0.4))),
    slots={"view": 1, "rough": 0.8},
    unit_m=0.3,
)

recipe(
    "pebbles",
    "ground",
    "rounded pebbles of assorted colours, smooth and domed",
    """
View(0, 0, {view}, {view})
Define(pebble, Worley(base_freq={mf:6}, to_01=True, seed={seed:pebble}))
Define(gap, Worley(combination="F2-F1", base_freq={mf:6}, to_01=True, seed={seed:pebble}))
Define(tone, fBm(octaves=2, base_freq={mf:7}, to_01=True, seed={seed:tone}))
Define(speck, fBm(octaves=3, base_freq={mf:60}, to_01=True, seed={seed:speck}))
Define(round, Threshold(((gap - 0.08) * 12), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:gap_col})
    .roughness(0.95),
  Layer(round)
    .basecolor({mix:base,base_alt,((tone * 0.8) + (speck * 0.2))})
    .roughness(({rough} + (speck * 0.1)))
    .height((Sqrt(round) * ({hv:0.05} + ((1 - pebble) * {hv:0.03}))))
)""",
    tags={
        "pebbles": 7,
        "pebble": 7,
        "river rock": 7,
        "river stones": 7,
        "stones": 2,
        "beach": 1.5,
        "rounded": 2,
        "smooth stones": 6,
        "cobble": 1,
        **GROUND,
    },
    colours=roles(
        ("base", (176, 166, 150)),
        ("base_alt", (110, 104, 100), "base", ("base", -0.4)),
        ("gap_col", (60, 54, 46), "grout"),
    ),
    slots={"view": 1, "rough": 0.5},
    unit_m=0.3,
)

recipe(
    "soil",
    "ground",
    "soil: brown earth with clods, grit and small stones",
    """
View(0, 0, {view}, {view})
Define(clod, fBm(octaves=6, base_freq=2, to_01=True, seed={seed:clod}))
Define(grit, fBm(octaves=3, base_freq={mf:90}, to_01=True, seed={seed:grit}))
Define(stoneCell, Worley(base_freq={mf:10}, to_01=True, seed={seed:stone}))
Define(stone, Threshold(((0.12 - stoneCell) * 30), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.35,base,((clod * 0.7) + (grit * 0.3))})
    .roughness(0.98)
    .height(((clod * {h:0.05}) + (grit * {hv:0.005}))),
  Layer(stone)
    .basecolor({mix:stone_col~-0.2,stone_col,grit})
    .roughness(0.8)
    .height((stone * ({h:0.05} + ((1 - stoneCell) * {hv:0.01}))))
)""",
    tags={
        "soil": 7,
        "dirt": 6,
        "earth": 4,
        "loam": 6,
        "topsoil": 7,
        "garden": 2,
        "field": 1.5,
        "plowed": 4,
        "compost": 5,
        "dirt road": 5,
        **GROUND,
    },
    colours=roles(("base", (104, 76, 52)), ("stone_col", (150, 140, 126), "accent")),
    slots={"view": 1.5, "rough": 0.98},
    unit_m=0.4,
)

recipe(
    "grass",
    "ground",
    "grass: dense blades in mixed greens with darker roots",
    """
View(0, 0, {view}, {view})
Define(bladeA, fBm(octaves=3, base_freq_x={mf:90}, base_freq_y={mf:12}, to_01=True, seed={seed:bladeA}))
Define(bladeB, Rotate(fBm(octaves=3, base_freq_x={mf:90}, base_freq_y={mf:12}, to_01=True, seed={seed:bladeB}), 20))
Define(patch, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:patch}))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.65})
    .roughness(0.9),
  Layer(Threshold(((bladeA - 0.45) * 8), below_at=0, above_at=1))
    .basecolor({mix:base~-0.3,base,((bladeA * 0.6) + (patch * 0.4))})
    .roughness(0.8)
    .sheen(0.3)
    .height((bladeA * {hv:0.02})),
  Layer(Threshold(((bladeB - 0.55) * 8), below_at=0, above_at=1))
    .basecolor({mix:base,tip,patch})
    .roughness(0.8)
    .height((bladeB * {hv:0.025}))
)""",
    tags={
        "grass": 7,
        "grassy": 6,
        "lawn": 7,
        "turf": 7,
        "meadow": 5,
        "field": 1.5,
        "pasture": 5,
        "hay": 2,
        **GROUND,
    },
    colours=roles(("base", (76, 130, 48)), ("tip", (150, 170, 70), "accent", ("base", 0.3))),
    slots={"view": 1, "rough": 0.8},
    presets={"dry": {"base": (170, 150, 80)}, "dead": {"base": (160, 140, 80)}},
    unit_m=0.3,
)

recipe(
    "moss",
    "ground",
    "moss: soft cushions of tiny green fronds in light and dark tufts",
    """
View(0, 0, {view}, {view})
Define(clump, Worley(base_freq={mf:7}, to_01=True, seed={seed:clump}))
Define(cushion, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:cushion}))
Define(frond, fBm(octaves=4, base_freq={mf:90}, to_01=True, seed={seed:frond}))
Material(
  Layer(1)
    .basecolor({mix:base~0.15,base~-0.6,((clump * 1.2) + (frond * 0.3))})
    .roughness(0.95)
    .sheen(0.5)
    .height(((((1 - clump) * {hv:0.04}) + (cushion * {h:0.03})) + (frond * {hv:0.006}))),
  Layer(Threshold(((frond - 0.62) * 10), below_at=0, above_at=0.6))
    .basecolor({rgb:tip})
    .roughness(0.95)
)""",
    tags={"moss": 7, "mossy": 4, "lichen": 4, "moss covered": 5, "sphagnum": 7, "bryophyte": 7},
    colours=roles(("base", (92, 124, 40)), ("tip", (160, 180, 70), "accent", ("base", 0.35))),
    slots={"view": 1, "rough": 0.95},
    unit_m=0.3,
)

recipe(
    "forest-floor",
    "ground",
    "forest floor: leaf litter, twigs and roots, rocks and moss on soil",
    """
View(0, 0, {view}, {view})
Define(soilN, fBm(octaves=5, base_freq=2, to_01=True, seed={seed:soil}))
Define(leaf, Min(Rotate(Worley(distance="manhattan", base_freq_x={mf:10}, base_freq_y={mf:6}, to_01=True, seed={seed:leaf}), 30), Rotate(Worley(distance="manhattan", base_freq_x={mf:9}, base_freq_y={mf:5}, to_01=True, seed={seed:leaf2}), -55)))
Define(leafTone, fBm(octaves=2, base_freq={mf:10}, to_01=True, seed={seed:leafTone}))
Define(root, fBm(octaves=4, base_freq_x={mf:1.5}, base_freq_y={mf:5}, to_01=True, seed={seed:root}))
Define(rockN, fBm(octaves=5, base_freq=1.6, to_01=True, seed={seed:rock}))
Define(mossN, fBm(octaves=4, base_freq=1.8, to_01=True, seed={seed:moss}))
Material(
  Layer(1)
    .basecolor({mix:soil_col~-0.3,soil_col,soilN})
    .roughness(0.95)
    .height((soilN * {h:0.02})),
  Layer(Threshold(((0.22 - leaf) * 40), below_at=0, above_at=1))
    .basecolor({mix:leaf_a,leaf_b,((leafTone * 0.7) + (leaf * 1.5))})
    .roughness(0.8)
    .height(({h:0.02} + ((0.22 - leaf) * {hv:0.05}))),
  Layer(Threshold(((0.03 - Abs((root - 0.5))) * 40), below_at=0, above_at=1))
    .basecolor({rgb:root_col})
    .roughness(0.8)
    .height({h:0.035}),
  Layer(Threshold(((rockN - 0.64) * 25), below_at=0, above_at=1))
    .basecolor({mix:rock_col~-0.35,rock_col,((leafTone * 0.5) + ((rockN - 0.5) * 2))})
    .roughness(0.85)
    .height(({h:0.04} + ((rockN - 0.64) * {h:0.4}))),
  Layer(Threshold(((mossN - 0.6) * 10), below_at=0, above_at=1))
    .basecolor({mix:moss_col~-0.3,moss_col,leafTone})
    .roughness(0.95)
    .sheen(0.4)
    .height({h:0.03})
)""",
    tags={
        "forest floor": 9,
        "forest": 3,
        "leaf litter": 8,
        "woodland": 4,
        "roots": 3,
        "twigs": 3,
        "undergrowth": 5,
        "jungle floor": 7,
        "rocks": 1.5,
        "duff": 5,
        **GROUND,
    },
    colours=roles(
        ("soil_col", (72, 54, 36)),
        ("leaf_a", (150, 90, 40), "accent"),
        ("leaf_b", (100, 70, 34), "accent"),
        ("root_col", (96, 70, 46), "accent"),
        ("rock_col", (128, 124, 116), "accent"),
        ("moss_col", (90, 120, 40), "accent"),
    ),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.5,
)

recipe(
    "snow",
    "ground",
    "snow: soft white drifts with cool blue shadows and sparkle",
    """
View(0, 0, {view}, {view})
Define(drift, fBm(octaves=5, base_freq=1.2, to_01=True, seed={seed:drift}))
Define(crust, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:crust}))
Define(sparkle, Worley(base_freq={mf:70}, to_01=True, seed={seed:sparkle}))
Material(
  Layer(1)
    .basecolor({mix:shadow,base,((drift * 0.7) + (crust * 0.3))})
    .roughness(0.7)
    .sheen(0.3)
    .subsurface(0.3)
    .height(((drift * {h:0.06}) + (crust * {hv:0.004}))),
  Layer(Threshold(((0.04 - sparkle) * 40), below_at=0, above_at=1))
    .basecolor(255, 255, 255)
    .roughness(0.05)
    .coat(1)
)""",
    tags={
        "snow": 7,
        "snowy": 5,
        "powder": 2,
        "frost": 3,
        "frosty": 3,
        "winter": 2,
        "slush": 4,
        "drift": 2,
        "snowfield": 7,
        **GROUND,
    },
    colours=roles(("base", (244, 246, 250)), ("shadow", (196, 210, 230), "base", ("base", -0.12))),
    slots={"view": 2, "rough": 0.7},
    unit_m=0.5,
)

recipe(
    "mud",
    "ground",
    "mud: wet brown sludge with glossy puddles",
    """
View(0, 0, {view}, {view})
Define(sludge, fBm(octaves=6, base_freq=1.5, to_01=True, seed={seed:sludge}))
Define(grit, fBm(octaves=3, base_freq={mf:70}, to_01=True, seed={seed:grit}))
Define(puddle, Threshold(((0.42 - sludge) * 12), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.3,base,((sludge * 0.7) + (grit * 0.3))})
    .roughness((0.6 + (grit * 0.3)))
    .height(((sludge * {h:0.05}) + (grit * {hv:0.004}))),
  Layer(puddle)
    .basecolor({rgb:base~-0.45})
    .roughness(0.04)
    .coat(1)
)""",
    tags={
        "mud": 8,
        "muddy": 5,
        "sludge": 6,
        "swamp": 4,
        "bog": 5,
        "wet soil": 6,
        "wet earth": 6,
        "clay": 2,
        "marsh": 4,
        **GROUND,
    },
    colours=roles(("base", (100, 74, 50))),
    slots={"view": 2, "rough": 0.6},
    unit_m=0.5,
)

recipe(
    "cracked-earth",
    "ground",
    "dry cracked earth: curled polygonal mud plates with deep cracks",
    """
View(0, 0, {view}, {view})
Define(plate, Worley(base_freq=2.2, to_01=True, seed={seed:plate}))
Define(crack, Worley(combination="F2-F1", base_freq=2.2, to_01=True, seed={seed:plate}))
Define(grit, fBm(octaves=4, base_freq={mf:70}, to_01=True, seed={seed:grit}))
Define(open, Threshold(((crack - {gap}) * 25), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.6})
    .roughness(1),
  Layer(open)
    .basecolor({mix:base~-0.15,base,((plate * 0.5) + (grit * 0.5))})
    .roughness(0.95)
    .height((open * (({h:0.03} + (plate * {h:0.02})) + (grit * {hv:0.003}))))
)""",
    tags={
        "cracked earth": 9,
        "dry mud": 8,
        "dried mud": 8,
        "drought": 7,
        "parched": 7,
        "desert floor": 5,
        "cracked clay": 7,
        "mud cracks": 8,
        "dry": 1.5,
        "arid": 4,
        **GROUND,
    },
    colours=roles(("base", (176, 140, 100))),
    slots={"view": 2, "rough": 0.95, "gap": 0.04},
    patterns=("giraffe",),
    unit_m=0.3,
)

recipe(
    "salt-flat",
    "ground",
    "salt flat crust: white crystalline plates with raised polygon ridges",
    """
View(0, 0, {view}, {view})
Define(cell, Worley(combination="F2-F1", base_freq=1.8, to_01=True, seed={seed:cell}))
Define(ridge, Threshold(((0.06 - cell) * 25), below_at=0, above_at=1))
Define(crystal, fBm(octaves=4, base_freq={mf:80}, to_01=True, seed={seed:crystal}))
Define(stain, fBm(octaves=4, base_freq=1.2, to_01=True, seed={seed:stain}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.12,base,((crystal * 0.6) + (stain * 0.4))})
    .roughness(0.8)
    .height(((ridge * {h:0.04}) + (crystal * {hv:0.004}))),
  Layer((ridge * 0.7))
    .basecolor({rgb:base~0.5})
    .roughness(0.6)
    .sheen(0.3)
)""",
    tags={
        "salt flat": 9,
        "salt flats": 9,
        "salt": 5,
        "playa": 7,
        "crust": 3,
        "evaporite": 7,
        "crystalline": 1.5,
        "evaporates": 1.5,
        "alkali": 5,
        "salt pan": 8,
    },
    colours=roles(("base", (234, 230, 222))),
    slots={"view": 2, "rough": 0.8},
    patterns=("giraffe",),
    unit_m=0.5,
)
