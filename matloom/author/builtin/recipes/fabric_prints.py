"""Printed and yarn-dyed fabric patterns: stripes, gingham, tartan, houndstooth, polka dots,
florals, camouflage, diamonds (argyle / Navajo), chevron, square-in-square, splatter,
honeycomb, tie-dye and wave prints.

Each pattern is a set of masks over a ``base`` colour layer. All colours are shaded by the
micro-texture (woven threads by default; "vinyl", "knit", "paper" ... swap it), so the same
pattern reads as cloth, plastic or paper. The first prompt colour is the background unless a
colour is tied to "stripes", "dots", "flowers" ... by the prompt.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.fabric import FABRIC_WORDS, ORIENT

PRINT_WORDS = {**FABRIC_WORDS, "print": 1.5, "printed": 1.5, "vinyl": 0.5}

recipe(
    "stripes",
    "fabric",
    "striped fabric: alternating bands of two colours with a fine pinstripe",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(band, ({axis} - Floor({axis})))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold((((band - (1 - {width})) * 60)), below_at=0, above_at=1))
    .basecolor({mcol:stripe})
    .roughness({micro:rough}),
  Layer(Threshold(((0.03 - Abs((band - 0.25))) * 80), below_at=0, above_at=1))
    .basecolor({mcol:pin})
    .roughness({micro:rough})
)""",
    tags={**PRINT_WORDS, "awning": 3, "seersucker": 2, "ticking": 4, "breton": 4},
    colours=roles(
        ("base", (236, 234, 226)),
        ("stripe", (40, 60, 120), "accent"),
        ("pin", (200, 200, 200), "accent", ("stripe", 0.5)),
    ),
    slots={"view": 4, "rough": 0.8, "width": 0.4, "axis": "X()"},
    micro="weave",
    patterns=("stripes", "rows"),
    presets=ORIENT,
    count_nouns=("stripe",),
    repeat=1.0,
    unit_m=0.03,
)

recipe(
    "gingham",
    "fabric",
    "gingham / check: crossing translucent colour bands on white",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(bandX, Threshold(((0.5 - (X() - Floor(X()))) * 60), below_at=0, above_at=1))
Define(bandY, Threshold(((0.5 - (Y() - Floor(Y()))) * 60), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer((bandX * 0.55))
    .basecolor({mcol:check})
    .roughness({micro:rough}),
  Layer((bandY * 0.55))
    .basecolor({mcol:check})
    .roughness({micro:rough})
)""",
    tags={**PRINT_WORDS, "gingham": 6, "picnic": 2, "tablecloth": 3, "buffalo": 4},
    colours=roles(("check", (190, 40, 44), "accent"), ("base", (240, 238, 232))),
    slots={"view": 6, "rough": 0.8},
    micro="weave",
    patterns=("checker", "checks"),
    count_nouns=("check", "square"),
    repeat=1.0,
    unit_m=0.01,
)

recipe(
    "tartan",
    "fabric",
    "tartan / plaid: crossing bands of several widths and colours",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(fx, (X() - Floor(X())))
Define(fy, (Y() - Floor(Y())))
Define(wideX, Threshold(((0.17 - Abs((fx - 0.3))) * 60), below_at=0, above_at=1))
Define(wideY, Threshold(((0.17 - Abs((fy - 0.3))) * 60), below_at=0, above_at=1))
Define(thinX, Threshold(((0.03 - Abs((fx - 0.75))) * 60), below_at=0, above_at=1))
Define(thinY, Threshold(((0.03 - Abs((fy - 0.75))) * 60), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(((wideX + wideY) * 0.5))
    .basecolor({mcol:band})
    .roughness({micro:rough}),
  Layer(((thinX + thinY) * 0.6))
    .basecolor({mcol:line})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "tartan": 7,
        "plaid": 7,
        "flannel": 2,
        "scottish": 3,
        "kilt": 4,
        "madras": 5,
    },
    colours=roles(
        ("base", (170, 30, 40)),
        ("band", (20, 40, 70), "accent"),
        ("line", (220, 200, 80), "accent"),
    ),
    slots={"view": 2, "rough": 0.85},
    micro="twill",
    patterns=("plaid", "checks"),
    unit_m=0.1,
)

recipe(
    "houndstooth",
    "fabric",
    "houndstooth: 2/2 twill woven with four dark and four light yarns in warp and weft",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(hi, Floor((X() * 8)))
Define(hj, Floor((Y() * 8)))
Define(top, Threshold(((1.5 - ((hi - hj) - (4 * Floor(((hi - hj) / 4))))) * 10), below_at=0, above_at=1))
Define(warpDark, Threshold(((3.5 - (hi - (8 * Floor((hi / 8))))) * 10), below_at=0, above_at=1))
Define(weftDark, Threshold(((3.5 - (hj - (8 * Floor((hj / 8))))) * 10), below_at=0, above_at=1))
Define(tooth, ((top * warpDark) + ((1 - top) * weftDark)))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(tooth)
    .basecolor({mcol:tooth})
    .roughness({micro:rough})
)""",
    tags={**PRINT_WORDS, "houndstooth": 8, "dogtooth": 8, "pied de poule": 8, "tweed": 1.5},
    colours=roles(("tooth", (24, 24, 26), "accent"), ("base", (236, 232, 220))),
    slots={"view": 5, "rough": 0.85},
    micro="twill",
    patterns=("houndstooth",),
    unit_m=0.01,
)

recipe(
    "polka-dots",
    "fabric",
    "polka dots: round dots in a staggered grid",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(row, Floor(Y()))
Define(dx, (((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5))
Define(dy, ((Y() - row) - 0.5))
Define(dot, Threshold((({radius} - Sqrt(((dx * dx) + (dy * dy)))) * 60), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer(dot)
    .basecolor({mcol:dot})
    .roughness({micro:rough})
)""",
    tags={**PRINT_WORDS, "polka": 6, "spotty": 4, "dalmatian": 2},
    colours=roles(("base", (200, 30, 40)), ("dot", (240, 238, 232), "accent")),
    slots={"view": 5, "rough": 0.8, "radius": 0.22},
    micro="weave",
    patterns=("dots",),
    count_nouns=("dot",),
    repeat=1.0,
    unit_m=0.02,
)

recipe(
    "floral-print",
    "fabric",
    "floral print: five-petal flowers of two sizes with leaves",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, ((Y() - Floor(Y())) - 0.5))
Define(r, Sqrt(((lx * lx) + (ly * ly))))
Define(c, (lx / (r + 0.0001)))
Define(petals, Threshold((((0.28 + (0.1 * (((16 * (c * (c * (c * (c * c))))) - (20 * (c * (c * c)))) + (5 * c)))) - r) * 40), below_at=0, above_at=1))
Define(sx, ((((X() * 1.6) + 0.5) - Floor(((X() * 1.6) + 0.5))) - 0.5))
Define(sy, ((((Y() * 1.6) + 0.3) - Floor(((Y() * 1.6) + 0.3))) - 0.5))
Define(small, Threshold(((0.13 - Sqrt(((sx * sx) + (sy * sy)))) * 50), below_at=0, above_at=1))
Define(leaf, Threshold(((0.09 - Abs(((Abs(lx) + Abs(ly)) - 0.45))) * 30), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height({micro:h}),
  Layer((leaf * (1 - petals)))
    .basecolor({mcol:leaf})
    .roughness({micro:rough}),
  Layer((small * (1 - petals)))
    .basecolor({mcol:flower2})
    .roughness({micro:rough}),
  Layer(petals)
    .basecolor({mix:flower,flower~0.3,r})
    .roughness({micro:rough}),
  Layer(Threshold(((0.06 - r) * 60), below_at=0, above_at=1))
    .basecolor({rgb:centre})
    .roughness({micro:rough})
)""",
    tags={
        **PRINT_WORDS,
        "floral": 5,
        "flower": 4,
        "flowers": 4,
        "flowery": 4,
        "botanical": 4,
        "blossom": 4,
        "rose": 1,
        "daisy": 4,
        "calico": 1,
        "chintz": 5,
        "paisley": 3,
        "liberty": 2,
        "trees": 2,
        "leaves": 2,
    },
    colours=roles(
        ("base", (232, 226, 214)),
        ("flower", (210, 80, 110), "accent"),
        ("leaf", (80, 130, 70), "accent"),
        ("flower2", (240, 200, 90), "accent"),
        ("centre", (240, 210, 80), "accent", ("flower2", 0.1)),
    ),
    slots={"view": 3, "rough": 0.8},
    micro="weave",
    patterns=("floral",),
    unit_m=0.05,
)
