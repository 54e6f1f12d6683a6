"""Leather and skin: leather, suede, crocodile, snakeskin, reptile scales, leopard, zebra,
giraffe and cow prints, and fur.

Grain comes from Worley cells (pebbled leather, croc scales), animal coats from thresholded
noise (blotches), noise-warped ``Sin`` bands (zebra stripes) and Worley F2-F1 networks
(giraffe patches). The pattern recipes are also used for printed fabrics of the same motif.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.snippets import SCALES

ANIMAL = {
    "animal print": 3,
    "animal": 1.5,
    "skin": 1.5,
    "hide": 1.5,
    "fur": 1,
    "print": 1,
    "fabric": 0.5,
    "pattern": 0.5,
    "coat": 1,
}

recipe(
    "leather",
    "leather",
    "leather: pebbled grain, fine creases and soft tonal mottling",
    """
View(0, 0, {view}, {view})
Define(pebble, Worley(base_freq={mf:30}, to_01=True, seed={seed:pebble}))
Define(crease, Worley(combination="F2-F1", base_freq={mf:30}, to_01=True, seed={seed:pebble}))
Define(tone, fBm(octaves=4, base_freq=1.2, to_01=True, seed={seed:tone}))
Define(wrinkle, fBm(octaves=4, base_freq_x={mf:6}, base_freq_y={mf:2}, to_01=True, seed={seed:wrinkle}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.4,base,(((tone * 0.35) + (Min((crease * 3), 1) * 0.45)) + (wrinkle * 0.2))})
    .roughness(({rough} + (pebble * 0.15)))
    .coat(0.2)
    .height((((Min((crease * 3), 1) * {hv:0.006}) + (wrinkle * {h:0.006})) + ((1 - pebble) * {hv:0.004})))
)""",
    tags={
        "leather": 6,
        "hide": 2.5,
        "pebbled": 3,
        "full grain": 4,
        "faux leather": 4,
        "pleather": 5,
        "saddle": 3,
        "wallet": 2,
        "handbag": 2,
        "sofa": 1.5,
        "couch": 1.5,
        "jacket": 1.5,
        "boot": 1.5,
        "tanned": 3,
        "cowhide leather": 3,
    },
    colours=roles(("base", (110, 66, 40))),
    slots={"view": 1, "rough": 0.55},
    presets={
        "tan": {"base": (176, 120, 70)},
        "saddle": {"base": (140, 80, 40)},
        "oxblood": {"base": (96, 26, 28)},
        "cognac": {"base": (150, 72, 30)},
    },
    unit_m=0.1,
)

recipe(
    "suede",
    "leather",
    "suede / nubuck: velvety nap with brushed light-dark patches",
    """
View(0, 0, {view}, {view})
Define(nap, fBm(octaves=4, base_freq_x=0.8, base_freq_y=2, to_01=True, seed={seed:nap}))
Define(fibre, fBm(octaves=4, base_freq={mf:120}, to_01=True, seed={seed:fibre}))
Define(scale, Worley(combination="F2-F1", base_freq={mf:10}, to_01=True, seed={seed:scale}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.25,base~0.08,(((nap * 0.6) + (fibre * 0.25)) + (Min((scale * 5), 1) * {scaled}))})
    .roughness(0.95)
    .sheen(0.7)
    .height(((fibre * {hv:0.002}) + (Min((scale * 5), 1) * {hv:0.001})))
)""",
    tags={
        "suede": 7,
        "nubuck": 7,
        "chamois": 5,
        "microsuede": 7,
        "alcantara": 7,
        "brushed leather": 5,
        "napped": 3,
        "leather": 1.5,
    },
    colours=roles(("base", (176, 132, 90))),
    slots={"view": 1, "rough": 0.95, "scaled": 0.0},
    presets={"scaled": {"scaled": 0.08}},
    unit_m=0.1,
)

recipe(
    "crocodile",
    "leather",
    "crocodile / alligator: rows of large rectangular bony scales",
    """
View(0, 0, {view}, {view})
Define(cell, Worley(distance="chebyshev", base_freq_x=2.2, base_freq_y=3.2, to_01=True, seed={seed:cell}))
Define(groove, Worley(combination="F2-F1", distance="chebyshev", base_freq_x=2.2, base_freq_y=3.2, to_01=True, seed={seed:cell}))
Define(scaleMask, Threshold(((groove - 0.05) * 20), below_at=0, above_at=1))
Define(tone, fBm(octaves=3, base_freq=1.5, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.6})
    .roughness(0.8),
  Layer(scaleMask)
    .basecolor({mix:base~-0.3,base,((tone * 0.5) + (cell * 0.5))})
    .roughness({rough})
    .coat(0.4)
    .height((scaleMask * ({h:0.02} + ((1 - cell) * {h:0.03}))))
)""",
    tags={
        "crocodile": 8,
        "alligator": 8,
        "croc": 8,
        "caiman": 8,
        "gator": 6,
        "reptile": 2,
        "embossed leather": 3,
    },
    colours=roles(("base", (70, 80, 50))),
    slots={"view": 2, "rough": 0.4},
    unit_m=0.1,
)

recipe(
    "snakeskin",
    "leather",
    "snakeskin: small overlapping scales with python blotch pattern",
    "View(0, 0, {view}, {view})\n"
    + SCALES
    + """
Define(blotch, fBm(octaves=4, base_freq=1.3, to_01=True, seed={seed:blotch}))
Define(mark, Threshold(((blotch - 0.55) * 20), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.3,base,scaleRim})
    .roughness({rough})
    .coat(0.3)
    .height((scaleRim * {h:0.012})),
  Layer(mark)
    .basecolor({mix:mark_col,mark_col~0.2,scaleRim})
    .roughness({rough})
)""",
    tags={
        "snake": 7,
        "snakeskin": 8,
        "python": 8,
        "viper": 7,
        "boa": 6,
        "cobra": 6,
        "reptile": 3,
        "scales": 2,
        **ANIMAL,
    },
    colours=roles(("base", (196, 176, 130)), ("mark_col", (70, 50, 36), "accent")),
    slots={"view": 8, "rough": 0.4, "scale_w": 0.5, "scale_h": 0.32},
    patterns=("scales",),
    unit_m=0.01,
)

recipe(
    "reptile-scales",
    "leather",
    "reptile / dragon scales: domed overlapping scales with dark rims",
    "View(0, 0, {view}, {view})\n"
    + SCALES
    + """
Define(tone, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.55,base,(Sqrt(scaleRim) * (0.6 + (tone * 0.4)))})
    .roughness({rough})
    .coat(0.4)
    .height((Sqrt(scaleRim) * {h:0.05}))
)""",
    tags={
        "scales": 3,
        "scaly": 5,
        "scaled": 2,
        "dragon": 6,
        "lizard": 6,
        "iguana": 7,
        "gecko": 6,
        "armadillo": 5,
        "pangolin": 7,
        "reptile": 4,
        "chainmail": 2,
    },
    colours=roles(("base", (70, 120, 80))),
    slots={"view": 5, "rough": 0.35, "scale_w": 1, "scale_h": 0.6},
    patterns=("scales",),
    unit_m=0.02,
)

recipe(
    "leopard-print",
    "leather",
    "leopard print: broken dark rosettes with amber centres on tan",
    """
View(0, 0, {view}, {view})
Define(spot, Worley(base_freq=3.6, to_01=True, seed={seed:spot}))
Define(breakup, fBm(octaves=4, base_freq=9, to_01=True, seed={seed:breakup}))
Define(ring, Threshold(((0.09 - Abs(((spot + (breakup * 0.1)) - 0.24))) * 30), below_at=0, above_at=1))
Define(centre, Threshold(((0.2 - spot) * 30), below_at=0, above_at=1))
Define(fur, fBm(octaves=4, base_freq_x={mf:30}, base_freq_y={mf:90}, to_01=True, seed={seed:fur}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.15,base,fur})
    .roughness(0.9)
    .sheen(0.4)
    .height((fur * {hv:0.003})),
  Layer((centre * 0.8))
    .basecolor({rgb:inner})
    .roughness(0.9),
  Layer((ring * Threshold(((breakup - 0.3) * 10), below_at=0, above_at=1)))
    .basecolor({rgb:spot_col})
    .roughness(0.9)
)""",
    tags={
        "leopard": 8,
        "cheetah": 6,
        "jaguar": 7,
        "ocelot": 7,
        "rosettes": 5,
        "big cat": 4,
        **ANIMAL,
    },
    colours=roles(
        ("base", (214, 170, 100)),
        ("spot_col", (40, 28, 20), "accent"),
        ("inner", (176, 112, 50), "accent", ("base", -0.2)),
    ),
    slots={"view": 2, "rough": 0.9},
    patterns=("leopard", "dots"),
    unit_m=0.1,
)

recipe(
    "zebra-print",
    "leather",
    "zebra print: bold wavy black stripes on white",
    """
View(0, 0, {view}, {view})
Define(warp, fBm(octaves=4, base_freq=0.8, seed={seed:warp}))
Define(stripe, Sin((((X() * 2.4) + (warp * 2.5)) * 3.1416)))
Define(fur, fBm(octaves=4, base_freq_x={mf:90}, base_freq_y={mf:30}, to_01=True, seed={seed:fur}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.1,base,fur})
    .roughness(0.9)
    .sheen(0.3)
    .height((fur * {hv:0.003})),
  Layer(Threshold(((stripe + (warp * 0.3)) * 8), below_at=0, above_at=1))
    .basecolor({rgb:stripe_col})
    .roughness(0.9)
)""",
    tags={"zebra": 9, "tiger stripe": 6, "tiger stripes": 6, **ANIMAL},
    colours=roles(("base", (236, 232, 222)), ("stripe_col", (22, 22, 22), "accent")),
    slots={"view": 3, "rough": 0.9},
    patterns=("zebra", "stripes"),
    unit_m=0.1,
    presets={"tiger": {"base": (222, 130, 40)}},
)

recipe(
    "giraffe-print",
    "leather",
    "giraffe print: large brown polygonal patches on cream lines",
    """
View(0, 0, {view}, {view})
Define(edge, Worley(combination="F2-F1", base_freq=2, to_01=True, seed={seed:patch}))
Define(wobble, fBm(octaves=4, base_freq=6, to_01=True, seed={seed:wobble}))
Define(patch, Threshold(((((edge + (wobble * 0.06)) - 0.1) - {gap}) * 30), below_at=0, above_at=1))
Define(tone, fBm(octaves=3, base_freq=2, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({rgb:base})
    .roughness(0.9)
    .sheen(0.3),
  Layer(patch)
    .basecolor({mix:patch_col,patch_col~-0.3,tone})
    .roughness(0.9)
)""",
    tags={"giraffe": 9, "polygonal": 2, "patches": 1.5, **ANIMAL},
    colours=roles(("base", (236, 220, 186)), ("patch_col", (150, 86, 40), "accent")),
    slots={"view": 2, "rough": 0.9, "gap": 0.0},
    patterns=("giraffe",),
    unit_m=0.2,
)

recipe(
    "cow-print",
    "leather",
    "cow print: large irregular black patches on white hide",
    """
View(0, 0, {view}, {view})
Define(blob, fBm(octaves=5, base_freq={blob_f}, to_01=True, seed={seed:blob}))
Define(hair, fBm(octaves=4, base_freq_x={mf:30}, base_freq_y={mf:90}, to_01=True, seed={seed:hair}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.1,base,hair})
    .roughness(0.9)
    .sheen(0.4)
    .height((hair * {hv:0.003})),
  Layer(Threshold(((blob - 0.56) * 30), below_at=0, above_at=1))
    .basecolor({mix:patch_col,patch_col~0.1,hair})
    .roughness(0.9)
)""",
    tags={"cow": 7, "cowhide": 8, "holstein": 8, "dalmatian": 7, "pony": 4, "pinto": 6, **ANIMAL},
    colours=roles(("base", (236, 234, 228)), ("patch_col", (24, 22, 22), "accent")),
    slots={"view": 2, "rough": 0.9, "blob_f": 1.0},
    patterns=("dots",),
    presets={"dalmatian": {"blob_f": 4.0}},
    unit_m=0.3,
)

recipe(
    "fur",
    "leather",
    "fur: long directional hair strands in soft clumps",
    """
View(0, 0, {view}, {view})
Define(clump, fBm(octaves=4, base_freq_x=2, base_freq_y=0.8, to_01=True, seed={seed:clump}))
Define(strand, fBm(octaves=4, base_freq_x={mf:80}, base_freq_y={mf:8}, to_01=True, seed={seed:strand}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.45,base~0.1,((strand * 0.6) + (clump * 0.4))})
    .roughness(0.95)
    .sheen(0.8)
    .height(((strand * {hv:0.015}) + (clump * {h:0.02})))
)""",
    tags={
        "fur": 7,
        "furry": 7,
        "faux fur": 8,
        "pelt": 6,
        "mink": 6,
        "sheepskin": 6,
        "shearling": 6,
        "hairy": 5,
        "hair": 3,
        "shaggy": 6,
        "mohair": 5,
        "alpaca": 5,
        "rabbit": 4,
        "fox": 4,
        "wolf": 4,
        "bear": 3,
    },
    colours=roles(("base", (150, 110, 76))),
    slots={"view": 1, "rough": 0.95},
    unit_m=0.1,
)
