"""Masonry and tiles: brick bonds, brick paving, ashlar stone walls, square / subway / hexagon /
triangle / checker / mosaic / fish-scale tiles and concrete pavers.

Tile recipes take a micro-texture (``glaze`` by default, ``marble``, ``stone`` ... from the
prompt), shared between all tile colours, so "black and white marble checker tile" gets veined
tiles. Tiles sit on a grout substrate; their mask drives coverage and a bevelled height.
"""

from __future__ import annotations

from matloom.author.builtin.recipes.base import recipe, roles
from matloom.author.builtin.recipes.snippets import (
    HERRINGBONE,
    HEX,
    HEX_TONE,
    SCALES,
    TRIANGLE,
    hash01,
)


def glazed_tile_stack(tile_role: str, height: str, accent_mask: str | None = None) -> str:
    """The Material block shared by the glazed-tile recipes: grout substrate, the ``tile`` mask
    layer with its micro-texture, and optionally a second tone over ``tile * accent_mask``."""
    block = f"""Material(
  Layer(1)
    .basecolor({{rgb:grout}})
    .roughness(0.9),
  Layer(tile)
    .basecolor({{mcol:{tile_role}}})
    .roughness({{micro:rough}})
    {{micro:extra}}
    .height(((tile * {{h:{height}}}) + {{micro:h}}))"""
    if accent_mask is not None:
        block += f""",
  Layer((tile * {accent_mask}))
    .basecolor({{mcol:tile_b}})
    .roughness({{micro:rough}})"""
    return block + "\n)"


TILE_WORDS = {
    "tile": 2.5,
    "tiles": 2.5,
    "tiled": 2.5,
    "ceramic": 1.5,
    "porcelain": 1.5,
    "floor": 0.5,
    "bathroom": 1,
    "kitchen": 0.8,
    "wall tile": 1,
}
TILE_PRESETS = {
    "terracotta": {"tile": (186, 96, 62), "rough": 0.8},
    "saltillo": {"tile": (196, 110, 70), "rough": 0.8},
    "quarry": {"tile": (160, 76, 50), "rough": 0.8},
}
BRICK_ROLES = roles(
    ("brick", (158, 72, 54)),
    ("mortar", (186, 180, 168), "grout"),
    ("brick_dark", (110, 48, 38), "base", ("brick", -0.35)),
)

recipe(
    "brick-wall",
    "masonry",
    "brick wall in running bond: varied bricks, recessed mortar",
    """
View(0, 0, {view}, {view})
Define(brick, Bricks(brick_width=1, brick_height=0.34, offset={offset}, mortar={gap}, feather=0.012))
Define(row, Floor((Y() / 0.34)))
"""
    + hash01("tone", "Floor((X() - (row * {offset})))", "row")
    + """
Define(grit, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:grit}))
Define(burn, fBm(octaves=3, base_freq=2.5, to_01=True, seed={seed:burn}))
Material(
  Layer(1)
    .basecolor({mix:mortar,mortar~-0.2,grit})
    .roughness(0.95)
    .height((grit * {hv:0.004})),
  Layer(brick)
    .basecolor({mix:brick,brick_dark,(((tone * 0.55) + (burn * 0.25)) + (grit * 0.2))})
    .roughness(({rough} + (grit * 0.1)))
    .height((brick * ({h:0.025} + (grit * {hv:0.005}))))
)""",
    tags={
        "brick": 5,
        "bricks": 5,
        "brickwork": 5,
        "masonry": 2.5,
        "wall": 1.2,
        "running bond": 3,
        "stack bond": 3,
        "mortar": 1.5,
        "clay": 1,
    },
    colours=BRICK_ROLES,
    slots={"view": 4, "rough": 0.85, "gap": 0.045, "offset": 0.5},
    patterns=("bricks",),
    count_nouns=("brick", "row", "course"),
    repeat=1.0,
    unit_m=0.23,
    presets={
        "stack": {"offset": 0.0},
        "stacked": {"offset": 0.0},
        "white brick": {"brick": (220, 214, 204)},
        "painted brick": {"brick": (226, 222, 214)},
        "yellow brick": {"brick": (206, 168, 100)},
    },
)

recipe(
    "brick-paving",
    "masonry",
    "brick paving in herringbone: rectangular pavers at right angles",
    """
View(0, 0, {view}, {view})
"""
    + HERRINGBONE.replace("Define(hbHoriz, (hq0 + hq1))\n", "")
    + """
Define(paver, Threshold(((hbEdge - {gap}) * 40), below_at=0, above_at=1))
Define(grit, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({mix:mortar,mortar~-0.25,grit})
    .roughness(0.95),
  Layer(paver)
    .basecolor({mix:brick,brick_dark,((hbTone * 0.7) + (grit * 0.3))})
    .roughness(({rough} + (grit * 0.1)))
    .height((paver * {h:0.02}))
)""",
    tags={
        "brick": 3,
        "bricks": 3,
        "paving": 3,
        "pavers": 4,
        "paver": 4,
        "path": 1.5,
        "driveway": 2.5,
        "patio": 1.5,
        "pavement": 2,
        "walkway": 2,
    },
    colours=roles(
        ("brick", (160, 76, 56)),
        ("mortar", (150, 144, 132), "grout"),
        ("brick_dark", (110, 50, 40), "base", ("brick", -0.35)),
    ),
    slots={"view": 4, "rough": 0.85, "gap": 0.06, "hb_w": 0.35},
    patterns=("herringbone", "zigzag"),
    unit_m=0.3,
)

recipe(
    "stone-block-wall",
    "masonry",
    "ashlar stone wall: large dressed blocks of varied width",
    """
View(0, 0, {view}, {view})
Define(block, Bricks(brick_width=1.3, brick_height=0.55, offset=0.37, mortar={gap}, feather=0.02))
Define(row, Floor((Y() / 0.55)))
"""
    + hash01("tone", "Floor(((X() - (row * 0.481)) / 1.3))", "row")
    + """
Define(chisel, fBm(octaves=5, base_freq={mf:14}, to_01=True, seed={seed:chisel}))
Define(grit, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({mix:mortar,mortar~-0.2,grit})
    .roughness(0.95),
  Layer(block)
    .basecolor({mix:stone,stone_dark,(((tone * 0.5) + (chisel * 0.3)) + (grit * 0.2))})
    .roughness(({rough} + (grit * 0.1)))
    .height((block * (({h:0.03} + (chisel * {hv:0.02})) + (grit * {hv:0.004}))))
)""",
    tags={
        "stone wall": 5,
        "ashlar": 6,
        "block": 2,
        "blocks": 2,
        "masonry": 2.5,
        "castle": 3,
        "fortress": 3,
        "limestone blocks": 4,
        "stonework": 5,
        "wall": 1.2,
        "stone": 1.5,
        "dungeon": 2.5,
    },
    colours=roles(
        ("stone", (170, 162, 148)),
        ("mortar", (120, 114, 104), "grout"),
        ("stone_dark", (120, 112, 100), "base", ("stone", -0.32)),
    ),
    slots={"view": 4, "rough": 0.85, "gap": 0.05},
    unit_m=0.4,
    count_nouns=("block", "row", "course"),
    repeat=1.3,
)

recipe(
    "square-tiles",
    "masonry",
    "square tiles with bevelled edges on a grout bed",
    """
View(0, 0, {view}, {view})
Define(tile, Bricks(brick_width=1, brick_height=1, offset=0, mortar={gap}, feather=0.04))
"""
    + hash01("tone", "Floor(X())", "Floor(Y())")
    + """
{micro:def}
Define(groutGrit, fBm(octaves=3, base_freq={mf:60}, to_01=True, seed={seed:grout}))
Material(
  Layer(1)
    .basecolor({mix:grout,grout~-0.2,groutGrit})
    .roughness(0.9),
  Layer(tile)
    .basecolor({mcol:tile})
    .roughness({micro:rough})
    {micro:extra}
    .height(((tile * {h:0.02}) + {micro:h})),
  Layer(((tile * tone) * {vary}))
    .basecolor({mcol:tile~-0.12})
    .roughness({micro:rough})
)""",
    tags={**TILE_WORDS, "square": 1.5, "terracotta": 2, "saltillo": 3, "quarry": 1},
    colours=roles(
        ("tile", (226, 224, 218)), ("grout", (150, 146, 138), "grout", ("tile", -0.35, "c"))
    ),
    slots={"view": 3, "rough": 0.2, "gap": 0.05, "vary": 0.35},
    micro="glaze",
    patterns=("squares", "grid"),
    presets=TILE_PRESETS,
    count_nouns=("tile",),
    repeat=1.0,
    unit_m=0.3,
)

recipe(
    "subway-tiles",
    "masonry",
    "glossy subway tiles: 2:1 rectangles in running bond",
    """
View(0, 0, {view}, {view})
Define(tile, Bricks(brick_width=1, brick_height=0.5, offset=0.5, mortar={gap}, feather=0.05))
{micro:def}
"""
    + glazed_tile_stack("tile", "0.02"),
    tags={**TILE_WORDS, "subway": 5, "metro": 4, "backsplash": 3, "rectangular": 1},
    colours=roles(
        ("tile", (236, 236, 232)), ("grout", (170, 168, 162), "grout", ("tile", -0.3, "c"))
    ),
    slots={"view": 3, "rough": 0.15, "gap": 0.04},
    micro="glaze",
    patterns=("bricks",),
    unit_m=0.15,
    count_nouns=("tile", "row"),
    repeat=0.5,
)

recipe(
    "hexagon-tiles",
    "masonry",
    "hexagonal tiles on grout, per-tile tone variation",
    "View(0, 0, {view}, {view})\n"
    + HEX
    + "\n"
    + HEX_TONE
    + """
Define(tile, Threshold(((((0.5 - {gap}) - hexD)) * 60), below_at=0, above_at=1))
Define(pick, Threshold(((hexTone - (1 - {mix_share})) * 50), below_at=0, above_at=1))
{micro:def}
"""
    + glazed_tile_stack("tile", "0.02", "pick"),
    tags={**TILE_WORDS, "hexagon": 2, "hex": 2, "hexagonal": 2},
    colours=roles(
        ("tile", (230, 230, 226)),
        ("tile_b", (200, 200, 196), "accent", ("tile", -0.12)),
        ("grout", (120, 118, 112), "grout", ("tile", -0.45, "c")),
    ),
    slots={"view": 4, "rough": 0.2, "gap": 0.04, "mix_share": 0.4},
    micro="glaze",
    patterns=("hexagon",),
    unit_m=0.15,
)

recipe(
    "triangle-tiles",
    "masonry",
    "triangular tiles in a 60-degree lattice, two alternating tones",
    "View(0, 0, {view}, {view})\n"
    + TRIANGLE
    + """
Define(tile, Threshold(((triEdge - {gap}) * 80), below_at=0, above_at=1))
{micro:def}
"""
    + glazed_tile_stack("tile", "0.02", "triUp"),
    tags={**TILE_WORDS, "triangle": 2, "triangular": 2, "triangles": 2},
    colours=roles(
        ("tile", (220, 218, 210)),
        ("tile_b", (190, 188, 180), "accent", ("tile", -0.14)),
        ("grout", (120, 118, 112), "grout", ("tile", -0.45, "c")),
    ),
    slots={"view": 4, "rough": 0.2, "gap": 0.03},
    micro="glaze",
    patterns=("triangles",),
    unit_m=0.15,
)

recipe(
    "checker-tiles",
    "masonry",
    "checkerboard floor tiles in two alternating colours",
    """
View(0, 0, {view}, {view})
Define(tile, Bricks(brick_width=1, brick_height=1, offset=0, mortar={gap}, feather=0.03))
Define(checker, Threshold((Sin((X() * 3.1416)) * Sin((Y() * 3.1416))), below_at=0, above_at=0, above_to=1))
{micro:def}
"""
    + glazed_tile_stack("tile_a", "0.015", "checker"),
    tags={**TILE_WORDS, "checkerboard": 2, "chess": 2, "diner": 1.5},
    colours=roles(
        ("tile_a", (24, 24, 26)),
        ("tile_b", (232, 230, 224), "accent"),
        ("grout", (128, 126, 122), "grout"),
    ),
    slots={"view": 4, "rough": 0.15, "gap": 0.02},
    micro="glaze",
    patterns=("checker",),
    count_nouns=("tile", "square"),
    repeat=1.0,
    unit_m=0.3,
)

recipe(
    "mosaic-tiles",
    "masonry",
    "mosaic of small square tesserae in a three-colour random mix",
    """
View(0, 0, {view}, {view})
Define(tess, Bricks(brick_width=0.25, brick_height=0.25, offset=0, mortar={gap}, feather=0.02))
"""
    + hash01("pick", "Floor((X() * 4))", "Floor((Y() * 4))")
    + """
{micro:def}
Material(
  Layer(1)
    .basecolor({rgb:grout})
    .roughness(0.9),
  Layer(tess)
    .basecolor({mcol:tile_a})
    .roughness({micro:rough})
    {micro:extra}
    .height(((tess * {h:0.01}) + {micro:h})),
  Layer((tess * Threshold(((pick - 0.62) * 100), below_at=0, above_at=1)))
    .basecolor({mcol:tile_b})
    .roughness({micro:rough}),
  Layer((tess * Threshold(((0.3 - pick) * 100), below_at=0, above_at=1)))
    .basecolor({mcol:tile_c})
    .roughness({micro:rough})
)""",
    tags={
        **TILE_WORDS,
        "mosaic": 5,
        "tesserae": 6,
        "tessera": 6,
        "pool": 2,
        "glass tile": 2,
        "smalti": 6,
    },
    colours=roles(
        ("tile_a", (40, 110, 170)),
        ("tile_b", (80, 160, 200), "accent"),
        ("tile_c", (230, 236, 240), "accent"),
        ("grout", (200, 198, 192), "grout"),
    ),
    slots={"view": 2, "rough": 0.15, "gap": 0.025},
    micro="glaze",
    patterns=("mosaic",),
    unit_m=0.2,
)

recipe(
    "fish-scale-tiles",
    "masonry",
    "fish-scale (scallop) tiles in offset overlapping rows",
    "View(0, 0, {view}, {view})\n"
    + SCALES
    + """
Define(rim, Threshold(((scaleRim - {gap}) * 40), below_at=0, above_at=1))
{micro:def}
Material(
  Layer(1)
    .basecolor({rgb:grout})
    .roughness(0.9),
  Layer(rim)
    .basecolor({mix:tile,tile~-0.2,scaleRim})
    .roughness({micro:rough})
    {micro:extra}
    .height(((rim * (1 - scaleRim)) * {h:0.03}))
)""",
    tags={**TILE_WORDS, "fish scale": 5, "scallop": 4, "scalloped": 4, "fan": 2, "mermaid": 3},
    colours=roles(("tile", (90, 160, 170)), ("grout", (220, 218, 210), "grout")),
    slots={"view": 3, "rough": 0.15, "gap": 0.06, "scale_w": 1, "scale_h": 0.5},
    micro="glaze",
    patterns=("scales", "waves"),
    unit_m=0.1,
)

recipe(
    "concrete-pavers",
    "masonry",
    "grey concrete pavers in a basket-weave pattern",
    """
View(0, 0, {view}, {view})
Define(checker, Threshold((Sin((X() * 3.1416)) * Sin((Y() * 3.1416))), below_at=0, above_at=0, above_to=1))
Define(paver, ((checker * Bricks(brick_width=1, brick_height=0.5, offset=0, mortar={gap}, feather=0.04)) + ((1 - checker) * Bricks(brick_width=0.5, brick_height=1, offset=0, mortar={gap}, feather=0.04))))
"""
    + hash01("tone", "Floor((X() * 2))", "Floor((Y() * 2))")
    + """
Define(grit, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:grit}))
Material(
  Layer(1)
    .basecolor({rgb:grout})
    .roughness(0.95),
  Layer(paver)
    .basecolor({mix:base,base_alt,((tone * 0.6) + (grit * 0.4))})
    .roughness(({rough} + (grit * 0.1)))
    .height((paver * ({h:0.02} + (grit * {hv:0.003}))))
)""",
    tags={
        "pavers": 5,
        "paver": 5,
        "paving": 3,
        "pavement": 3,
        "patterned": 1.5,
        "sidewalk": 3,
        "concrete blocks": 3,
        "interlocking": 4,
        "plaza": 2,
        "walkway": 2,
    },
    colours=roles(
        ("base", (160, 158, 154)),
        ("base_alt", (124, 120, 116), "base", ("base", -0.22)),
        ("grout", (92, 88, 82), "grout"),
    ),
    slots={"view": 4, "rough": 0.85, "gap": 0.035},
    patterns=("basketweave", "checker"),
    unit_m=0.2,
)
