"""Fabric constructions: plain weave, twill, denim, knit jersey, rib knit, corduroy, velvet,
fleece / felt, satin / silk, burlap, lace, mesh / net, quilted, embossed, strips with gaps,
sequins, terry, tweed, basket weave and rope.

Woven and knitted recipes take a micro-texture (``weave``, ``twill``, ``knit`` ...), chosen from
the prompt's fibre words, that shades every colour by its thread field. Plain colours of long
descriptions fill the ``base`` role; a second colour fills ``fleck`` (mottling, heather).
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles

FABRIC_WORDS = {
    "fabric": 1.5,
    "cloth": 1.5,
    "textile": 1.5,
    "cotton": 1.2,
    "polyester": 1.2,
    "wool": 1.0,
    "woven": 1.0,
    "garment": 1.0,
    "blend": 0.5,
    "weight": 0.5,
    "midweight": 0.5,
    "upholstery": 1.0,
    "drape": 0.5,
    "shirt": 0.8,
    "dress": 0.8,
    "blanket": 0.8,
    "nylon": 1.0,
}
ORIENT = {
    "horizontal": {"axis": "Y()", "cross": "X()"},
    "horizontally": {"axis": "Y()", "cross": "X()"},
    "vertical": {"axis": "X()", "cross": "Y()"},
    "vertically": {"axis": "X()", "cross": "Y()"},
    "diagonal": {"axis": "((X() + Y()) * 0.7071)", "cross": "((Y() - X()) * 0.7071)"},
}
PLAIN_ROLES = roles(("base", (176, 168, 156)), ("fleck", (150, 142, 132), "base", ("base", -0.12)))

recipe(
    "plain-weave",
    "fabric",
    "plain-weave cloth: visible over-under threads, soft slub mottling",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(slub, fBm(octaves=4, base_freq_x={mf:2}, base_freq_y={mf:24}, to_01=True, seed={seed:slub}))
Define(tone, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(((slub * 0.35) + (tone * 0.25)))
    .basecolor({mcol:fleck})
    .roughness({micro:rough})
)""",
    tags={
        **FABRIC_WORDS,
        "linen": 2.5,
        "canvas": 2.5,
        "muslin": 3,
        "calico": 3,
        "poplin": 3,
        "chambray": 2,
        "broadcloth": 3,
        "solid": 0.5,
        "plain": 1,
        "woven": 1.5,
        "thread": 1,
        "weave": 1,
    },
    colours=PLAIN_ROLES,
    slots={"view": 2, "rough": 0.85},
    micro="weave",
    patterns=("weave",),
    unit_m=0.05,
)

recipe(
    "twill-fabric",
    "fabric",
    "twill cloth: fine diagonal ribs from a 2/2 twill draft",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(tone, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer((tone * 0.4))
    .basecolor({mcol:fleck})
    .roughness({micro:rough})
)""",
    tags={
        **FABRIC_WORDS,
        "twill": 5,
        "gabardine": 5,
        "chino": 5,
        "drill": 3,
        "serge": 5,
        "khaki": 1,
        "trousers": 2,
    },
    colours=PLAIN_ROLES,
    slots={"view": 2, "rough": 0.8},
    micro="twill",
    unit_m=0.05,
)

recipe(
    "denim",
    "fabric",
    "denim: indigo 3/1 twill with pale weft flecks and faded streaks",
    """
View(0, 0, {view}, {view})
Define(tc, Floor((X() * {mf:90})))
Define(tr, Floor((Y() * {mf:90})))
Define(tm, ((tc - tr) - (4 * Floor(((tc - tr) / 4)))))
Define(weftShow, Threshold(((tm - 2.5) * 10), below_at=0, above_at=1))
Define(thread, Weave(over=3, under=1, base_freq={mf:90}, warp_width=0.92, feather=0.5))
Define(slub, fBm(octaves=4, base_freq_x={mf:3}, base_freq_y={mf:20}, to_01=True, seed={seed:slub}))
Define(fade, fBm(octaves=4, base_freq_x=1.5, base_freq_y=4, to_01=True, seed={seed:fade}))
Material(
  Layer(1)
    .basecolor({mix:warp~-0.3,warp,((thread * 0.5) + (slub * 0.5))})
    .roughness({rough})
    .height((thread * {hv:0.004})),
  Layer((weftShow * 0.45))
    .basecolor({rgb:weft})
    .roughness({rough}),
  Layer(Threshold(((fade - 0.55) * 3), below_at=0, above_at=0.45))
    .basecolor({rgb:warp~0.3})
    .roughness({rough})
)""",
    tags={"denim": 7, "jeans": 6, "jean": 4, "dungaree": 5, "indigo": 2, **FABRIC_WORDS},
    colours=roles(("warp", (56, 82, 130)), ("weft", (200, 204, 210), "accent")),
    slots={"view": 1, "rough": 0.85},
    unit_m=0.03,
)

recipe(
    "knit-jersey",
    "fabric",
    "jersey knit: columns of small V-shaped loops",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(tone, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer((tone * 0.3))
    .basecolor({mcol:fleck})
    .roughness({micro:rough})
)""",
    tags={
        "knit": 4,
        "knitted": 4,
        "jersey": 5,
        "stockinette": 6,
        "sweater": 3,
        "t shirt": 3,
        "stretchy": 1.5,
        "stretch": 1,
        "interlock": 4,
        **FABRIC_WORDS,
    },
    colours=PLAIN_ROLES,
    slots={"view": 1.5, "rough": 0.85},
    micro="knit",
    unit_m=0.03,
)

recipe(
    "rib-knit",
    "fabric",
    "rib knit: raised parallel ridges of knit loops",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(rib, Abs(Sin((({axis} / {rib_w}) * 3.1416))))
Material(
  Layer(1)
    .basecolor({mix:base~-0.25,base,((rib * 0.6) + ({micro:field} * 0.4))})
    .roughness({micro:rough})
    {micro:extra}
    .height(((rib * {h:0.03}) + {micro:h}))
)""",
    tags={
        "rib": 4,
        "ribbed": 4,
        "ridges": 2,
        "rows": 1.5,
        "knit": 2,
        "knitting": 2,
        "cuff": 3,
        "ribbing": 5,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (170, 160, 150))),
    slots={"view": 2, "rough": 0.8, "axis": "X()", "rib_w": 0.16},
    micro="knit",
    patterns=("rows",),
    presets=ORIENT,
    count_nouns=("rib", "row", "ridge"),
    repeat=0.16,
    unit_m=0.08,
)

recipe(
    "corduroy",
    "fabric",
    "corduroy: soft piled wales with deep grooves and nap sheen",
    """
View(0, 0, {view}, {view})
Define(wale, Abs(Sin((({axis} / {rib_w}) * 3.1416))))
Define(pile, fBm(octaves=4, base_freq={mf:90}, to_01=True, seed={seed:pile}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.35,base,((wale * 0.75) + (pile * 0.25))})
    .roughness(0.9)
    .sheen(0.8)
    .height(((Sqrt(wale) * {h:0.03}) + (pile * {hv:0.002})))
)""",
    tags={
        "corduroy": 7,
        "cord": 2,
        "wale": 6,
        "wales": 6,
        "nap": 2,
        "raised nap": 3,
        "embossed": 1.5,
        "lines": 1,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (150, 110, 70))),
    slots={"view": 2, "rough": 0.9, "axis": "X()", "rib_w": 0.2},
    patterns=("rows", "stripes"),
    presets=ORIENT,
    unit_m=0.05,
)

recipe(
    "velvet",
    "fabric",
    "velvet: deep pile with crushed light and dark sheen patches",
    """
View(0, 0, {view}, {view})
Define(crush, fBm(octaves=5, base_freq=1.2, to_01=True, seed={seed:crush}))
Define(pile, fBm(octaves=4, base_freq={mf:100}, to_01=True, seed={seed:pile}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.45,base~0.1,((crush * 0.8) + (pile * 0.2))})
    .roughness(0.95)
    .sheen(1)
    .height(((crush * {h:0.01}) + (pile * {hv:0.002})))
)""",
    tags={
        "velvet": 7,
        "velour": 6,
        "velveteen": 6,
        "crushed": 2,
        "plush": 3,
        "luxurious": 1,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (120, 24, 48))),
    slots={"view": 2, "rough": 0.95},
    unit_m=0.3,
)

recipe(
    "fleece-felt",
    "fabric",
    "fleece / felt: dense fuzzy fibres with soft mottling",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(tone, fBm(octaves=4, base_freq=1.5, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness(0.95)
    {micro:extra}
    .height({micro:h}),
  Layer((tone * 0.45))
    .basecolor({mcol:fleck})
    .roughness(0.95)
)""",
    tags={
        "fleece": 6,
        "felt": 6,
        "felted": 6,
        "flannel": 4,
        "fuzzy": 2.5,
        "fluffy": 2.5,
        "minky": 5,
        "sherpa": 5,
        "soft": 1,
        "boucle": 4,
        "blanket": 1.5,
        **FABRIC_WORDS,
    },
    colours=PLAIN_ROLES,
    slots={"view": 2, "rough": 0.95},
    micro="fleece",
    unit_m=0.05,
)

recipe(
    "satin-silk",
    "fabric",
    "satin / silk: smooth lustrous cloth with soft flowing folds",
    """
View(0, 0, {view}, {view})
Define(fold, fBm(octaves=3, base_freq_x=0.5, base_freq_y=1.6, to_01=True, seed={seed:fold}))
Define(weave, Weave(over=4, under=1, shift=2, base_freq={mf:90}, warp_width=0.95, feather=0.6))
Material(
  Layer(1)
    .basecolor({mix:base~-0.35,base~0.2,fold})
    .roughness({rough})
    .sheen(0.5)
    .anisotropy(0.5)
    .height(((fold * {h:0.06}) + (weave * {hv:0.001})))
)""",
    tags={
        "satin": 6,
        "silk": 6,
        "silky": 3,
        "charmeuse": 6,
        "sateen": 6,
        "lustrous": 2,
        "taffeta": 5,
        "chiffon": 3,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (200, 170, 190))),
    slots={"view": 2, "rough": 0.3},
    unit_m=0.3,
)

recipe(
    "burlap",
    "fabric",
    "burlap / hessian: coarse open weave of hairy jute yarns",
    """
View(0, 0, {view}, {view})
Define(yarn, Weave(base_freq={mf:22}, warp_width=0.7, feather=0.5))
Define(hair, fBm(octaves=4, base_freq={mf:80}, to_01=True, seed={seed:hair}))
Define(slub, fBm(octaves=3, base_freq_x={mf:3}, base_freq_y={mf:12}, to_01=True, seed={seed:slub}))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(1),
  Layer(Threshold(((yarn + (hair * 0.3)) - 0.25), below_at=0, above_at=1))
    .basecolor({mix:base~-0.3,base,((yarn * 0.6) + (slub * 0.4))})
    .roughness(0.95)
    .height((yarn * {hv:0.012}))
)""",
    tags={
        "burlap": 7,
        "hessian": 7,
        "jute": 6,
        "sack": 4,
        "sackcloth": 6,
        "gunny": 6,
        "twine": 2,
        "coarse": 1.5,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (178, 146, 100)), ("gap", (40, 32, 22), "grout", ("base", -0.8))),
    slots={"view": 1, "rough": 0.95},
    patterns=("weave",),
    unit_m=0.05,
)
