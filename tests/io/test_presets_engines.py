"""Bit depth, EXR, normal conventions, packed textures and engine presets (default suite)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.colour import linear_to_srgb
from matloom.io import exr, png
from matloom.io.presets import PRESETS
from matloom.runtime.export import export_maps


def _q8(values: np.ndarray) -> np.ndarray:
    return png.quantize_unit8(values).astype(int)


def test_bits16_applies_to_every_png_map(render_presets) -> None:
    maps, result = render_presets("full", bits=16)
    out = result.out_dir
    for entry in result.manifest["maps"]:
        if entry["file"].endswith(".png"):
            assert png.read_png(out / entry["file"]).dtype == np.uint16, entry["file"]
            assert entry["encoding"].startswith("png16"), entry
    rough = png.read_png(out / "roughness.png")
    np.testing.assert_array_equal(rough, png.quantize_unit16(maps.roughness))
    normal = png.read_png(out / "normal_gl.png")
    assert normal.shape == (64, 64, 3)
    np.testing.assert_allclose(normal / 65535, maps.normal * 0.5 + 0.5, atol=1 / 65535)
    base = png.read_png(out / "basecolor.png")
    assert base.shape == (64, 64, 4)
    srgb = linear_to_srgb(maps.basecolor_linear)
    np.testing.assert_allclose(base[..., :3] / 65535, srgb, atol=1 / 65535)
    angle = {m["name"]: m for m in result.manifest["maps"]}["anisotropy_angle"]
    assert "/ 65535" in angle["decode"]


@pytest.mark.parametrize("precision", ["half", "float"])
def test_exr_format_writes_every_map_as_exr(render_presets, precision: str) -> None:
    maps, result = render_presets("full", float_format="exr", exr_precision=precision)
    out = result.out_dir
    files = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert all(f.endswith(".exr") for f in files if f != "material.json"), files
    assert "normal_gl.exr" in files and "basecolor.exr" in files
    dtype = np.float16 if precision == "half" else np.float32
    rough = exr.read_exr(out / "roughness.exr")
    np.testing.assert_array_equal(rough, maps.roughness.astype(dtype).astype(np.float32))
    base = exr.read_exr(out / "basecolor.exr")
    assert base.shape == (64, 64, 4)
    np.testing.assert_array_equal(base[..., 3], maps.alpha.astype(dtype).astype(np.float32))
    entry = {m["name"]: m for m in result.manifest["maps"]}["roughness"]
    assert entry["encoding"] == ("exr-half" if precision == "half" else "exr-float32")


def test_normal_dx_green_is_one_minus_gl(render_presets) -> None:
    _, result = render_presets("plain", normals=("gl", "dx"))
    gl = png.read_png(result.out_dir / "normal_gl.png").astype(int)
    dx = png.read_png(result.out_dir / "normal_dx.png").astype(int)
    np.testing.assert_array_equal(dx[..., 1], 255 - gl[..., 1])
    np.testing.assert_array_equal(dx[..., [0, 2]], gl[..., [0, 2]])
    entry = {m["name"]: m for m in result.manifest["maps"]}["normal"]
    assert entry["files"] == {"gl": "normal_gl.png", "dx": "normal_dx.png"}


def test_constant_maps_as_values(render_presets) -> None:
    _, result = render_presets("plain", constants=True)
    by_name = {m["name"]: m for m in result.manifest["maps"]}
    assert by_name["metallic"] == {**by_name["metallic"], "file": None, "constant": 0.0}
    assert not (result.out_dir / "metallic.png").exists()
    assert by_name["roughness"]["file"] == "roughness.png"
    assert (result.out_dir / "roughness.png").exists()
    assert set(result.manifest["files"]) == {
        p.name for p in result.out_dir.iterdir() if p.name[0] != "." and p.suffix != ".json"
    }


def test_unreal_preset(render_presets) -> None:
    maps, result = render_presets("full", presets=["unreal"], unit_m=0.5)
    folder = result.out_dir / "unreal"
    names = sorted(p.name for p in folder.iterdir())
    assert names == ["T_full_BC.png", "T_full_E.png", "T_full_H.png", "T_full_N_dx.png",
                     "T_full_ORM.png"]  # fmt: skip
    orm = png.read_png(folder / "T_full_ORM.png").astype(int)
    np.testing.assert_array_equal(orm[..., 0], _q8(maps.ao))
    np.testing.assert_array_equal(orm[..., 1], _q8(maps.roughness))
    np.testing.assert_array_equal(orm[..., 2], _q8(maps.metallic))
    normal = png.read_png(folder / "T_full_N_dx.png").astype(int)
    gl = _q8(maps.normal * 0.5 + 0.5)
    np.testing.assert_array_equal(normal[..., 1], 255 - gl[..., 1])  # DirectX
    height = png.read_png(folder / "T_full_H.png")
    assert height.dtype == np.uint16 and height.max() == 65535 and height.min() == 0
    entry = result.manifest["presets"]["unreal"]
    h = entry["files"]["height"]
    assert h["displacement_scale_m"] == pytest.approx((h["max"] - h["min"]) * 0.5)
    assert entry["physical_size"]["width_m"] == pytest.approx(1.0)
    assert "unreal/T_full_ORM.png" in result.manifest["files"]


@pytest.mark.parametrize("preset", sorted(PRESETS))
def test_every_preset_names_its_normal_convention(render_presets, preset: str) -> None:
    """A normal map's file name carries its convention: ``normal_gl`` / ``normal_dx``, or
    Unreal's ``_N`` suffix followed by ``_dx``."""
    _, result = render_presets("full", presets=[preset])
    normal = result.manifest["presets"][preset]["files"].get("normal")
    if normal is None:  # a preset without a normal texture of its own
        return
    stem = Path(normal["file"]).stem
    tag = "dx" if normal["convention"].startswith("DirectX") else "gl"
    assert stem.endswith((f"normal_{tag}", f"_N_{tag}")), normal


def test_unity_mask_map(render_presets) -> None:
    maps, result = render_presets("full", presets=["unity"])
    folder = result.out_dir / "unity"
    mask = png.read_png(folder / "full_maskmap.png").astype(int)
    assert mask.shape == (64, 64, 4)
    np.testing.assert_array_equal(mask[..., 0], _q8(maps.metallic))
    np.testing.assert_array_equal(mask[..., 1], _q8(maps.ao))
    assert np.all(mask[..., 2] == 255)  # detail mask
    np.testing.assert_array_equal(mask[..., 3], _q8(1 - maps.roughness))
    assert (folder / "full_normal_gl.png").exists()


def test_godot_orm_and_constants(render_presets) -> None:
    maps, result = render_presets("plain", presets=["godot"])
    folder = result.out_dir / "godot"
    orm = png.read_png(folder / "plain_orm.png").astype(int)
    np.testing.assert_array_equal(orm[..., 1], _q8(maps.roughness))
    assert np.all(orm[..., 2] == 0)
    _, flat = render_presets("flat", presets=list(PRESETS))
    for preset, entry in flat.manifest["presets"].items():
        values = entry["constant_values"]
        assert values.get("roughness", 0.25) == 0.25, preset
        pngs = [f for f in entry["files"].values() if f["file"].endswith(".png")]
        assert pngs == [], (preset, pngs)  # constant maps are values, not files


def test_physical_size_in_manifest(render_presets) -> None:
    _, result = render_presets("plain", unit_m=0.02)
    size = result.manifest["physical_size"]
    assert size["width_m"] == pytest.approx(0.2) and size["height_scale_m"] == 0.02
    assert size["texels_per_m"] == pytest.approx(320)
    _, unknown = render_presets("flat")
    assert unknown.manifest["physical_size"] is None


def test_bad_arguments_write_nothing(tmp_path: Path, preset_maps) -> None:
    maps = preset_maps("flat")
    for kwargs in ({"presets": ["bogus"]}, {"unit_m": 0.0}, {"bits": 12},
                   {"exr_precision": "double"}, {"normals": ("yx",)}):  # fmt: skip
        with pytest.raises(ValueError):
            export_maps(maps, tmp_path / "o", **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_preset_never_overwrites_a_foreign_file(tmp_path: Path, preset_maps) -> None:
    out = tmp_path / "o"
    (out / "gltf").mkdir(parents=True)
    (out / "gltf" / "plain.gltf").write_text("mine")
    from matloom.io.outdir import OutputError

    with pytest.raises(OutputError, match="plain.gltf"):
        export_maps(preset_maps("plain"), out, presets=["gltf"], name="plain")
    assert (out / "gltf" / "plain.gltf").read_text() == "mine"
    assert not (out / "material.json").exists()


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args], capture_output=True, text=True, timeout=120
    )


def test_cli_presets_bits_unit_and_square_texels(tmp_path: Path) -> None:
    src = tmp_path / "bricks.mat"
    src.write_text("View(0, 0, 4, 4)\nMaterial(Layer(1).roughness(0.5).height(fBm(seed=1)))\n")
    out = tmp_path / "out"
    res = _cli("render", str(src), "-o", str(out), "--width", "64", "--height", "32",
               "--preset", "gltf", "--preset", "unreal", "--bits", "16", "--unit-m", "0.25",
               "--no-preview")  # fmt: skip
    assert res.returncode == 0, res.stderr
    manifest = json.loads((out / "material.json").read_text())
    assert manifest["square_texels"] is True
    assert manifest["view"] == {"x1": -2.0, "y1": 0.0, "x2": 6.0, "y2": 4.0}  # widened
    assert manifest["view_adjusted"]["program_view"] == [0, 0, 4, 4]
    assert (out / "gltf" / "bricks.glb").exists()
    assert (out / "unreal" / "T_bricks_N_dx.png").exists()
    assert manifest["physical_size"]["width_m"] == pytest.approx(2.0)
    assert png.read_png(out / "roughness.png").dtype == np.uint16


@pytest.mark.parametrize(
    "args, words",
    [
        (["--unit-m", "0"], "--unit-m"),
        (["--unit-m", "nan"], "--unit-m"),
        (["--preset", "blender"], "--preset"),
        (["--bits", "12"], "--bits"),
        (["--name", "///"], "--name"),
    ],
)
def test_cli_bad_options_are_one_line(tmp_path: Path, args: list[str], words: str) -> None:
    src = tmp_path / "p.mat"
    src.write_text("Material(Layer(1))\n")
    res = _cli("render", str(src), "-o", str(tmp_path / "o"), "--size", "8", *args)
    assert res.returncode == 2
    assert "Traceback" not in res.stderr and words in res.stderr
