"""Plastic, rubber and foam: glossy plastic, vinyl, rubber, acoustic foam wedges, reticulated
foam, closed-cell foam, perforated foam, trash-bag film, bubble wrap, thermochromic plastic and
ferrofluid.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

recipe(
    "plastic",
    "plastic",
    "moulded plastic: uniform colour, faint mould grain, soft gloss",
    """
View(0, 0, {view}, {view})
Define(grain, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:grain}))
Define(sheen, fBm(octaves=3, base_freq_x=0.7, base_freq_y=1.5, to_01=True, seed={seed:sheen}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.12,base~0.05,((sheen * 0.7) + (grain * 0.3))})
    .roughness(({rough} + (grain * 0.05)))
    .coat(0.5)
    .height(((grain * {hv:0.002}) + (sheen * {h:0.006})))
)""",
    tags={
        "plastic": 5,
        "abs": 3,
        "polymer": 3,
        "acrylic": 3,
        "injection": 2,
        "moulded": 3,
        "molded": 3,
        "polypropylene": 5,
        "polycarbonate": 5,
        "toy": 1.5,
        "lego": 4,
        "synthetic": 1,
    },
    colours=roles(("base", (210, 60, 50))),
    slots={"view": 1, "rough": 0.3},
    unit_m=0.2,
)

recipe(
    "vinyl",
    "plastic",
    "soft vinyl: smooth shiny skin with a faint embossed grain",
    """
View(0, 0, {view}, {view})
Define(emboss, Worley(base_freq={mf:40}, to_01=True, seed={seed:emboss}))
Define(fold, fBm(octaves=3, base_freq_x=0.6, base_freq_y=1.4, to_01=True, seed={seed:fold}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.25,base~0.08,((fold * 0.8) + (emboss * 0.2))})
    .roughness(({rough} + (emboss * 0.08)))
    .coat(0.7)
    .height(((fold * {h:0.02}) + ((1 - emboss) * {hv:0.002})))
)""",
    tags={
        "vinyl": 6,
        "pvc": 5,
        "latex": 5,
        "patent": 4,
        "faux": 1,
        "naugahyde": 7,
        "oilcloth": 6,
        "soft": 0.5,
        "shiny": 0.5,
    },
    colours=roles(("base", (200, 40, 40))),
    slots={"view": 1, "rough": 0.25},
    unit_m=0.2,
)

recipe(
    "rubber",
    "plastic",
    "rubber: matte dark elastomer with fine stipple and raised dots",
    """
View(0, 0, {view}, {view})
Define(stipple, fBm(octaves=4, base_freq={mf:90}, to_01=True, seed={seed:stipple}))
Define(row, Floor((Y() / 0.866)))
Define(dx, (((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(dy, (((Y() / 0.866) - row) - 0.5))
Define(stud, Threshold(((0.25 - Sqrt(((dx * dx) + ((dy * 0.866) * (dy * 0.866))))) * 30), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.2,base,stipple})
    .roughness(({rough} + (stipple * 0.1)))
    .height(((stud * {h:0.03}) + (stipple * {hv:0.002})))
)""",
    tags={
        "rubber": 6,
        "rubbery": 6,
        "neoprene": 6,
        "silicone": 4,
        "tyre": 4,
        "tire": 4,
        "rubber mat": 8,
        "gym floor": 6,
        "elastomer": 6,
    },
    colours=roles(("base", (44, 44, 46))),
    slots={"view": 6, "rough": 0.85},
    unit_m=0.02,
)

recipe(
    "acoustic-foam",
    "plastic",
    "acoustic foam panels: wedge ridges alternating direction per tile",
    """
View(0, 0, {view}, {view})
Define(tile, Bricks(brick_width=1, brick_height=1, offset=0, mortar=0.03, feather=0.02))
Define(flip, Threshold((Sin((X() * 3.1416)) * Sin((Y() * 3.1416))), below_at=0, above_at=0, above_to=1))
Define(ridge, ((flip * Abs(Sin((X() * 4 * 3.1416)))) + ((1 - flip) * Abs(Sin((Y() * 4 * 3.1416))))))
Define(pore, fBm(octaves=3, base_freq={mf:90}, to_01=True, seed={seed:pore}))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.6})
    .roughness(1),
  Layer(tile)
    .basecolor({mix:base~-0.4,base,((ridge * 0.8) + (pore * 0.2))})
    .roughness(1)
    .height((tile * ((ridge * {h:0.08}) + (pore * {hv:0.003}))))
)""",
    tags={
        "acoustic": 7,
        "soundproofing": 7,
        "sound": 2,
        "studio": 3,
        "wedge": 5,
        "wedges": 5,
        "egg crate": 6,
        "foam": 3,
        "panels": 1,
        "anechoic": 7,
    },
    colours=roles(("base", (60, 62, 68))),
    slots={"view": 4, "rough": 1},
    patterns=("checker", "rows"),
    unit_m=0.3,
)

recipe(
    "reticulated-foam",
    "plastic",
    "reticulated foam: open-pore web of thin struts over dark voids",
    """
View(0, 0, {view}, {view})
Define(strutA, Worley(combination="F2-F1", base_freq={mf:9}, to_01=True, seed={seed:strutA}))
Define(strutB, Worley(combination="F2-F1", base_freq={mf:14}, to_01=True, seed={seed:strutB}))
Define(web, Max(Threshold(((0.06 - strutA) * 30), below_at=0, above_at=1), (Threshold(((0.05 - strutB) * 30), below_at=0, above_at=1) * 0.7)))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.75})
    .roughness(1),
  Layer(web)
    .basecolor({mix:base~-0.35,base,web})
    .roughness(0.9)
    .height((web * {hv:0.02}))
)""",
    tags={
        "reticulated": 9,
        "open pore": 6,
        "open cell": 6,
        "porous": 2,
        "filter": 3,
        "filters": 3,
        "sponge": 3,
        "web like": 3,
        "foam": 3,
        "air conditioning": 2,
    },
    colours=roles(("base", (210, 170, 90))),
    slots={"view": 1, "rough": 0.9},
    patterns=("mesh",),
    unit_m=0.05,
)

recipe(
    "foam",
    "plastic",
    "closed-cell foam: soft matte slab with fine bubbly pores",
    """
View(0, 0, {view}, {view})
Define(cell, Worley(base_freq={mf:40}, to_01=True, seed={seed:cell}))
Define(tone, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.12,base,((cell * 0.6) + (tone * 0.4))})
    .roughness(0.95)
    .subsurface(0.3)
    .height(((cell * {hv:0.004}) + (tone * {h:0.004})))
)""",
    tags={
        "foam": 5,
        "styrofoam": 7,
        "polystyrene": 7,
        "eva": 5,
        "foam board": 7,
        "sponge": 3,
        "memory foam": 7,
        "polyurethane": 4,
        "insulation": 3,
    },
    colours=roles(("base", (236, 236, 230))),
    slots={"view": 1, "rough": 0.95},
    unit_m=0.05,
)

recipe(
    "perforated-foam",
    "plastic",
    "thick foam sheet with punched round holes in a staggered grid",
    """
View(0, 0, {view}, {view})
Define(row, Floor((Y() / 0.866)))
Define(dx, (((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(dy, ((((Y() / 0.866) - row) - 0.5) * 0.866))
Define(hole, Threshold((({radius} - Sqrt(((dx * dx) + (dy * dy)))) * 60), below_at=0, above_at=1))
Define(cell, Worley(base_freq={mf:40}, to_01=True, seed={seed:cell}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.1,base,cell})
    .roughness(0.95)
    .subsurface(0.3)
    .height(({h:0.03} + (cell * {hv:0.003}))),
  Layer(hole)
    .basecolor({rgb:back})
    .roughness(1)
    .height(0)
)""",
    tags={
        "foam": 4,
        "holes": 2,
        "punched": 3,
        "perforated": 3,
        "bendable": 2,
        "thick": 1,
        "sponge": 2,
        "pegboard": 5,
        "cutouts": 2,
    },
    colours=roles(("base", (236, 236, 230)), ("back", (26, 26, 28), "grout")),
    slots={"view": 5, "rough": 0.95, "radius": 0.28},
    patterns=("perforated", "dots", "circles"),
    count_nouns=("hole",),
    repeat=1.0,
    unit_m=0.02,
)

recipe(
    "trash-bag",
    "plastic",
    "trash-bag film: thin glossy black plastic full of creases and folds",
    """
View(0, 0, {view}, {view})
Define(fold, fBm(octaves=4, base_freq_x=1.2, base_freq_y=0.6, to_01=True, seed={seed:fold}))
Define(crease, Worley(combination="F2-F1", base_freq=3, to_01=True, seed={seed:crease}))
Define(crinkle, Worley(combination="F2-F1", base_freq=9, to_01=True, seed={seed:crinkle}))
Material(
  Layer(1)
    .basecolor({mix:base,base~0.18,((fold * 0.6) + (crinkle * 0.4))})
    .roughness({rough})
    .coat(0.8)
    .height((((fold * {h:0.12}) + (Min((crease * 3), 1) * {h:0.03})) + (crinkle * {h:0.01})))
)""",
    tags={
        "trash bag": 10,
        "garbage bag": 10,
        "bin bag": 10,
        "bin liner": 10,
        "plastic bag": 8,
        "polythene": 7,
        "polyethylene": 6,
        "plastic film": 7,
        "cling": 4,
        "tarp": 5,
        "tarpaulin": 6,
        "trash": 4,
        "garbage": 4,
        "crinkled": 2,
        "wrinkled": 2,
    },
    colours=roles(("base", (28, 28, 32))),
    slots={"view": 2, "rough": 0.25},
    unit_m=0.3,
)

recipe(
    "bubble-wrap",
    "plastic",
    "bubble wrap: clear film with a grid of air bubbles",
    """
View(0, 0, {view}, {view})
Define(row, Floor((Y() / 0.866)))
Define(dx, (((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(dy, ((((Y() / 0.866) - row) - 0.5) * 0.866))
Define(dome, Max((0.14 - ((dx * dx) + (dy * dy))), 0))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.2})
    .roughness(0.2)
    .transmission(0.5),
  Layer(Threshold((dome * 60), below_at=0, above_at=1))
    .basecolor({mix:base,base~0.5,(dome * 7)})
    .roughness(0.05)
    .transmission(0.4)
    .coat(1)
    .height((Sqrt(dome) * {h:0.25}))
)""",
    tags={"bubble wrap": 10, "bubblewrap": 10, "bubbles": 3, "packaging": 4, "air cushion": 6},
    colours=roles(("base", (210, 226, 232))),
    slots={"view": 6, "rough": 0.1},
    patterns=("circles", "dots"),
    unit_m=0.01,
)

recipe(
    "thermochromic",
    "plastic",
    "thermochromic surface: heat-map blooms shifting across hues",
    """
View(0, 0, {view}, {view})
Define(heat, fBm(octaves=4, base_freq=1, to_01=True, seed={seed:heat}))
Define(hand, Worley(base_freq=1.5, to_01=True, seed={seed:hand}))
Define(temp, ((heat * 0.7) + ((1 - hand) * 0.6)))
Material(
  Layer(1)
    .basecolor({mix:cold,mid,Threshold(((temp - 0.35) * 3), below_at=0, above_at=1)})
    .roughness({rough})
    .coat(0.6),
  Layer(Threshold(((temp - 0.62) * 4), below_at=0, above_at=1))
    .basecolor({mix:warm,hot,Threshold(((temp - 0.8) * 4), below_at=0, above_at=1)})
    .roughness({rough})
)""",
    tags={
        "thermochromic": 10,
        "heat sensitive": 8,
        "mood ring": 8,
        "mood": 2,
        "color changing": 7,
        "colour changing": 7,
        "temperature": 2,
        "thermal": 3,
        "heat map": 7,
        "liquid crystal": 6,
    },
    colours=roles(
        ("cold", (30, 30, 120)),
        ("mid", (30, 150, 140), "accent"),
        ("warm", (230, 180, 40), "accent"),
        ("hot", (210, 40, 60), "accent"),
    ),
    slots={"view": 2, "rough": 0.25},
    patterns=("iridescent",),
    unit_m=0.2,
)

recipe(
    "ferrofluid",
    "plastic",
    "ferrofluid: glossy black liquid raised into a field of sharp spikes",
    """
View(0, 0, {view}, {view})
Define(row, Floor((Y() / 0.866)))
Define(dx, (((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(dy, ((((Y() / 0.866) - row) - 0.5) * 0.866))
Define(swell, fBm(octaves=3, base_freq=0.6, to_01=True, seed={seed:swell}))
Define(spike, (Max((0.5 - Sqrt(((dx * dx) + (dy * dy)))), 0) * (0.4 + swell)))
Material(
  Layer(1)
    .basecolor({mix:base,base~0.25,(spike * 2)})
    .metallic(0.4)
    .roughness({rough})
    .coat(1)
    .height((spike * {h:0.35}))
)""",
    tags={
        "ferrofluid": 10,
        "magnetic fluid": 10,
        "magnetic": 3,
        "spiky": 4,
        "spikes": 4,
        "spike": 3,
        "liquid": 1.5,
        "fluid": 1.5,
    },
    colours=roles(("base", (18, 18, 20))),
    slots={"view": 6, "rough": 0.08},
    unit_m=0.01,
)
