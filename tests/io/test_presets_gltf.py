"""glTF preset: structure, and the Khronos glTF validator (npm ``gltf-validator``, installed
into ``.tools/`` by ``make tools``, which ``make test`` runs) reports 0 errors for the .gltf and
the .glb. Without node or the validator the validator test skips and says why."""

from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VALIDATOR_DIR = Path(os.environ.get("GLTF_VALIDATOR_DIR", ROOT / ".tools" / "node_modules"))
NODE = shutil.which("node")
HAS_VALIDATOR = NODE is not None and (VALIDATOR_DIR / "gltf-validator" / "index.js").is_file()
SKIP_REASON = (
    "needs node and the Khronos glTF validator: run `make tools` "
    "(npm install --prefix .tools gltf-validator)"
)


def _validate(*files: Path) -> list[dict]:
    res = subprocess.run(
        [NODE or "node", str(Path(__file__).with_name("gltf_validate.js")), *map(str, files)],
        capture_output=True,
        text=True,
        timeout=120,
        env={**os.environ, "GLTF_VALIDATOR_DIR": str(VALIDATOR_DIR)},
    )
    assert res.returncode == 0, res.stderr
    return [json.loads(line) for line in res.stdout.splitlines()]


@pytest.mark.skipif(not HAS_VALIDATOR, reason=SKIP_REASON)
@pytest.mark.parametrize("program", ["full", "plain", "flat"])
def test_khronos_validator_reports_no_errors(render_presets, program: str) -> None:
    _, result = render_presets(program, presets=["gltf"], unit_m=0.5)
    folder = result.out_dir / "gltf"
    reports = _validate(folder / f"{program}.gltf", folder / f"{program}.glb")
    for report in reports:
        assert report["errors"] == 0, report["messages"]
        assert report["warnings"] == 0, report["messages"]


def test_material_uses_orm_normal_and_extensions_only_where_used(render_presets) -> None:
    _, full = render_presets("full", presets=["gltf"], unit_m=0.5)
    doc = json.loads((full.out_dir / "gltf" / "full.gltf").read_text())
    material = doc["materials"][0]
    pbr = material["pbrMetallicRoughness"]
    images = [image["uri"] for image in doc["images"]]
    orm = doc["textures"][pbr["metallicRoughnessTexture"]["index"]]["source"]
    assert images[orm] == "full_orm.png"
    assert material["occlusionTexture"]["index"] == pbr["metallicRoughnessTexture"]["index"]
    assert images[doc["textures"][material["normalTexture"]["index"]]["source"]] == (
        "full_normal_gl.png"
    )
    assert material["alphaMode"] == "BLEND"
    assert set(doc["extensionsUsed"]) == {
        "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_transmission",
        "KHR_materials_ior", "KHR_materials_anisotropy", "KHR_materials_emissive_strength",
    }  # fmt: skip
    assert material["extras"]["matloom"]["physical_size"]["width_m"] == pytest.approx(1.0)
    _, plain = render_presets("plain", presets=["gltf"])
    doc = json.loads((plain.out_dir / "gltf" / "plain.gltf").read_text())
    assert "extensionsUsed" not in doc
    assert doc["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"]
    _, flat = render_presets("flat", presets=["gltf"])
    doc = json.loads((flat.out_dir / "gltf" / "flat.gltf").read_text())
    pbr = doc["materials"][0]["pbrMetallicRoughness"]
    assert pbr["roughnessFactor"] == 0.25 and pbr["metallicFactor"] == 1.0
    assert "images" not in doc  # every map is constant: factors only


def test_glb_embeds_the_same_pngs(render_presets) -> None:
    _, result = render_presets("plain", presets=["gltf"])
    folder = result.out_dir / "gltf"
    data = (folder / "plain.glb").read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    json_len = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20 : 20 + json_len])
    blob = data[20 + json_len + 8 :]
    for image in doc["images"]:
        view = doc["bufferViews"][image["bufferView"]]
        png = blob[view["byteOffset"] : view["byteOffset"] + view["byteLength"]]
        assert png == (folder / image["name"]).read_bytes()
