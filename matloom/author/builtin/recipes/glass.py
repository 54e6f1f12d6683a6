"""Ice, glass and crystal: ice, cracked ice, frosted glass, clear glass, stained glass, quartz
crystal, amber with inclusions, bismuth hopper crystal and water.

Transmissive recipes set ``transmission`` and ``ior``; the head-on preview mixes transmission
toward grey, so they keep a tinted base colour and put structure (cracks, facets, bubbles) in
separate upper layers so that the material still reads clearly.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

GLASSY = {"glass": 1.5, "transparent": 1, "translucent": 1, "clear": 0.5}

recipe(
    "ice",
    "glass",
    "ice: cold translucent blue with trapped bubbles and faint fractures",
    """
View(0, 0, {view}, {view})
Define(depth, fBm(octaves=5, base_freq=1.2, to_01=True, seed={seed:depth}))
Define(fracture, Worley(combination="F2-F1", base_freq=1.5, to_01=True, seed={seed:fracture}))
Define(bubbleCell, Worley(base_freq={mf:18}, to_01=True, seed={seed:bubble}))
Define(bubble, Threshold(((0.06 - bubbleCell) * 40), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.3,base,depth})
    .roughness({rough})
    .transmission(0.45)
    .ior(1.31)
    .coat(0.6)
    .height((depth * {h:0.02})),
  Layer(Max(Threshold(((0.025 - fracture) * 40), below_at=0, above_at=0.7), (bubble * 0.8)))
    .basecolor({rgb:base~0.6})
    .roughness(0.3)
)""",
    tags={
        "ice": 6,
        "icy": 4,
        "frozen": 5,
        "glacier": 6,
        "glacial": 6,
        "iceberg": 6,
        "ice cube": 6,
        "frost": 2,
        **GLASSY,
    },
    colours=roles(("base", (170, 210, 232))),
    slots={"view": 2, "rough": 0.1},
    unit_m=0.3,
)

recipe(
    "cracked-ice",
    "glass",
    "cracked ice: thick clear ice shattered by white fracture planes",
    """
View(0, 0, {view}, {view})
Define(shard, Worley(base_freq=1.6, to_01=True, seed={seed:shard}))
Define(crack, Worley(combination="F2-F1", base_freq=1.6, to_01=True, seed={seed:shard}))
Define(fine, Worley(combination="F2-F1", base_freq=4, to_01=True, seed={seed:fine}))
Define(depth, fBm(octaves=4, base_freq=1, to_01=True, seed={seed:depth}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.35,base,((shard * 0.5) + (depth * 0.5))})
    .roughness(0.05)
    .transmission(0.4)
    .ior(1.31)
    .coat(0.8)
    .height((shard * {h:0.03})),
  Layer(Threshold(((0.05 - fine) * 30), below_at=0, above_at=0.5))
    .basecolor({rgb:base~0.7})
    .roughness(0.3),
  Layer(Threshold(((0.04 - crack) * 40), below_at=0, above_at=1))
    .basecolor({rgb:base~0.8})
    .roughness(0.4)
)""",
    tags={
        "cracked ice": 10,
        "shattered ice": 9,
        "broken ice": 9,
        "frozen lake": 7,
        "ice": 3,
        "cracked": 1,
    },
    colours=roles(("base", (150, 200, 228))),
    slots={"view": 2, "rough": 0.05},
    absorbs=("cracked",),
    unit_m=0.3,
)

recipe(
    "frosted-glass",
    "glass",
    "frosted glass: diffuse translucent pane with fine etched grain",
    """
View(0, 0, {view}, {view})
Define(etch, fBm(octaves=3, base_freq={mf:100}, to_01=True, seed={seed:etch}))
Define(haze, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:haze}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.1,base,((haze * 0.6) + (etch * 0.4))})
    .roughness(({rough} + (etch * 0.1)))
    .transmission(0.6)
    .ior(1.5)
    .height((etch * {hv:0.001}))
)""",
    tags={
        "frosted glass": 9,
        "frosted": 4,
        "sandblasted": 6,
        "etched glass": 8,
        "obscure": 3,
        "privacy glass": 8,
        "matte glass": 7,
        "glass": 2,
    },
    colours=roles(("base", (214, 226, 230))),
    slots={"view": 1, "rough": 0.55},
    unit_m=0.3,
)

recipe(
    "clear-glass",
    "glass",
    "clear glass pane: tinted transmission with faint reflections",
    """
View(0, 0, {view}, {view})
Define(reflect, fBm(octaves=3, base_freq_x=0.6, base_freq_y=1.4, to_01=True, seed={seed:reflect}))
Define(streak, Abs(Sin((((X() + (Y() * 0.6)) * 1.5) + (reflect * 2)))))
Material(
  Layer(1)
    .basecolor({mix:base~-0.15,base~0.2,((streak * 0.5) + (reflect * 0.5))})
    .roughness({rough})
    .transmission(0.7)
    .ior(1.52)
    .coat(1)
    .height((streak * {h:0.004}))
)""",
    tags={
        "glass": 4,
        "window": 3,
        "pane": 4,
        "windowpane": 5,
        "transparent": 2,
        "clear": 1,
        "tempered": 4,
        "glazing": 4,
    },
    colours=roles(("base", (190, 216, 214))),
    slots={"view": 2, "rough": 0.03},
    unit_m=0.5,
)

recipe(
    "stained-glass",
    "glass",
    "stained glass: vivid coloured panes joined by dark lead came",
    """
View(0, 0, {view}, {view})
Define(pane, Worley(combination="F2-F1", base_freq=2.2, to_01=True, seed={seed:pane}))
Define(hueA, fBm(octaves=2, base_freq=2.5, to_01=True, seed={seed:hueA}))
Define(hueB, fBm(octaves=2, base_freq=2.5, to_01=True, seed={seed:hueB}))
Define(lead, Threshold(((0.04 - pane) * 40), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:glass_a,glass_b,Threshold(((hueA - 0.5) * 6), below_at=0, above_at=1)})
    .roughness(0.1)
    .transmission(0.3)
    .emissive({rgb:glass_a}, 0.2),
  Layer(Threshold(((hueB - 0.55) * 6), below_at=0, above_at=1))
    .basecolor({mix:glass_c,glass_d,hueA})
    .roughness(0.1)
    .transmission(0.3),
  Layer(lead)
    .basecolor({rgb:lead_col})
    .metallic(0.6)
    .roughness(0.6)
    .height((lead * {h:0.02}))
)""",
    tags={
        "stained glass": 10,
        "stained": 2,
        "leaded": 5,
        "cathedral": 4,
        "tiffany": 7,
        "church window": 8,
        "leadlight": 8,
        "glass": 1.5,
    },
    colours=roles(
        ("glass_a", (200, 40, 50)),
        ("glass_b", (40, 80, 190), "accent"),
        ("glass_c", (230, 180, 40), "accent"),
        ("glass_d", (40, 150, 70), "accent"),
        ("lead_col", (40, 40, 44), "grout"),
    ),
    slots={"view": 2, "rough": 0.1},
    patterns=("mosaic",),
    unit_m=0.2,
)

recipe(
    "quartz-crystal",
    "glass",
    "crystal cluster: faceted translucent points with bright edges",
    """
View(0, 0, {view}, {view})
Define(facet, Worley(distance="manhattan", base_freq=2.5, to_01=True, seed={seed:facet}))
Define(edge, Worley(combination="F2-F1", distance="manhattan", base_freq=2.5, to_01=True, seed={seed:facet}))
Define(inner, fBm(octaves=4, base_freq=2, to_01=True, seed={seed:inner}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.35,base,((facet * 0.5) + (inner * 0.5))})
    .roughness(0.05)
    .transmission(0.35)
    .ior(1.54)
    .coat(1)
    .height(((1 - facet) * {h:0.12})),
  Layer(Threshold(((0.04 - edge) * 30), below_at=0, above_at=0.8))
    .basecolor({rgb:base~0.7})
    .roughness(0.05)
)""",
    tags={
        "crystal": 5,
        "crystals": 5,
        "quartz": 7,
        "amethyst": 7,
        "geode": 7,
        "gem": 3,
        "gemstone": 3,
        "citrine": 7,
        "crystalline": 2,
        "faceted": 4,
        "diamond": 1,
        "selenite": 7,
        "mineral": 1,
    },
    colours=roles(("base", (226, 226, 236))),
    slots={"view": 2, "rough": 0.05},
    presets={
        "amethyst": {"base": (150, 96, 190)},
        "citrine": {"base": (236, 180, 70)},
        "rose quartz": {"base": (236, 190, 200)},
        "emerald": {"base": (40, 160, 90)},
    },
    unit_m=0.1,
)

recipe(
    "amber-resin",
    "glass",
    "amber / resin: translucent gold with bubbles and dark inclusions",
    """
View(0, 0, {view}, {view})
Define(depth, fBm(octaves=5, base_freq=1.1, to_01=True, seed={seed:depth}))
Define(bubbleCell, Worley(base_freq={mf:10}, to_01=True, seed={seed:bubble}))
Define(incl, fBm(octaves=5, base_freq=2.2, to_01=True, seed={seed:incl}))
Define(insect, Threshold(((incl - 0.64) * 10), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.45,base,depth})
    .roughness({rough})
    .transmission(0.3)
    .subsurface(0.6)
    .ior(1.54)
    .coat(1),
  Layer((Threshold(((0.05 - bubbleCell) * 30), below_at=0, above_at=1) * 0.35))
    .basecolor({rgb:base~0.55})
    .roughness(0.1),
  Layer(insect)
    .basecolor({mix:inclusion,inclusion~0.2,incl})
    .roughness(0.5)
)""",
    tags={
        "amber": 7,
        "resin": 6,
        "epoxy": 6,
        "fossilized": 3,
        "fossil": 3,
        "insects": 3,
        "insect": 3,
        "trapped": 2,
        "copal": 7,
        "prehistoric": 2,
        "honey": 2,
        "inclusions": 4,
        "preserved": 1.5,
    },
    colours=roles(("base", (214, 140, 40)), ("inclusion", (60, 36, 20), "accent")),
    slots={"view": 2, "rough": 0.08},
    unit_m=0.05,
)

recipe(
    "bismuth-crystal",
    "glass",
    "bismuth hopper crystal: stair-stepped squares, iridescent oxide",
    """
View(0, 0, {view}, {view})
Define(cx, ((X() - Floor(X())) - 0.5))
Define(cy, ((Y() - Floor(Y())) - 0.5))
Define(ring, (Max(Abs(cx), Abs(cy)) * 8))
Define(step, Floor(ring))
Define(lip, Threshold((((ring - step) - 0.8) * 20), below_at=0, above_at=1))
Define(oxide, fBm(octaves=3, base_freq=1.2, to_01=True, seed={seed:oxide}))
Define(film, ((step * 0.9) + (oxide * 3)))
Material(
  Layer(1)
    .basecolor((160 + (Sin(film) * 90)), (150 + (Sin((film + 2.1)) * 90)), (160 + (Sin((film + 4.2)) * 90)))
    .metallic(0.4)
    .roughness({rough})
    .height(((4 - step) * {h:0.015})),
  Layer((lip * 0.8))
    .basecolor(220, 214, 226)
    .metallic(0.7)
    .roughness(0.2)
)""",
    tags={
        "bismuth": 10,
        "hopper": 7,
        "stair stepped": 6,
        "stepped": 3,
        "iridescent": 3,
        "oxide": 2,
        "geometric crystals": 5,
        "crystal": 2,
        "crystals": 2,
        "rainbow": 2,
    },
    colours=roles(("base", (180, 160, 200))),
    slots={"view": 3, "rough": 0.25},
    patterns=("iridescent", "squares"),
    unit_m=0.02,
)

recipe(
    "water-surface",
    "glass",
    "water surface: rippled transparent water over a darker depth",
    """
View(0, 0, {view}, {view})
Define(ripple, fBm(octaves=5, base_freq=1.5, to_01=True, seed={seed:ripple}))
Define(caustic, Worley(combination="F2-F1", base_freq=3, to_01=True, seed={seed:caustic}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.4,base,((ripple * 0.6) + (Min((caustic * 3), 1) * 0.4))})
    .roughness(0.03)
    .transmission(0.5)
    .ior(1.33)
    .coat(1)
    .height((ripple * {h:0.03})),
  Layer(Threshold(((0.04 - caustic) * 20), below_at=0, above_at=0.6))
    .basecolor({rgb:base~0.6})
    .roughness(0.03)
)""",
    tags={
        "water": 6,
        "pool": 3,
        "swimming pool": 7,
        "lake": 5,
        "ocean": 5,
        "sea": 4,
        "ripples": 3,
        "pond": 5,
        "liquid": 2,
        "puddle": 3,
        "caustics": 6,
    },
    colours=roles(("base", (60, 140, 170))),
    slots={"view": 2, "rough": 0.03},
    unit_m=0.5,
)
