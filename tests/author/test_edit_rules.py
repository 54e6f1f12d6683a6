"""Offline edits: a table of requests over library entries and examples, with the parameter
changes each must make (or its refusal), all checked clean and local. The other categories
(overlays added, lines rewritten, escalation) are in test_edit_categories.py."""

from __future__ import annotations

from pathlib import Path

import pytest

from matloom.author.edit import EditRefused, edit_offline
from matloom.library.author import author

ROOT = Path(__file__).resolve().parents[2] / "matloom"


def _file(rel: str) -> str:
    return (ROOT / rel).read_text(encoding="utf-8")


def _entry(name: str) -> str:
    from matloom.library import load_library

    return load_library().entry(name).program


PROGRAMS = {
    "black": lambda: _file("examples/black_ceramic_tiles.mat"),
    "weathered": lambda: _file("examples/weathered_brick.mat"),
    "quick": lambda: _file("examples/bricks_quickstart.mat"),
    "brickwall": lambda: _file("library/entries/masonry/brick-wall.mat"),
    "square": lambda: _file("library/entries/tiles/square-tiles.mat"),
    "rustymoss": lambda: author("rusty mossy brick wall").program,
    "worndirty": lambda: author("worn dirty leather").program,
    "painted": lambda: _entry("painted-metal"),
    "rusted": lambda: _entry("rusted-metal"),
    "brushed": lambda: _entry("brushed-metal"),
    "velvet": lambda: _entry("velvet"),
    "leather": lambda: _entry("leather"),
    "porcelain": lambda: _entry("porcelain-white-glaze"),
    "delft": lambda: _entry("delft-blue-tiles-tulip"),
    "concrete": lambda: _entry("polished-concrete"),
    "cobble": lambda: _entry("cobblestone-fan-pattern"),
    "zellige": lambda: _entry("zellige-glazed-tiles"),
    "teak": lambda: _entry("teak-deck-caulked"),
    "flag": lambda: _entry("flagstone"),
    "copper": lambda: _entry("copper-patina"),
    "toy": lambda: _entry("toy-brick-stud-baseplate"),
    "mud": lambda: _entry("muddy-field-puddles"),
    "croc": lambda: _entry("crocodile"),
    "hazard": lambda: _entry("hazard-stripes-painted-steel"),
    "sidewalk": lambda: _entry("sidewalk-slabs-expansion-joints"),
}

_cache: dict[str, str] = {}


def program(name: str) -> str:
    if name not in _cache:
        _cache[name] = PROGRAMS[name]()
    return _cache[name]


# (program, request, expected assignments (a subset, values approx), expected View changes).
# The steps are those of author/edit/words.toml, sized to show in a lit preview: a joint x2 or
# /2, a roughness comparative at least 0.22 and half the way to its end (down: x0.45), a finish
# adjective the library's finish roughness (matte 0.82), a tone step at least 14 L* (CIELAB).
TABLE: list[tuple[str, str, dict[str, object], dict[str, object]]] = [
    # the paper's three
    ("black", "wider grout", {"define:tileMask.Bricks.mortar": 0.04}, {}),
    ("black", "blue glaze", {"layer:2.basecolor.base": (40, 80, 170)}, {}),
    (
        "black",
        "higher roughness",  # 0.85 + 0.22 (clamped), 0.04 + (1 - 0.04) / 2; the coat x0.3
        {"layer:1.roughness.base": 1.0, "layer:2.roughness.base": 0.52, "layer:2.coat": 0.285},
        {},
    ),
    # joints
    ("black", "narrower mortar joints", {"define:tileMask.Bricks.mortar": 0.01}, {}),
    ("square", "wider grout", {"define:tile.Bricks.mortar": 0.1}, {}),  # written from its default
    (
        "brickwall",
        "wider mortar",
        {
            "define:brick.Bricks.mortar": 0.1,
            "define:edge.Bricks.mortar": 0.1,
            "define:tone.Bricks.mortar": 0.1,
        },
        {},
    ),
    ("weathered", "thinner joints", {"define:brick.Bricks.mortar": 0.03}, {}),
    # the composed brick wall has unit_m=0.23: a 12 mm joint is 0.012 / 0.23 units
    ("rustymoss", "12 mm mortar joints", {"define:brick.Bricks.mortar": 0.012 / 0.23}, {}),
    # colours: named, comparative (CIELAB), a named colour that selects ("the blue"), a family
    ("black", "darker grout", {"layer:1.basecolor.base": (8, 11, 15)}, {}),
    ("black", "slightly darker grout", {"layer:1.basecolor.base": (26, 28, 30)}, {}),
    ("square", "blue glaze", {"define:tile": (40, 80, 170)}, {}),
    ("brickwall", "darker grout", {"define:mortar": (132, 126, 113)}, {}),
    ("brickwall", "make the bricks white", {"define:brick": (236, 236, 232)}, {}),
    ("weathered", "darker mortar", {"layer:1.basecolor": (120, 116, 106)}, {}),
    ("quick", "green bricks", {"layer:2.basecolor": (60, 130, 60)}, {}),
    ("rustymoss", "lighter mortar", {"define:mortar": (231, 225, 211)}, {}),
    ("delft", "make the blue darker", {"define:cobalt": (0, 35, 98)}, {}),
    ("concrete", "lighter grey", {"define:base": (206, 204, 198)}, {}),
    (
        "cobble",
        "grey stones",
        {"define:stone": (128, 128, 128), "define:stone_warm": (124, 124, 124)},
        {},
    ),
    ("painted", "red paint", {"define:paint_col": (186, 32, 36)}, {}),
    ("brickwall", "redder bricks", {"define:brick": (166, 52, 39)}, {}),  # 0.45 of the way
    # the cobbles' mask reads a Define named for the joint: the first layer is the grout
    ("cobble", "white grout", {"define:joint": (236, 236, 232)}, {}),
    # roughness: comparatives, finish adjectives, flipped words, the clear coat with it
    ("square", "higher roughness", {"define:rough": 0.6, "layer:1.roughness": 1.0}, {}),
    ("square", "make it glossier", {"define:rough": 0.03, "layer:1.roughness": 0.405}, {}),
    ("brickwall", "rougher", {"define:rough": 1.0, "layer:1.roughness": 1.0}, {}),
    ("quick", "matte", {"layer:1.roughness": 0.82, "layer:2.roughness": 0.82}, {}),
    ("quick", "shinier", {"layer:1.roughness": 0.225, "layer:2.roughness": 0.225}, {}),
    (
        "weathered",
        "make it smoother",
        {"layer:1.roughness": 0.4275, "layer:2.roughness.base": 0.315},
        {},
    ),
    ("black", "less shiny tiles", {"layer:2.roughness.base": 0.52, "layer:2.coat": 0.285}, {}),
    (
        "porcelain",
        "make it less shiny",
        {"define:rough": 0.515, "layer:1.coat": 0.3, "layer:2.coat": 0.3},
        {},
    ),
    ("leather", "it is too rough", {"define:rough": 0.252, "layer:1.coat": 0.525}, {}),
    ("painted", "make the coating rougher", {"define:rough": 0.725}, {}),
    # single channels and relief
    ("velvet", "less sheen", {"layer:1.sheen.base": 0.4}, {}),
    ("velvet", "no sheen", {"layer:1.sheen.base": 0.0}, {}),
    ("leather", "more clearcoat", {"layer:1.coat": 0.525}, {}),
    ("brushed", "less metallic", {"layer:1.metallic": 0.5}, {}),
    ("brickwall", "deeper relief", {"define:relief": 2.0}, {}),
    ("brickwall", "flatter", {"define:relief": 0.5}, {}),
    # scale
    (
        "black",
        "bigger tiles",
        {"define:tileMask.Bricks.brick_width": 0.75, "define:tileMask.Bricks.brick_height": 0.75},
        {},
    ),
    # the square tiles tile: x0.6 is the nearest factor that keeps whole tiles across the View
    ("square", "smaller tiles", {"define:tile.Bricks.brick_height": 0.6}, {}),
    # no noun: the View zooms, so every feature (bricks and noises) scales in step
    ("weathered", "denser", {}, {"window": [0.25, 0.25, 9.25, 9.25]}),
    ("weathered", "sparser", {}, {"window": [0.25, 0.25, 4.25, 4.25]}),
    (
        "concrete",
        "larger aggregate",
        {"define:aggD.Worley.base_freq": 17.3333, "define:aggV.Worley.base_freq": 17.3333},
        {},
    ),
    # the cobbles are drawn from constants: the View zooms (x2, so the repeat stays whole)
    ("cobble", "smaller stones", {}, {"window": [0.1, 0.05, 4.1, 4.05]}),
    # conditions: an amount, a measured coverage
    ("rustymoss", "more rust", {"define:cover": 0.8}, {}),
    ("rustymoss", "less rust", {"define:cover": 0.2}, {}),
    ("rustymoss", "less moss", {"define:cover2": 0.2}, {}),
    ("worndirty", "more wear", {"define:cover": 0.8}, {}),
    ("worndirty", "less dirt", {"define:cover2": 0.2}, {}),
    ("rusted", "less rust", {"define:wear": 0.3}, {}),
    # View
    ("black", "make it tileable", {}, {"tileable": True}),
    ("weathered", "seamless please", {}, {"tileable": True}),
    ("black", "1 m wide", {}, {"unit_m": 0.5}),
    ("square", "make it 30 cm across", {}, {"unit_m": 0.1}),
    ("brickwall", "3 ft wide", {}, {"unit_m": 0.2286}),
    # unit_m known (0.23 m per unit, 4 units): the window grows x3 (whole, so it still tiles)
    ("rustymoss", "make it 3 m wide", {}, {"window": [0.13, 0.13, 12.13, 12.13]}),
    # third round (classes of the v3 "no"s): the new colour of a swap, not the old one
    (
        "zellige",
        "swap the emerald glaze for a deep cobalt blue",
        {"define:glaze": (11, 42, 110)},
        {},
    ),
    # what a clause keeps ("don't touch the glaze") is not edited
    (
        "zellige",
        "take only the grout down to a warm mid grey; don't touch the glaze",
        {"define:grout": (138, 128, 113)},
        {},
    ),
    # "scale ... up", "double": x2, the tiles' own pattern (whole cells: it tiles)
    (
        "zellige",
        "scale the tiles up, double their size",
        {"define:tile_edge.Bricks.brick_width": 2.0, "define:pick.Bricks.brick_height": 2.0},
        {},
    ),
    # a colour word on the joint is no colour request when a width word is there; a wider
    # joint is at least 3.5 pixels of a 192-pixel preview (View 2 units: 0.0365)
    ("teak", "widen the black caulking seams", {"define:strip.Bricks.mortar": 0.0364583}, {}),
    ("croc", "widen the grooves between the scales", {"define:bellyEdge.Bricks.mortar": 0.044}, {}),
    # a noun naming a layer's coverage ("the slabs") recolours that layer's colours
    ("flag", "make the slabs a cool blue-grey", {"define:base": (87, 101, 165)}, {}),
    # no parameter draws the flagstones: the View zooms (a material noun, not refused)
    ("flag", "smaller flagstones", {}, {"window": [0.0, 0.0, 6.0, 6.0]}),
    ("hazard", "wider stripes", {}, {"window": [0.8, 0.55, 1.3, 1.05]}),
    # "pull X back": less of the condition (the overlay's cover), not the metal's colour
    ("copper", "pull the verdigris back", {"define:cover": 0.42}, {}),
    # the material's own noun ("the baseplate", "the leather", "the mud") is its main colour
    ("toy", "make the baseplate bright red", {"define:plastic": (249, 17, 23)}, {}),
    ("croc", "dye the leather oxblood red", {"define:base": (140, 30, 32)}, {}),
    ("mud", "make the mud a reddish clay brown", {"define:mud": (140, 65, 40)}, {}),
    # a condition's noun qualified by a property is not "more of it"
    ("mud", "push the boot prints deeper into the mud", {"define:relief": 2.0}, {}),
    ("toy", "taller studs", {"define:relief": 2.0}, {}),
    # a swap's old colour selects the part ("the yellow stripes"); "keep the black" is kept
    (
        "hazard",
        "swap only the yellow stripes for safety orange, keep the black",
        {"define:yellow": (232, 118, 30)},
        {},
    ),
    (
        "sidewalk",
        "lighten the concrete but keep the joints dark",
        {"define:concrete": (214, 210, 203)},
        {},
    ),
]

REFUSED: list[tuple[str, str, str]] = [
    ("black", "make it fluffy", "no offline rule"),
    ("black", "less rust", "no rust in this program to reduce"),
    ("square", "make it tileable", "tileable already"),
    ("square", "make the hinges red", "no part of the program is named like 'hinges'"),
    ("velvet", "less transparent", "no transmission parameter"),
    ("cobble", "widen the joints between the stones", "no joint"),
    ("quick", "rougher", ""),  # not refused: checked below as a contrast
]


def _close(a: object, b: object) -> bool:
    if isinstance(b, tuple):
        return isinstance(a, list | tuple) and all(
            abs(x - y) <= 1.0 for x, y in zip(a, b, strict=True)
        )
    return isinstance(a, int | float) and abs(float(a) - float(b)) <= 1e-3 * max(1.0, abs(float(b)))  # type: ignore[arg-type]


def test_table_is_large_enough() -> None:
    assert len(TABLE) >= 30
    assert len({p for p, *_ in TABLE}) >= 10


@pytest.mark.parametrize(
    ("name", "request_", "expected", "view"), TABLE, ids=[f"{p}:{r}" for p, r, *_ in TABLE]
)
def test_offline_edit(
    name: str, request_: str, expected: dict[str, object], view: dict[str, object]
) -> None:
    text = program(name)
    result = edit_offline(text, request_, size=32)
    plan = result.report.plan
    for address, value in expected.items():
        # a colour slot whose name is also another Define's is the pseudo-parameter colour:NAME
        slot = address.replace("define:", "colour:")
        if address not in plan["assignments"] and isinstance(value, tuple):
            address = slot
        assert address in plan["assignments"], (address, plan["assignments"])
        assert _close(plan["assignments"][address], value), (address, plan["assignments"][address])
    assert plan["view"] == view
    # never a no-op, never seeds, always clean and local
    assert result.program != text
    assert result.report.changes
    assert not any("seed" in c.address for c in result.report.changes)
    assert result.report.ok, result.report.locality.describe()
    if plan["intended"] and "alpha" not in plan["intended"]:
        assert set(result.report.locality.changed) <= result.report.locality.allowed
    assert not result.report.warnings, result.report.warnings  # every step shows


@pytest.mark.parametrize(("name", "request_", "reason"), [r for r in REFUSED if r[2]])
def test_refusal_lists_parameters(name: str, request_: str, reason: str) -> None:
    with pytest.raises(EditRefused, match=reason) as info:
        edit_offline(program(name), request_, size=32)
    assert info.value.params, "a refusal lists the parameters it could change"
    assert "parameters it could change:" in str(info.value)


def test_already_at_limit_is_refused_not_a_noop() -> None:
    text = program("quick").replace("roughness(0.5)", "roughness(1)")
    with pytest.raises(EditRefused, match="already at the limit"):
        edit_offline(text, "rougher", size=32)


@pytest.mark.parametrize(
    ("name", "request_", "line"),
    [
        # no parameter draws the lead came: the edges of its distance threshold move
        ("leaded", "thicker lead came between the diamonds", "define:came"),
        # "more flecks": the measured coverage of the flecks' layer
        ("tweed", "pack in more of the coloured flecks", "define:flecks"),
    ],
)
def test_coverage_by_threshold_edges(name: str, request_: str, line: str) -> None:
    text = {"leaded": "leaded-diamond-quarry-window", "tweed": "herringbone-tweed"}[name]
    result = edit_offline(_entry(text), request_, size=32)
    assert list(result.report.plan["replace"]) == [line]
    assert result.report.ok and not result.report.plan["assignments"]


@pytest.mark.parametrize(
    "request_", ["drier mud, kill most of the wet shine", "make the mud a reddish clay brown"]
)
def test_a_condition_noun_naming_the_material_adds_no_overlay(request_: str) -> None:
    result = edit_offline(program("mud"), request_, size=32)
    assert "add" not in result.report.plan and result.report.plan["rule"] != "overlay"


def test_physical_size_changes_no_map() -> None:
    result = edit_offline(program("black"), "2 m wide", size=32)
    assert result.report.locality.changed == ()
    assert "unit_m=1" in result.program
