"""``anisotropy_angle`` is the brushing direction; glTF's anisotropy direction and OpenPBR's
tangent are the direction the highlight stretches, across it (angle + 90 degrees). Blender reads
both in tests/blender/test_blender_brushing.py; the lit preview in
tests/render/test_lit_brushing.py."""

from __future__ import annotations

import json
import math
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import pytest

import matloom
from matloom.io import png
from matloom.runtime.export import export_maps


def _export(tmp_path: Path, angle: str, preset: str) -> Path:
    program = f"Material(Layer(1).metallic(1).anisotropy(0.8).anisotropy_angle({angle}))"
    maps = matloom.evaluate(program, 8, 8)
    return export_maps(maps, tmp_path / "out", presets=[preset], name="m").out_dir / preset


@pytest.mark.parametrize(("brush", "stretch"), [(0, 90), (30, 120), (90, 0), (135, 45)])
def test_gltf_rotation_is_across_the_brushing(tmp_path: Path, brush: int, stretch: int) -> None:
    doc = json.loads((_export(tmp_path, str(brush), "gltf") / "m.gltf").read_text())
    aniso = doc["materials"][0]["extensions"]["KHR_materials_anisotropy"]
    assert aniso["anisotropyRotation"] == pytest.approx(math.radians(stretch))


def test_gltf_direction_texture_is_across_the_brushing(tmp_path: Path) -> None:
    folder = _export(tmp_path, "X() * 0.001", "gltf")  # brushing ~0: a texture, not a factor
    rgb = png.read_png(folder / "m_anisotropy.png").astype(np.float64) / 255 * 2 - 1
    np.testing.assert_allclose(rgb[..., 0], 0.0, atol=0.01)  # direction (0, 1): up, across x
    np.testing.assert_allclose(rgb[..., 1], 1.0, atol=0.01)


def _tangent_weights(root: ET.Element) -> tuple[str, str]:
    """The factors of the UV tangent and bitangent in the shader's geometry_tangent."""
    nodes = {e.get("name"): e for e in root}
    shader = next(e for e in root if e.tag == "open_pbr_surface")
    (link,) = [i for i in shader if i.get("name") == "geometry_tangent"]
    total = nodes[nodes[link.get("nodename")].find("input").get("nodename")]
    weights = []
    for term in total:
        product = {i.get("name"): i for i in nodes[term.get("nodename")]}
        assert nodes[product["in1"].get("nodename")].tag in ("tangent", "bitangent")
        weights.append(product["in2"].get("value") or product["in2"].get("nodename"))
    return weights[0], weights[1]


@pytest.mark.parametrize(("brush", "stretch"), [(0, 90), (30, 120), (90, 180)])
def test_materialx_tangent_is_across_the_brushing(tmp_path: Path, brush: int, stretch: int) -> None:
    root = ET.parse(_export(tmp_path, str(brush), "mtlx") / "m.mtlx").getroot()
    along_t, along_b = _tangent_weights(root)
    assert float(along_t) == pytest.approx(math.cos(math.radians(stretch)), abs=1e-7)
    assert float(along_b) == pytest.approx(math.sin(math.radians(stretch)), abs=1e-7)


def test_materialx_angle_map_is_turned_a_quarter(tmp_path: Path) -> None:
    folder = _export(tmp_path, "X() * 90", "mtlx")
    root = ET.parse(folder / "m.mtlx").getroot()
    nodes = {e.get("name"): e for e in root}
    along_t, along_b = _tangent_weights(root)
    assert (nodes[along_t].tag, nodes[along_b].tag) == ("cos", "sin")
    turned = nodes[nodes[along_t].find("input").get("nodename")]
    inputs = {i.get("name"): i for i in turned}
    assert turned.tag == "add" and float(inputs["in2"].get("value")) == pytest.approx(math.pi / 2)
    degrees = png.read_png(folder / "m_anisotropy_angle.png").astype(np.float64) / 65535 * 180
    x = (np.arange(8) + 0.5) / 8  # the default View: X from 0 to 1 across the columns
    np.testing.assert_allclose(degrees[0], x * 90, atol=0.01)
