"""Concrete, plaster and paint: raw and polished concrete, plaster / stucco, painted walls,
peeling and blistered paint, asphalt and fresco.

These are continuous substrates (one ``Layer(1)``) with multi-octave mottling (a coarse fBm for
broad tone, a fine one for grain) and sparse discrete features (pores, aggregate, blisters,
paint flakes) as thresholded upper layers.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

recipe(
    "concrete",
    "concrete",
    "cast concrete: cloudy grey mottle, pinhole pores, faint formwork seams",
    """
View(0, 0, {view}, {view})
Define(cloud, fBm(octaves=5, base_freq=1.2, to_01=True, seed={seed:cloud}))
Define(grit, fBm(octaves=4, base_freq={mf:70}, to_01=True, seed={seed:grit}))
Define(poreCell, Worley(base_freq={mf:26}, to_01=True, seed={seed:pore}))
Define(pore, Threshold(((0.09 - poreCell) * 40), below_at=0, above_at=1))
Define(seam, Translate(Bricks(brick_width=100, brick_height=1.5, offset=0, mortar=0.012, feather=0.01), 50, 0.4))
Material(
  Layer(1)
    .basecolor({mix:base,base_dark,((cloud * 0.7) + (grit * 0.3))})
    .roughness(({rough} + (grit * 0.08)))
    .height(((cloud * {h:0.01}) + (grit * {hv:0.003}))),
  Layer((((1 - seam) * 0.5) + (pore * 0.8)))
    .basecolor({rgb:base_dark~-0.35})
    .roughness(0.95)
)""",
    tags={
        "concrete": 5,
        "cement": 4,
        "raw concrete": 2,
        "brutalist": 3,
        "cast": 1,
        "beton": 4,
        "slab": 1,
        "sidewalk": 1.5,
        "walkways": 1,
        "walkway": 1,
    },
    colours=roles(
        ("base", (156, 154, 148)), ("base_dark", (118, 116, 110), "base", ("base", -0.25))
    ),
    slots={"view": 2, "rough": 0.85},
    absorbs=(),
    unit_m=0.5,
)

recipe(
    "polished-concrete",
    "concrete",
    "polished concrete floor: smooth sheen with exposed aggregate",
    """
View(0, 0, {view}, {view})
Define(cloud, fBm(octaves=5, base_freq=1, to_01=True, seed={seed:cloud}))
Define(aggCell, Worley(base_freq={mf:22}, to_01=True, seed={seed:agg}))
Define(agg, Threshold(((0.16 - aggCell) * 30), below_at=0, above_at=1))
Define(fine, fBm(octaves=3, base_freq={mf:60}, to_01=True, seed={seed:fine}))
Material(
  Layer(1)
    .basecolor({mix:base,base_dark,((cloud * 0.75) + (fine * 0.25))})
    .roughness(({rough} + (cloud * 0.08)))
    .coat(0.5)
    .height((cloud * {h:0.001})),
  Layer((agg * 0.7))
    .basecolor({mix:base_dark~-0.2,base~0.2,fine})
    .roughness({rough})
)""",
    tags={
        "polished concrete": 7,
        "concrete": 3,
        "screed": 4,
        "microcement": 5,
        "terrazzo": 0.5,
        "floor": 0.5,
    },
    colours=roles(
        ("base", (172, 170, 166)), ("base_dark", (132, 130, 126), "base", ("base", -0.22))
    ),
    slots={"view": 2, "rough": 0.18},
    unit_m=0.5,
)

recipe(
    "plaster",
    "concrete",
    "trowelled plaster / stucco: soft undulating relief, chalky tone",
    """
View(0, 0, {view}, {view})
Define(trowel, fBm(octaves=6, base_freq=1.8, to_01=True, seed={seed:trowel}))
Define(swirl, Threshold(((trowel - 0.5) * 4), below_at=0, above_at=1))
Define(grit, fBm(octaves=4, base_freq={mf:80}, to_01=True, seed={seed:grit}))
Define(tone, fBm(octaves=3, base_freq=0.8, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base,base_dark,((tone * 0.6) + (swirl * 0.4))})
    .roughness(({rough} + (grit * 0.1)))
    .height((((swirl * {h:0.02}) + (trowel * {h:0.01})) + (grit * {hv:0.004})))
)""",
    tags={
        "plaster": 5,
        "stucco": 5,
        "render": 2,
        "drywall": 3,
        "lime plaster": 5,
        "limewash": 5,
        "venetian": 2,
        "adobe": 3,
        "wall": 1,
        "walls": 1,
        "skim": 2,
        "tadelakt": 5,
        "textured wall": 3,
    },
    colours=roles(
        ("base", (226, 220, 206)), ("base_dark", (196, 188, 172), "base", ("base", -0.14))
    ),
    slots={"view": 2, "rough": 0.85},
    presets={"adobe": {"base": (196, 150, 110)}},
    unit_m=0.5,
)

recipe(
    "painted-wall",
    "concrete",
    "painted wall: flat paint colour with fine roller orange-peel texture",
    """
View(0, 0, {view}, {view})
Define(peel, fBm(octaves=4, base_freq={mf:40}, to_01=True, seed={seed:peel}))
Define(tone, fBm(octaves=3, base_freq=0.7, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base,base~-0.06,((tone * 0.7) + (peel * 0.3))})
    .roughness(({rough} + (peel * 0.06)))
    .height((peel * {hv:0.003}))
)""",
    tags={
        "painted": 3,
        "paint": 2,
        "painted wall": 5,
        "emulsion": 4,
        "wall": 1,
        "walls": 1,
        "interior": 1,
        "satin paint": 3,
        "eggshell": 2,
        "solid": 0.5,
    },
    colours=roles(("base", (214, 210, 200))),
    slots={"view": 2, "rough": 0.6},
    unit_m=0.5,
)

recipe(
    "peeling-paint",
    "concrete",
    "old paint coat blistering and peeling off a grey substrate",
    """
View(0, 0, {view}, {view})
Define(flake, fBm(octaves=6, base_freq=2.2, to_01=True, seed={seed:flake}))
Define(paint, Threshold(((flake - (0.62 - ({wear} * 0.3))) * 30), below_at=0, above_at=1))
Define(blisterCell, Worley(base_freq={mf:9}, to_01=True, seed={seed:blister}))
Define(blister, Threshold(((0.3 - blisterCell) * 6), below_at=0, above_at=1))
Define(grit, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({mix:under,under~-0.3,grit})
    .roughness(0.95)
    .height((grit * {hv:0.004})),
  Layer(paint)
    .basecolor({mix:paint,paint~-0.12,blister})
    .roughness({rough})
    .height((paint * ({h:0.01} + (blister * {hv:0.03}))))
)""",
    tags={
        "peeling": 5,
        "blistered": 6,
        "blister": 6,
        "blistering": 6,
        "flaking": 4,
        "chipped paint": 5,
        "paint": 2.5,
        "old paint": 4,
        "cracked paint": 4,
    },
    colours=roles(("paint", (196, 204, 192)), ("under", (120, 114, 106), "base")),
    slots={"view": 2, "rough": 0.55, "wear": 0.5},
    absorbs=("chipped", "worn", "cracked"),
    unit_m=0.5,
)

recipe(
    "asphalt",
    "concrete",
    "asphalt road surface: black binder with grey aggregate stones",
    """
View(0, 0, {view}, {view})
Define(stoneCell, Worley(base_freq={mf:36}, to_01=True, seed={seed:stone}))
Define(stone, Threshold(((0.3 - stoneCell) * 12), below_at=0, above_at=1))
Define(tone, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:tone}))
Define(fine, fBm(octaves=3, base_freq={mf:90}, to_01=True, seed={seed:fine}))
Material(
  Layer(1)
    .basecolor({mix:base,base~0.08,tone})
    .roughness(0.9)
    .height((fine * {hv:0.002})),
  Layer(stone)
    .basecolor({mix:stone_col,stone_col~-0.3,fine})
    .roughness(0.8)
    .height((stone * (1 - stoneCell) * {hv:0.01}))
)""",
    tags={
        "asphalt": 6,
        "tarmac": 6,
        "blacktop": 6,
        "road": 3,
        "street": 1.5,
        "bitumen": 5,
        "parking": 2,
    },
    colours=roles(("base", (46, 46, 48)), ("stone_col", (120, 118, 114), "accent")),
    slots={"view": 1, "rough": 0.9},
    unit_m=0.3,
)

recipe(
    "fresco",
    "concrete",
    "fresco: faded mural pigments soaked into lime plaster, fine craquelure",
    """
View(0, 0, {view}, {view})
Define(plasterTone, fBm(octaves=4, base_freq=1, to_01=True, seed={seed:plaster}))
Define(pigA, Threshold(((fBm(octaves=4, base_freq=0.9, to_01=True, seed={seed:pigA}) - 0.5) * 5), below_at=0, above_at=1))
Define(pigB, Threshold(((fBm(octaves=4, base_freq=1.3, to_01=True, seed={seed:pigB}) - 0.55) * 5), below_at=0, above_at=1))
Define(crackle, Worley(combination="F2-F1", base_freq={mf:10}, to_01=True, seed={seed:crackle}))
Define(grit, fBm(octaves=4, base_freq={mf:70}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({mix:base,base~-0.15,plasterTone})
    .roughness(0.9)
    .height(((plasterTone * {h:0.01}) + (grit * {hv:0.003}))),
  Layer((pigA * 0.75))
    .basecolor({mix:pigment_a,pigment_a~0.2,grit})
    .roughness(0.9),
  Layer((pigB * 0.7))
    .basecolor({mix:pigment_b,pigment_b~0.2,grit})
    .roughness(0.9),
  Layer(Threshold(((0.03 - crackle) * 30), below_at=0, above_at=0.6))
    .basecolor({rgb:base~-0.5})
    .roughness(0.95)
)""",
    tags={
        "fresco": 7,
        "frescoes": 7,
        "mural": 5,
        "wall painting": 5,
        "renaissance": 2,
        "pigment": 2,
        "lime": 1,
        "byzantine": 2,
        "pompeii": 3,
    },
    colours=roles(
        ("base", (228, 214, 186)),
        ("pigment_a", (178, 92, 60), "accent"),
        ("pigment_b", (90, 120, 150), "accent"),
    ),
    slots={"view": 2, "rough": 0.9},
    unit_m=0.5,
)
