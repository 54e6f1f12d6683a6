"""Offline edits: a table of requests over library entries and examples, with the parameter
changes each must make (or its refusal), all checked clean and local."""

from __future__ import annotations

from pathlib import Path

import pytest

from matloom.author.edit import EditRefused, edit_offline
from matloom.library.author import author

ROOT = Path(__file__).resolve().parents[2] / "matloom"


def _file(rel: str) -> str:
    return (ROOT / rel).read_text(encoding="utf-8")


PROGRAMS = {
    "black": lambda: _file("examples/black_ceramic_tiles.mat"),
    "weathered": lambda: _file("examples/weathered_brick.mat"),
    "quick": lambda: _file("examples/bricks_quickstart.mat"),
    "brickwall": lambda: _file("library/entries/masonry/brick-wall.mat"),
    "square": lambda: _file("library/entries/tiles/square-tiles.mat"),
    "rustymoss": lambda: author("rusty mossy brick wall").program,
    "worndirty": lambda: author("worn dirty leather").program,
}

_cache: dict[str, str] = {}


def program(name: str) -> str:
    if name not in _cache:
        _cache[name] = PROGRAMS[name]()
    return _cache[name]


# (program, request, expected assignments (a subset, values approx), expected View changes)
TABLE: list[tuple[str, str, dict[str, object], dict[str, object]]] = [
    # the paper's three
    ("black", "wider grout", {"define:tileMask.Bricks.mortar": 0.032}, {}),
    ("black", "blue glaze", {"layer:2.basecolor.base": (40, 80, 170)}, {}),
    (
        "black",
        "higher roughness",
        {"layer:1.roughness.base": 0.91, "layer:2.roughness.base": 0.424},
        {},
    ),
    # joints
    ("black", "narrower mortar joints", {"define:tileMask.Bricks.mortar": 0.0125}, {}),
    ("square", "wider grout", {"define:tile.Bricks.mortar": 0.08}, {}),  # written from its default
    (
        "brickwall",
        "wider mortar",
        {
            "define:brick.Bricks.mortar": 0.08,
            "define:edge.Bricks.mortar": 0.08,
            "define:tone.Bricks.mortar": 0.08,
        },
        {},
    ),
    ("weathered", "thinner joints", {"define:brick.Bricks.mortar": 0.0375}, {}),
    # the composed brick wall has unit_m=0.23: a 12 mm joint is 0.012 / 0.23 units
    ("rustymoss", "12 mm mortar joints", {"define:brick.Bricks.mortar": 0.012 / 0.23}, {}),
    # colours
    ("black", "darker grout", {"layer:1.basecolor.base": (28, 29, 32)}, {}),
    ("square", "blue glaze", {"define:tile": (40, 80, 170)}, {}),
    ("brickwall", "darker grout", {"define:mortar": (145, 134, 110)}, {}),
    ("brickwall", "make the bricks white", {"define:brick": (236, 236, 232)}, {}),
    ("weathered", "darker mortar", {"layer:1.basecolor": (127, 121, 107)}, {}),
    ("quick", "green bricks", {"layer:2.basecolor": (60, 130, 60)}, {}),
    ("rustymoss", "lighter mortar", {"define:mortar": (212, 209, 200)}, {}),
    # roughness
    ("square", "higher roughness", {"define:rough": 0.52, "layer:1.roughness": 0.94}, {}),
    ("square", "make it glossier", {"define:rough": 0.1, "layer:1.roughness": 0.45}, {}),
    ("brickwall", "rougher", {"define:rough": 0.928, "layer:1.roughness": 0.97}, {}),
    ("quick", "matte", {"layer:1.roughness": 0.8, "layer:2.roughness": 0.8}, {}),
    ("quick", "shinier", {"layer:1.roughness": 0.175, "layer:2.roughness": 0.175}, {}),
    (
        "weathered",
        "make it smoother",
        {"layer:1.roughness": 0.57, "layer:2.roughness.base": 0.42},
        {},
    ),
    # scale
    (
        "black",
        "bigger tiles",
        {"define:tileMask.Bricks.brick_width": 0.75, "define:tileMask.Bricks.brick_height": 0.75},
        {},
    ),
    ("square", "smaller tiles", {"define:tile.Bricks.brick_height": 0.666667}, {}),
    ("weathered", "denser", {"define:tone.fBm.base_freq": 3.75}, {}),
    ("weathered", "sparser", {"define:tone.fBm.base_freq": 1.66667}, {}),
    # overlay amounts
    ("rustymoss", "more rust", {"define:cover": 0.75}, {}),
    ("rustymoss", "less rust", {"define:cover": 0.25}, {}),
    ("rustymoss", "less moss", {"define:cover2": 0.25}, {}),
    ("worndirty", "more wear", {"define:cover": 0.75}, {}),
    ("worndirty", "less dirt", {"define:cover2": 0.25}, {}),
    # View
    ("black", "make it tileable", {}, {"tileable": True}),
    ("weathered", "seamless please", {}, {"tileable": True}),
    ("black", "1 m wide", {}, {"unit_m": 0.5}),
    ("square", "make it 30 cm across", {}, {"unit_m": 0.1}),
    ("brickwall", "3 ft wide", {}, {"unit_m": 0.2286}),
]

REFUSED: list[tuple[str, str, str]] = [
    ("black", "make it fluffy", "no offline rule"),
    ("black", "more rust", "no rust amount"),
    ("square", "make it tileable", "tileable already"),
    ("square", "darker grout", "no colour parameter named like 'grout'"),
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
    assert len({p for p, *_ in TABLE}) >= 5


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


def test_physical_size_changes_no_map() -> None:
    result = edit_offline(program("black"), "2 m wide", size=32)
    assert result.report.locality.changed == ()
    assert "unit_m=1" in result.program
