"""Material names that are ordinary file names (``01_bricks``: a file's stem; ``-lead``) give
valid USD prim names and MaterialX element names; the files keep the name as given. (The real
consumers read the same documents in test_presets_interop.py.)"""

from __future__ import annotations

import re
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

import matloom
from matloom.io.presets.common import identifier
from matloom.runtime.export import export_maps

IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
PROGRAM = (
    "View(0, 0, 2, 2)\nMaterial(\n  Layer(1).basecolor(200 * X(), 120, 80).roughness(X() * 0.5)\n"
    "    .height(Y() * 0.1).anisotropy(0.5)\n)"
)
NAMES = ["01_bricks", "-lead", "9", "brick-wall_2"]


def export(tmp_path: Path, name: str, presets: list[str]) -> Path:
    maps = matloom.evaluate(PROGRAM, 16, 16)
    return export_maps(maps, tmp_path / "out", presets=presets, name=name, unit_m=0.5).out_dir


@pytest.mark.parametrize(
    ("name", "expected"),
    [("01_bricks", "m01_bricks"), ("-lead", "_lead"), ("bricks", "bricks"), ("a.b c", "a_b_c")],
)
def test_identifier(name: str, expected: str) -> None:
    assert identifier(name) == expected and IDENTIFIER.match(expected)


@pytest.mark.parametrize("name", NAMES)
def test_usd_prim_names_are_identifiers(tmp_path: Path, name: str) -> None:
    text = (export(tmp_path, name, ["usd"]) / "usd" / f"{name}.usda").read_text()
    prims = re.findall(r'^\s*def \w+ "([^"]*)"', text, re.MULTILINE)
    (default,) = re.findall(r'defaultPrim = "([^"]*)"', text)
    paths = re.findall(r"<(/[^>]*)>", text)
    assert prims and paths
    for prim in [*prims, default]:
        assert IDENTIFIER.match(prim), prim
    for path in paths:
        prim_path = path.split(".")[0]
        assert all(IDENTIFIER.match(part) for part in prim_path.strip("/").split("/")), path
    assert f"@./{name}_basecolor.png@" in text  # the files keep the user's name


@pytest.mark.parametrize("name", NAMES)
def test_materialx_element_names_are_identifiers(tmp_path: Path, name: str) -> None:
    folder = export(tmp_path, name, ["mtlx"]) / "mtlx"
    root = ET.parse(folder / f"{name}.mtlx").getroot()
    names = [e.get("name") for e in root.iter() if e.get("name") is not None]
    nodenames = [e.get("nodename") for e in root.iter() if e.get("nodename") is not None]
    assert names and nodenames
    for element_name in names + nodenames:
        assert IDENTIFIER.match(element_name), element_name
    files = [e.get("value") for e in root.iter("input") if e.get("type") == "filename"]
    assert f"{name}_basecolor.png" in files
