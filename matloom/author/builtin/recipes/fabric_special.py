"""Special fabric constructions: lace, mesh / net, quilted, embossed, strips with gaps, sequins,
terry, tweed, basket weave and rope (split from ``fabric`` to keep modules short)."""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.fabric import FABRIC_WORDS

recipe(
    "lace",
    "fabric",
    "lace: fine net ground with floral rings and scalloped motifs",
    """
View(0, 0, {view}, {view})
Define(net, Max(Threshold(((0.12 - Abs(Sin((((X() + Y()) * 7) * 3.1416)))) * 12), below_at=0, above_at=1), Threshold(((0.12 - Abs(Sin((((X() - Y()) * 7) * 3.1416)))) * 12), below_at=0, above_at=1)))
Define(lx, ((X() - Floor(X())) - 0.5))
Define(ly, ((Y() - Floor(Y())) - 0.5))
Define(r, Sqrt(((lx * lx) + (ly * ly))))
Define(motif, Max(Threshold(((0.035 - Abs((r - 0.32))) * 60), below_at=0, above_at=1), Threshold(((0.09 - Abs((r - 0.14))) * 30), below_at=0, above_at=1)))
Define(web, Threshold(((0.03 - Abs((Abs(lx) - Abs(ly)))) * 50), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:back})
    .roughness(0.9),
  Layer(Max(Max(net, motif), (web * Threshold(((0.45 - r) * 20), below_at=0, above_at=1))))
    .basecolor({rgb:thread})
    .roughness(0.8)
    .sheen(0.4)
    .height((Max(net, motif) * {h:0.006}))
)""",
    tags={
        "lace": 7,
        "lacy": 6,
        "doily": 6,
        "crochet": 5,
        "openwork": 5,
        "cobweb": 4,
        "spider": 2,
        "web": 1.5,
        "delicate": 1.5,
        "bridal": 3,
        "tatting": 6,
        "filigree": 3,
        "intricate": 1,
        **FABRIC_WORDS,
    },
    colours=roles(("thread", (238, 236, 230)), ("back", (30, 30, 34), "base")),
    slots={"view": 3, "rough": 0.8},
    patterns=("mesh", "floral"),
    unit_m=0.05,
)

recipe(
    "mesh-net",
    "fabric",
    "mesh / net fabric: thin threads around open diamond holes",
    """
View(0, 0, {view}, {view})
Define(cellA, Abs(Sin((((X() + Y()) * {mesh_f}) * 3.1416))))
Define(cellB, Abs(Sin((((X() - Y()) * {mesh_f}) * 3.1416))))
Define(thread, Threshold((((1 - Min(cellA, cellB)) - (1 - {thread_w})) * 12), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:back})
    .roughness(0.9),
  Layer(thread)
    .basecolor({mix:base~-0.3,base,thread})
    .roughness({rough})
    .sheen(0.3)
    .height((thread * {h:0.01}))
)""",
    tags={
        "mesh": 4,
        "net": 4,
        "netting": 5,
        "tulle": 6,
        "fishnet": 7,
        "netted": 5,
        "airflow": 2,
        "breathable": 1.5,
        "open": 1,
        "holes": 1,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (60, 60, 64)), ("back", (200, 198, 192), "grout", ("base", -0.7, "c"))),
    slots={"view": 2, "rough": 0.6, "mesh_f": 3, "thread_w": 0.25},
    patterns=("mesh", "grid"),
    unit_m=0.05,
)

recipe(
    "quilted",
    "fabric",
    "quilted fabric: puffy diamond pillows between stitched seams",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(u, ((X() + Y()) * 0.7071))
Define(v, ((Y() - X()) * 0.7071))
Define(pillow, (Abs(Sin((u * 3.1416))) * Abs(Sin((v * 3.1416)))))
Material(
  Layer(1)
    .basecolor({mix:base~-0.3,base,Sqrt(pillow)})
    .roughness({micro:rough})
    {micro:extra}
    .height(((Sqrt(pillow) * {h:0.08}) + {micro:h}))
)""",
    tags={
        "quilted": 7,
        "quilt": 6,
        "quilting": 6,
        "padded": 5,
        "puffer": 5,
        "duvet": 4,
        "down": 1,
        "matelasse": 6,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (190, 186, 200))),
    slots={"view": 3, "rough": 0.6},
    micro="smooth",
    patterns=("quilted", "diamonds"),
    unit_m=0.08,
)

recipe(
    "embossed-fabric",
    "fabric",
    "fabric pressed with rows of raised circles or dots",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(row, Floor((Y() / 0.866)))
Define(cx, ((((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5)))
Define(cy, ((((Y() / 0.866) - row) - 0.5) * 0.866))
Define(ring, Sqrt(((cx * cx) + (cy * cy))))
Define(boss, Threshold(((0.34 - ring) * 12), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({mix:base~-0.2,base,((boss * 0.6) + ({micro:field} * 0.4))})
    .roughness({micro:rough})
    {micro:extra}
    .height(((boss * {h:0.04}) + {micro:h}))
)""",
    tags={
        "embossed": 3,
        "pressed": 4,
        "raised": 2,
        "dimension": 1.5,
        "bubbles": 3,
        "bubble": 2,
        "textured": 1,
        "puckered": 4,
        "seersucker": 4,
        "relief": 1,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (130, 200, 200))),
    slots={"view": 5, "rough": 0.7},
    micro="weave",
    patterns=("circles", "dots", "quilted"),
    count_nouns=("circle", "row", "dot"),
    repeat=1.0,
    unit_m=0.02,
)

recipe(
    "fabric-strips",
    "fabric",
    "parallel strips of fabric with open gaps and stitched seams",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(strip, Translate(Bricks(brick_width=100, brick_height=1, offset=0, axis="row", mortar={gap}, feather=0.03), 50, 0))
Define(seam, Threshold(((0.015 - Abs((((X() / {seam_every}) - Floor((X() / {seam_every}))) - 0.5))) * 80), below_at=0, above_at=1))
Material(
  Layer(1)
    .basecolor({rgb:back})
    .roughness(1),
  Layer(strip)
    .basecolor({mcol:base})
    .roughness({micro:rough})
    {micro:extra}
    .height(((strip * {h:0.02}) + {micro:h})),
  Layer((strip * seam))
    .basecolor({rgb:base~-0.35})
    .roughness(0.9)
)""",
    tags={
        "strips": 5,
        "strip": 5,
        "straps": 4,
        "strap": 4,
        "webbing": 5,
        "bands": 2,
        "gaps": 2.5,
        "spaces": 2,
        "spacing": 2,
        "not connected": 2,
        "slats": 1,
        "ribbons": 4,
        "ribbon": 4,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (70, 70, 74)), ("back", (16, 16, 18), "grout")),
    slots={"view": 4, "rough": 0.85, "gap": 0.35, "seam_every": 1.6},
    micro="weave",
    patterns=("rows",),
    count_nouns=("strip", "strap"),
    repeat=1.0,
    unit_m=0.08,
)

recipe(
    "sequins",
    "fabric",
    "sequinned fabric: overlapping shiny metallic discs",
    """
View(0, 0, {view}, {view})
Define(row, Floor((Y() / 0.8)))
Define(cx, ((((X() + ((row - (2 * Floor((row / 2)))) * 0.5)) - Floor((X() + ((row - (2 * Floor((row / 2)))) * 0.5)))) - 0.5)))
Define(cy, (((Y() / 0.8) - row) - 0.5))
Define(disc, Threshold(((0.48 - Sqrt(((cx * cx) + (cy * cy)))) * 30), below_at=0, above_at=1))
Define(tilt, fBm(octaves=2, base_freq={mf:12}, to_01=True, seed={seed:tilt}))
Material(
  Layer(1)
    .basecolor({rgb:base~-0.6})
    .roughness(0.8),
  Layer(disc)
    .basecolor({mix:base~-0.35,base~0.25,tilt})
    .metallic(0.9)
    .roughness(0.15)
    .height((disc * (((cx * 0.5) + (cy * 0.5)) + (tilt * 0.4)) * {h:0.08}))
)""",
    tags={
        "sequin": 7,
        "sequins": 7,
        "sequined": 7,
        "sequinned": 7,
        "paillette": 6,
        "glitter": 4,
        "sparkly": 3,
        "sparkle": 3,
        "disco": 3,
        "cocktail": 1.5,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (226, 196, 120))),
    slots={"view": 8, "rough": 0.35},
    patterns=("scales", "circles"),
    unit_m=0.006,
)

recipe(
    "terry-towel",
    "fabric",
    "terry cloth: dense loops of soft pile",
    """
View(0, 0, {view}, {view})
Define(loop, Worley(base_freq={mf:45}, to_01=True, seed={seed:loop}))
Define(tone, fBm(octaves=3, base_freq=1, to_01=True, seed={seed:tone}))
Material(
  Layer(1)
    .basecolor({mix:base,base~-0.3,((loop * 0.7) + (tone * 0.3))})
    .roughness(0.95)
    .sheen(0.5)
    .height(((1 - loop) * {hv:0.012}))
)""",
    tags={
        "terry": 7,
        "towel": 6,
        "towelling": 6,
        "toweling": 6,
        "bathrobe": 5,
        "loops": 3,
        "loop": 2,
        "chenille": 4,
        **FABRIC_WORDS,
    },
    colours=roles(("base", (236, 234, 228))),
    slots={"view": 1, "rough": 0.95},
    unit_m=0.03,
)

recipe(
    "tweed",
    "fabric",
    "tweed: coarse twill with multicoloured flecks",
    """
View(0, 0, {view}, {view})
{micro:def}
Define(flecks, fBm(octaves=3, base_freq={mf:40}, to_01=True, seed={seed:flecks}))
Define(flecks2, fBm(octaves=3, base_freq={mf:50}, to_01=True, seed={seed:flecks2}))
Material(
  Layer(1)
    .basecolor({mcol:base})
    .roughness(0.95)
    {micro:extra}
    .height({micro:h}),
  Layer(Threshold(((flecks - 0.62) * 20), below_at=0, above_at=1))
    .basecolor({mcol:fleck})
    .roughness(0.95),
  Layer(Threshold(((flecks2 - 0.64) * 20), below_at=0, above_at=1))
    .basecolor({mcol:fleck2})
    .roughness(0.95)
)""",
    tags={
        "tweed": 7,
        "harris": 4,
        "heather": 3,
        "heathered": 5,
        "melange": 5,
        "marled": 5,
        "flecked": 2,
        "wool": 1.5,
        **FABRIC_WORDS,
    },
    colours=roles(
        ("base", (120, 104, 84)),
        ("fleck", (170, 150, 120), "accent"),
        ("fleck2", (70, 60, 52), "accent"),
    ),
    slots={"view": 1.5, "rough": 0.95},
    micro="twill",
    patterns=("speckle",),
    unit_m=0.03,
)

recipe(
    "basket-weave-fabric",
    "fabric",
    "basket-weave cloth: groups of parallel yarns over and under",
    """
View(0, 0, {view}, {view})
Define(block, Weave(base_freq=4, warp_width=0.96, feather=0.3))
Define(checker, Threshold((Sin((X() * 4 * 3.1416)) * Sin((Y() * 4 * 3.1416))), below_at=0, above_at=0, above_to=1))
Define(yarnX, Abs(Sin(((X() * {yarns} * 4) * 3.1416))))
Define(yarnY, Abs(Sin(((Y() * {yarns} * 4) * 3.1416))))
Define(yarn, ((checker * yarnY) + ((1 - checker) * yarnX)))
Material(
  Layer(1)
    .basecolor({rgb:gap})
    .roughness(0.9),
  Layer(block)
    .basecolor({mix:base~-0.3,base,yarn})
    .roughness({rough})
    .sheen(0.3)
    .height((block * ((yarn * {h:0.01}) + {h:0.01}))),
  Layer((block * checker))
    .basecolor({mix:second~-0.3,second,yarn})
    .roughness({rough})
)""",
    tags={
        "basket weave": 7,
        "basketweave": 7,
        "basket": 2,
        "hopsack": 6,
        "panama": 4,
        "oxford": 3,
        "yarns": 1.5,
        "weaving": 1.5,
        "bumpy": 1,
        **FABRIC_WORDS,
    },
    colours=roles(
        ("base", (30, 30, 32)),
        ("second", (230, 228, 222), "accent"),
        ("gap", (20, 20, 20), "grout"),
    ),
    slots={"view": 1, "rough": 0.5, "yarns": 3},
    patterns=("basketweave", "weave"),
    count_nouns=("yarn",),
    unit_m=0.03,
)

recipe(
    "rope",
    "fabric",
    "twisted rope: rows of helical strands with fibre detail",
    """
View(0, 0, {view}, {view})
Define(row, ((Y() / 0.5) - Floor((Y() / 0.5))))
Define(round, Sqrt(Max((1 - ((((row * 2) - 1)) * (((row * 2) - 1)))), 0)))
Define(strand, Abs(Sin((((X() * 3) + (Y() * 6)) * 3.1416))))
Define(fibre, fBm(octaves=4, base_freq_x={mf:80}, base_freq_y={mf:20}, to_01=True, seed={seed:fibre}))
Material(
  Layer(1)
    .basecolor({mix:base~-0.5,base,(((round * 0.5) + (strand * 0.3)) + (fibre * 0.2))})
    .roughness(0.9)
    .height((((round * {h:0.05}) + (strand * round * {h:0.02})) + (fibre * {hv:0.003})))
)""",
    tags={
        "rope": 7,
        "ropes": 7,
        "cord": 3,
        "cordage": 6,
        "braided": 3,
        "twisted": 3,
        "hawser": 6,
        "nautical": 2,
        "twine": 3,
        "strength": 0.5,
    },
    colours=roles(("base", (200, 172, 122))),
    slots={"view": 2, "rough": 0.9},
    count_nouns=("rope", "strand"),
    repeat=0.5,
    unit_m=0.05,
)
