"""Exposed parameters (``matloom.lang.params``): addresses, kinds, ranges, units, affects, and
setting them (clamping, errors, round trips that change nothing else)."""

from __future__ import annotations

import pytest

import matloom
from matloom.cli.param_cmds import parse_value
from matloom.lang.params import Param, list_params, set_params, words
from matloom.lang.parser import parse_source

TEXT = """View(0, 0, 2, 2, unit_m=0.5)
Define(groutWidth, 0.03)  # the joint
Define(tile_r, 200)
Define(tile_g, 120)
Define(tile_b, 80)
Define(tiles, Bricks(brick_width=0.5, mortar=0.02))
Define(n, fBm(octaves=4, base_freq=8, seed=3))
Define(m, (fBm(octaves=2, seed=4) + fBm(octaves=3, seed=5)))
Material(
  Layer(1)
    .basecolor(tile_r, tile_g, tile_b)
    .roughness(0.6),
  Layer(tiles)
    .basecolor(90, 90, 90)
    .roughness(((0.4 + (n * 0.1)) + (m * groutWidth)))
    .anisotropy_angle(30)
    .emissive(255, 128, 0, 2)
    .height(-0.01)
)"""


def _by(text: str = TEXT) -> dict[str, Param]:
    return {p.address: p for p in list_params(text)}


def test_the_example_is_canonical() -> None:
    assert matloom.format(TEXT, comments=True) == TEXT


def test_addresses_in_source_order() -> None:
    assert [p.address for p in list_params(TEXT)] == [
        "define:groutWidth",
        "define:tile",
        "define:tiles.Bricks.brick_width",
        "define:tiles.Bricks.brick_height",
        "define:tiles.Bricks.offset",
        "define:tiles.Bricks.mortar",
        "define:tiles.Bricks.feather",
        "define:n.fBm.octaves",
        "define:n.fBm.base_freq",
        "define:n.fBm.seed",
        "define:m.fBm.octaves",
        "define:m.fBm.seed",
        "define:m.fBm#2.octaves",
        "define:m.fBm#2.seed",
        "layer:1.alpha",
        "layer:1.roughness",
        "layer:2.basecolor",
        "layer:2.anisotropy_angle",
        "layer:2.emissive",
        "layer:2.emissive.strength",
        "layer:2.height",
    ]


def test_kinds_ranges_units_and_labels() -> None:
    ps = _by()
    tile = ps["define:tile"]
    assert (tile.kind, tile.value, tile.low, tile.high, tile.label) == (
        "colour",
        (200.0, 120.0, 80.0),
        0.0,
        255.0,
        "tile colour",
    )
    mortar = ps["define:tiles.Bricks.mortar"]
    assert (mortar.kind, mortar.value, mortar.low, mortar.unit) == ("size", 0.02, 0, "units")
    assert mortar.metres == pytest.approx(0.01)  # unit_m = 0.5
    assert mortar.label == "tiles mortar width"
    assert (mortar.line, mortar.col) == (6, 46)
    assert ps["define:n.fBm.octaves"].kind == "count"
    assert ps["define:n.fBm.base_freq"].unit == "cycles/unit"
    assert ps["define:n.fBm.seed"].kind == "seed"
    assert ps["layer:2.anisotropy_angle"].kind == "angle"
    assert ps["layer:2.anisotropy_angle"].unit == "degrees"
    assert ps["layer:2.height"].value == -0.01 and ps["layer:2.height"].kind == "size"
    assert ps["layer:1.roughness"].low == 0 and ps["layer:1.roughness"].high == 1
    assert ps["layer:2.basecolor"].label == "tiles base colour"
    assert ps["define:groutWidth"].label == "grout width"
    assert ps["define:groutWidth"].kind == "scalar" and ps["define:groutWidth"].low is None
    assert ps["define:m.fBm#2.octaves"].label == "m (fBm 2) octaves"
    strength = ps["layer:2.emissive.strength"]
    assert strength.kind == "scalar" and strength.low == 0 and strength.high is None


def test_affects_follows_the_dependency_analysis() -> None:
    ps = _by()
    assert ps["define:groutWidth"].affects == ("roughness",)
    assert ps["define:tile"].affects == ("basecolor",)
    assert ps["layer:2.height"].affects == ("ao", "height", "normal")
    mortar = ps["define:tiles.Bricks.mortar"].affects
    assert "alpha" in mortar and "basecolor" in mortar and "normal" in mortar
    # an unwritten pattern parameter affects what its Define reaches
    assert ps["define:tiles.Bricks.feather"].affects == mortar


def test_a_define_named_in_a_static_parameter_takes_its_kind_and_range() -> None:
    # parsed without the checker: named values in static parameters are checked elsewhere
    program, _ = parse_source(
        "Define(grout, 0.02)\nDefine(b, Bricks(mortar=grout))\nMaterial(Layer(b).roughness(1))"
    )
    assert program is not None
    ps = {p.address: p for p in list_params(program)}
    grout = ps["define:grout"]
    assert (grout.kind, grout.low, grout.unit) == ("size", 0, "units")
    assert "define:b.Bricks.mortar" not in ps  # the Define is the parameter
    assert "roughness" in grout.affects and "alpha" in grout.affects


def test_words() -> None:
    assert words("groutWidth") == "grout width"
    assert words("wear_amount") == "wear amount"
    assert words("tileSizeX") == "tile size x"


def test_parse_value() -> None:
    assert parse_value("0.5") == 0.5 and parse_value("3") == 3
    assert parse_value("#ff8000") == (255.0, 128.0, 0.0)
    assert parse_value("10, 20,30") == (10.0, 20.0, 30.0)
    with pytest.raises(ValueError):
        parse_value("blue")
    with pytest.raises(ValueError):
        parse_value("1,2")


def _changed_lines(a: str, b: str) -> list[tuple[str, str]]:
    al, bl = a.split("\n"), b.split("\n")
    assert len(al) == len(bl)
    return [(x, y) for x, y in zip(al, bl, strict=True) if x != y]


@pytest.mark.parametrize(
    ("address", "value", "line"),
    [
        ("define:groutWidth", 0.05, "Define(groutWidth, 0.05)  # the joint"),
        ("define:tile", (10, 20, 30), None),
        ("define:tiles.Bricks.mortar", 0.1, "Define(tiles, Bricks(brick_width=0.5, mortar=0.1))"),
        (
            "define:m.fBm#2.octaves",
            6,
            "Define(m, (fBm(octaves=2, seed=4) + fBm(octaves=6, seed=5)))",
        ),
        ("layer:1.roughness", 0.25, "    .roughness(0.25),"),
        ("layer:2.basecolor", (1, 2, 3), "    .basecolor(1, 2, 3)"),
        ("layer:2.emissive.strength", 4, "    .emissive(255, 128, 0, 4)"),
        ("layer:2.height", -0.5, "    .height(-0.5)"),
    ],
)
def test_set_then_list_round_trips_and_changes_nothing_else(
    address: str, value: object, line: str | None
) -> None:
    new, warnings = set_params(TEXT, {address: value})
    assert warnings == []
    got = _by(new)[address].value
    assert got == (tuple(float(v) for v in value) if isinstance(value, tuple) else value)
    changed = _changed_lines(TEXT, new)
    if line is not None:
        assert [b for _, b in changed] == [line]
    else:
        assert [b for _, b in changed] == [
            "Define(tile_r, 10)",
            "Define(tile_g, 20)",
            "Define(tile_b, 30)",
        ]
    others = {a: p for a, p in _by(new).items() if a != address}
    before = {a: p for a, p in _by().items() if a != address}
    assert {a: p.value for a, p in others.items()} == {a: p.value for a, p in before.items()}


def test_set_an_unwritten_pattern_parameter_writes_it() -> None:
    new, _ = set_params(TEXT, {"define:tiles.Bricks.brick_height": 0.4})
    assert "Bricks(brick_width=0.5, brick_height=0.4, mortar=0.02)" in new


def test_set_a_colour_component_of_a_slot() -> None:
    new, _ = set_params(TEXT, {"define:tile_g": 7})
    assert "Define(tile_g, 7)" in new and _by(new)["define:tile"].value == (200.0, 7.0, 80.0)


def test_set_clamps_with_a_warning_naming_address_range_and_value() -> None:
    new, warnings = set_params(TEXT, {"layer:1.roughness": 1.7, "define:tile": (300, -5, 10)})
    assert "    .roughness(1)," in new
    assert warnings == [
        "layer:1.roughness: 1.7 is outside [0, 1]; clamped to 1",
        "define:tile: (300, -5, 10) is outside [0, 255]; clamped to (255, 0, 10)",
    ]
    _, warnings = set_params(TEXT, {"define:n.fBm.octaves": 0})
    assert warnings == ["define:n.fBm.octaves: 0 is outside [1, inf]; clamped to 1"]


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"define:grout": 1}, "unknown parameter 'define:grout'; close: define:groutWidth"),
        ({"define:tile": 3}, "define:tile is a colour"),
        ({"layer:1.roughness": (1, 2, 3)}, "layer:1.roughness takes a finite number"),
        ({"define:n.fBm.octaves": 2.5}, "give a whole number"),
        ({"define:tiles.Bricks.brick_width": 0}, "must be (0, inf], got 0"),
        ({"layer:1.roughness": True}, "takes a finite number"),
        ({"layer:1.roughness": float("nan")}, "takes a finite number"),
    ],
)
def test_set_errors_are_one_line_value_errors(values: dict, message: str) -> None:
    with pytest.raises(ValueError) as info:
        set_params(TEXT, values)
    assert message in str(info.value) and "\n" not in str(info.value)


def test_set_result_checks_clean_and_keeps_comments() -> None:
    new, _ = set_params(TEXT, {"define:tiles.Bricks.mortar": 0.08, "layer:2.height": 0.2})
    assert not [d for d in matloom.check(new) if d.is_error]
    assert "# the joint" in new


def test_python_api() -> None:
    assert [p.address for p in matloom.params(TEXT)] == [p.address for p in list_params(TEXT)]
    new, warnings = matloom.set_params(TEXT, {"layer:1.roughness": 0.3})
    assert ".roughness(0.3)" in new and warnings == []
    with pytest.raises(matloom.ProgramError):
        matloom.params("Material(Layer(1).roughness(nope))")
