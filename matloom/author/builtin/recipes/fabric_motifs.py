"""More printed fabric motifs: camouflage, diamonds (argyle / Navajo), chevron,
square-in-square, splatter, honeycomb, tie-dye and waves (split from ``fabric_prints``)."""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.fabric_prints import PRINT_WORDS
from matloom.author.builtin.recipes.snippets import HEX

recipe(
    "camouflage",
    "fabric",
    "camouflage: layered organic blotches in three or four colours",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(blobA, fBm(octaves=4, base_freq=0.9, to_01=True, seed={seed:blobA}))
Define(blobB, fBm(octaves=4, base_freq=1.1, to_01=True, seed={seed:blobB}))
Define(blobC, fBm(octaves=4, base_freq=1.4, to_01=True, seed={seed:blobC}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((blobA - 0.5) * 40), below_at=0, above_at=1))
    .basecolor({mcol:camo_b})
    .roughness({micro:rough}),
  Layer(Threshold(((blobB - 0.56) * 40), below_at=0, above_at=1))
    .basecolor({mcol:camo_c})
    .roughness({micro:rough}),
  Layer(Threshold(((blobC - 0.6) * 40), below_at=0, above_at=1))
    .basecolor({mcol:camo_d})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "camouflage": 7,
        "camo": 7,
        "military": 3,
        "army": 2.5,
        "woodland": 3,
        "hunting": 3,
        "disruptive": 3,
        "pvc": 0.5,
    },
    colours=roles(
        ("base", (156, 140, 100)),
        ("camo_b", (80, 90, 50), "accent"),
        ("camo_c", (96, 70, 44), "accent"),
        ("camo_d", (30, 30, 26), "accent"),
    ),
    slots={"view": 2, "rough": 0.85},
    micro="weave",
    patterns=("camo",),
    unit_m=0.2,
)

recipe(
    "diamond-print",
    "fabric",
    "diamond print (argyle / Navajo): nested diamonds with cross lines",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, (((Y() / 1.4) - Floor((Y() / 1.4))) - 0.5))
Define(dia, (Abs(lx) + Abs(ly)))
Define(outer, Threshold(((0.46 - dia) * 60), below_at=0, above_at=1))
Define(inner, Threshold(((0.2 - dia) * 60), below_at=0, above_at=1))
Define(band, Threshold(((0.04 - Abs(((Y() / 1.4) - (Floor((Y() / 1.4)) + 0.02)))) * 60), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer((outer * (1 - Threshold(((0.36 - dia) * 60), below_at=0, above_at=1))))
    .basecolor({mcol:accent})
    .roughness({micro:rough}),
  Layer(inner)
    .basecolor({mcol:accent2})
    .roughness({micro:rough}),
  Layer(Max(band, Threshold(((0.012 - Abs((Abs(lx) - Abs(ly)))) * 60), below_at=0, above_at=1)))
    .basecolor({mcol:accent})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "argyle": 7,
        "navajo": 6,
        "aztec": 6,
        "tribal": 4,
        "southwestern": 5,
        "kilim": 5,
        "diamond": 2,
        "diamonds": 2,
        "harlequin": 5,
        "ikat": 4,
    },
    colours=roles(
        ("base", (236, 230, 214)),
        ("accent", (120, 70, 40), "accent"),
        ("accent2", (160, 50, 34), "accent"),
    ),
    slots={"view": 3, "rough": 0.85},
    micro="knit",
    patterns=("diamonds", "zigzag"),
    unit_m=0.05,
)

recipe(
    "chevron-print",
    "fabric",
    "chevron / zig-zag stripes",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(zig, (Y() + Abs(((X() - Floor(X())) - 0.5))))
Define(band, (zig - Floor(zig)))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((band - 0.5) * 60), below_at=0, above_at=1))
    .basecolor({mcol:stripe})
    .roughness({micro:rough})
)""",
    tags={**PRINT_WORDS, "chevron": 6, "zigzag": 6, "zig zag": 6, "missoni": 5, "flame stitch": 5},
    colours=roles(("base", (236, 234, 226)), ("stripe", (40, 40, 44), "accent")),
    slots={"view": 4, "rough": 0.8},
    micro="weave",
    patterns=("zigzag",),
    unit_m=0.03,
)

recipe(
    "square-print",
    "fabric",
    "geometric print: concentric squares-in-squares in three colours",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, ((Y() - Floor(Y())) - 0.5))
Define(sq, Max(Abs(lx), Abs(ly)))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((0.42 - sq) * 80), below_at=0, above_at=1))
    .basecolor({mcol:accent})
    .roughness({micro:rough}),
  Layer(Threshold(((0.28 - sq) * 80), below_at=0, above_at=1))
    .basecolor({mcol:accent2})
    .roughness({micro:rough}),
  Layer(Threshold(((0.13 - sq) * 80), below_at=0, above_at=1))
    .basecolor({mcol:base})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "geometric": 3,
        "retro": 3,
        "60's": 3,
        "70s": 3,
        "mod": 2,
        "square in square": 6,
        "squares": 1.5,
        "concentric": 3,
        "op art": 4,
    },
    colours=roles(
        ("base", (232, 120, 30)),
        ("accent", (236, 200, 40), "accent"),
        ("accent2", (110, 50, 140), "accent"),
    ),
    slots={"view": 3, "rough": 0.7},
    micro="weave",
    patterns=("squares", "grid"),
    unit_m=0.05,
)

recipe(
    "splatter-print",
    "fabric",
    "paint-splatter print: drops and blots over mottled patches",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(patch, fBm(octaves=4, base_freq=1, to_01=True, seed={seed:patch}))
Define(dropA, Worley(base_freq=5, to_01=True, seed={seed:dropA}))
Define(dropB, Worley(base_freq=8, to_01=True, seed={seed:dropB}))
Define(spray, fBm(octaves=3, base_freq={mf:40}, to_01=True, seed={seed:spray}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((patch - 0.52) * 30), below_at=0, above_at=1))
    .basecolor({mcol:base2})
    .roughness({micro:rough}),
  Layer(Threshold(((((0.16 - dropA) * 30) + (spray - 0.5)) * 3), below_at=0, above_at=1))
    .basecolor({mcol:splat})
    .roughness({micro:rough}),
  Layer(Threshold(((((0.12 - dropB) * 30) + (spray - 0.5)) * 3), below_at=0, above_at=1))
    .basecolor({mcol:splat2})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "splatter": 6,
        "splattered": 6,
        "splashed": 5,
        "paint splatter": 6,
        "drips": 3,
        "pollock": 5,
        "speckled": 1.5,
    },
    colours=roles(
        ("base", (96, 70, 44)),
        ("base2", (44, 70, 40)),
        ("splat", (150, 200, 120), "accent"),
        ("splat2", (236, 236, 230), "accent"),
    ),
    slots={"view": 2, "rough": 0.8},
    micro="weave",
    patterns=("splatter", "speckle"),
    unit_m=0.2,
)

recipe(
    "honeycomb-print",
    "fabric",
    "honeycomb pattern: hexagon outlines over the base colour",
    "View(0, 0, {view}, {view})\n{micro:def}\n"
    + HEX
    + """
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height(((Threshold((((0.5 - {line}) - hexD) * 40), below_at=0, above_at=1) * {h:0.01}) + {micro:h})),
  Layer(Threshold(((hexD - (0.5 - {line})) * 40), below_at=0, above_at=1))
    .basecolor({mcol:line_col})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "honeycomb": 5,
        "honey comb": 5,
        "hexagon": 2,
        "hexagonal": 2,
        "beeswax": 1.5,
        "wraps": 1.5,
        "wrap": 1.5,
        "coated": 0.5,
    },
    colours=roles(
        ("base", (222, 186, 110)), ("line_col", (170, 120, 50), "accent", ("base", -0.45))
    ),
    slots={"view": 5, "rough": 0.5, "line": 0.07},
    micro="weave",
    patterns=("hexagon",),
    unit_m=0.01,
)

recipe(
    "tie-dye",
    "fabric",
    "tie-dye: swirled rings of bleeding colour",
    """
View(-{view*0.5}, -{view*0.5}, {view*0.5}, {view*0.5})
{micro:def}
Define(warp, fBm(octaves=4, base_freq=1, seed={seed:warp}))
Define(swirl, Sin((((Sqrt(((X() * X()) + (Y() * Y()))) * 6) + (warp * 3)) + ((X() * 0.8) - (Y() * 0.5)))))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((swirl * 2) + 0.5), below_at=0, above_at=1))
    .basecolor({mix:dye_a,dye_b,((warp * 0.5) + 0.5)})
    .roughness({micro:rough}),
  Layer(Threshold((((0 - swirl) * 3) - 1.2), below_at=0, above_at=1))
    .basecolor({mcol:dye_c})
    .roughness({micro:rough})
)""",
    tags={**PRINT_WORDS, "tie dye": 8, "tiedye": 8, "hippie": 3, "psychedelic": 4, "dyed": 1.5},
    colours=roles(
        ("base", (240, 236, 228)),
        ("dye_a", (220, 40, 120), "accent"),
        ("dye_b", (40, 120, 220), "accent"),
        ("dye_c", (250, 200, 40), "accent"),
    ),
    slots={"view": 4, "rough": 0.85},
    micro="weave",
    patterns=("tiedye", "marbled"),
    unit_m=0.1,
)

recipe(
    "wave-print",
    "fabric",
    "wavy stripes / scallop print",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(wave, ((Y() + (Sin((X() * 3.1416 * 2)) * {amp})) - Floor((Y() + (Sin((X() * 3.1416 * 2)) * {amp})))))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((wave - 0.55) * 60), below_at=0, above_at=1))
    .basecolor({mcol:stripe})
    .roughness({micro:rough}),
  Layer(Threshold(((0.04 - Abs((wave - 0.3))) * 60), below_at=0, above_at=1))
    .basecolor({mcol:line})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "wavy": 4,
        "waves": 4,
        "wave": 3,
        "ripple": 3,
        "scallops": 3,
        "ogee": 4,
        "undulating": 3,
    },
    colours=roles(
        ("base", (230, 226, 214)),
        ("stripe", (60, 110, 160), "accent"),
        ("line", (200, 160, 80), "accent"),
    ),
    slots={"view": 4, "rough": 0.8, "amp": 0.18},
    micro="weave",
    patterns=("waves",),
    unit_m=0.03,
)
