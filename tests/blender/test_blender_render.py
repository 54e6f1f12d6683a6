"""Real Cycles renders through `matloom blender` (64 px, 4 samples); skipped without Blender.

Blender is found like the command finds it: $MATLOOM_BLENDER, $MATLOOM_BLENDER_PYTHON (a Python
with bpy), `blender` on PATH or the project's .venv-blender (`make blender-venv`).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from matloom.blender import render_layouts
from matloom.blender.job import RenderOptions, build_job, load_source
from matloom.blender.layouts import LAYOUTS
from matloom.blender.runner import Blender
from matloom.io.png import read_png, written_by_matloom

pytestmark = pytest.mark.blender

ROOT = Path(__file__).resolve().parents[2]
PLANK = ROOT / "docs" / "examples" / "01_plank_floor.mat"
RELIEF = """View(0, 0, 2, 2)
Define(cells, Bricks(brick_width=0.5, brick_height=0.5, mortar=0.05, feather=0.05))
Material(
  Layer(1).basecolor(180, 180, 180).roughness(0.5),
  Layer(cells).basecolor(200, 120, 80).roughness(0.4).height(0.25)
)
"""
CUTOUT = """View(0, 0, 2, 2)
Define(cells, Bricks(brick_width=0.5, brick_height=0.5, mortar=0.12, feather=0.01))
Material(
  Layer(cells).basecolor(40, 160, 220).roughness(0.5)
)
"""


def _run(
    blender: Blender, *args: str, tmpdir: Path | None = None
) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    if tmpdir is not None:
        env["TMPDIR"] = str(tmpdir)
    flag = "MATLOOM_BLENDER_PYTHON" if blender.kind == "bpy" else "MATLOOM_BLENDER"
    env[flag] = blender.path
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "blender", *args, "--size", "64", "--samples", "4"],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert res.returncode == 0, res.stderr
    assert "Traceback" not in res.stderr
    return res


def _image(path: Path) -> np.ndarray:
    return read_png(path).astype(np.float64) / 255.0


@pytest.fixture(scope="module")
def plank(blender: Blender, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("plank")
    _run(blender, str(PLANK), "--layout", "both", "-o", str(out), "--save", "scene.blend")
    return out


def test_flat_and_staged_are_non_trivial_and_differ(plank: Path) -> None:
    flat, staged = _image(plank / "flat.png"), _image(plank / "staged.png")
    assert flat.shape == staged.shape == (64, 64, 4)
    for image in (flat, staged):
        assert image[..., :3].std() > 0.02  # not a flat colour
        assert image[..., :3].mean() > 0.05  # not black
    assert flat[..., 3].min() > 0.9  # the swatch fills the frame
    assert staged[..., 3].min() == 1.0  # the staged scene has a background
    assert np.abs(flat - staged).mean() > 0.05


def test_displacement_changes_the_render(blender: Blender, tmp_path: Path) -> None:
    program = tmp_path / "relief.mat"
    program.write_text(RELIEF)
    images = {}
    for name, mode in (("true", "true"), ("again", "true"), ("off", "off")):
        out = tmp_path / name
        _run(blender, str(program), "--layout", "staged", "-o", str(out), "--displacement", mode)
        images[name] = _image(out / "staged.png")
    moved = np.abs(images["true"] - images["off"]).mean()
    noise = np.abs(images["true"] - images["again"]).mean()
    assert moved > 0.01 and moved > 3 * noise


def test_alpha_cut_out(blender: Blender, tmp_path: Path) -> None:
    program = tmp_path / "cutout.mat"
    program.write_text(CUTOUT)
    _run(blender, str(program), "-o", str(tmp_path / "out"))
    alpha = _image(tmp_path / "out" / "flat.png")[..., 3]
    assert (alpha < 0.1).mean() > 0.05  # the mortar is cut out: transparent background
    assert (alpha > 0.9).mean() > 0.3  # the tiles stay


def _readback(blender: Blender, blend: Path) -> dict[str, Any]:
    script = Path(__file__).with_name("readback.py")
    if blender.kind == "bpy":
        cmd = [blender.path, str(script), str(blend)]
    else:
        cmd = [blender.path, "-b", "--factory-startup", "--python", str(script), "--", str(blend)]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    lines = [line for line in res.stdout.splitlines() if line.startswith("READBACK ")]
    assert lines, res.stdout[-2000:] + res.stderr[-2000:]
    return json.loads(lines[-1].removeprefix("READBACK "))


def test_saved_blend_has_the_material_wired(blender: Blender, plank: Path) -> None:
    data = _readback(blender, plank / "scene.blend")
    mat = data["materials"]["01_plank_floor"]
    links = {tuple(link) for link in mat["links"]}
    bsdf = "Principled BSDF"
    expected = {
        ("basecolor map", "Color", "Base x AO", "A"),
        ("ao map", "Color", "Base x AO", "B"),
        ("Base x AO", "Result", bsdf, "Base Color"),
        ("basecolor map", "Alpha", bsdf, "Alpha"),
        ("roughness map", "Color", bsdf, "Roughness"),
        ("metallic map", "Color", bsdf, "Metallic"),
        ("coat map", "Color", bsdf, "Coat Weight"),
        ("ior map", "Color", bsdf, "IOR"),
        ("normal map", "Color", "Normal Map (OpenGL)", "Color"),
        ("Normal Map (OpenGL)", "Normal", "Bump", "Normal"),
        ("Bump", "Normal", bsdf, "Normal"),
        ("height map", "Color", "Displacement", "Height"),
        ("Displacement", "Displacement", "Material Output", "Displacement"),
        ("anisotropy_angle map", "Color", "Angle to rotation", "Value"),
        ("Angle to rotation", "Value", bsdf, "Anisotropic Rotation"),
        ("UV Tangent", "Tangent", bsdf, "Tangent"),
        (bsdf, "BSDF", "Material Output", "Surface"),
    }
    assert expected <= links, expected - links
    assert mat["frames"] == ["Maps", "Relief", "Surface"]
    assert mat["displacement_method"] == "BOTH"
    images = data["images"]
    assert images["basecolor.png"]["colour_space"] == "sRGB"
    assert images["roughness.png"]["colour_space"] == "Non-Color"
    assert images["normal_gl.png"]["colour_space"] == "Non-Color"
    assert images["emissive.exr"]["colour_space"] == "Linear Rec.709"
    assert all(image["packed"] for image in images.values())
    # cameras and lights equal the layout table (with the camera placed for view 0)
    source = load_source(str(PLANK), size=16)
    try:
        job = build_job(source, RenderOptions(layouts=("flat", "staged")), plank)
    finally:
        source.cleanup()
    for render in job["renders"]:
        scene = data["scenes"][render["layout"]]
        assert scene["camera"]["location"] == pytest.approx(render["camera"]["location"], abs=1e-5)
        assert scene["camera"]["lens"] == pytest.approx(50)
        assert scene["samples"] == 4
        assert scene["view_transform"] == "AgX"
        assert scene["film_transparent"] == LAYOUTS[render["layout"]].film_transparent
    lights = data["scenes"]["staged"]["lights"]
    for spec in LAYOUTS["staged"].lights:
        light = lights[f"{spec.name} light"]
        assert light["location"] == pytest.approx(list(spec.location))
        assert (light["energy"], light["shape"]) == (pytest.approx(spec.power_w), spec.shape)
        assert light["size"] == pytest.approx(spec.size)
    assert data["scenes"]["flat"]["lights"] == {}


def test_material_only_blend_is_an_asset(blender: Blender, tmp_path: Path) -> None:
    _run(blender, str(PLANK), "-o", str(tmp_path), "--save-material-only")
    data = _readback(blender, tmp_path / "material.blend")
    assert data["materials"]["01_plank_floor"]["asset"]
    assert all(image["packed"] for image in data["images"].values())


def test_single_png(
    blender: Blender, tmp_path: Path, tmp_path_factory: pytest.TempPathFactory
) -> None:
    """The issue's form: `matloom blender PROGRAM --layout staged -o out.png`. Nothing is left
    in $TMPDIR (Blender's own `blender_*` folder goes inside MatLoom's and goes with it)."""
    target = tmp_path / "out.png"
    tmpdir = tmp_path_factory.mktemp("tmpdir")
    res = _run(blender, str(PLANK), "--layout", "staged", "-o", str(target), tmpdir=tmpdir)
    assert res.stdout.split() == [str(target)]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.png"]
    assert list(tmpdir.iterdir()) == []
    assert written_by_matloom(target)
    image = _image(target)
    assert image.shape == (64, 64, 4) and image[..., :3].std() > 0.02


def _export(tmp_path: Path, name: str, *presets: str) -> Path:
    out = tmp_path / name
    args = [arg for preset in presets for arg in ("--preset", preset)]
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "render", str(PLANK), "-o", str(out), "--size", "64"]
        + args,
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert res.returncode == 0, res.stderr
    return out


def test_saved_blend_splits_a_packed_orm(blender: Blender, tmp_path: Path) -> None:
    """An export with an ORM (glTF) or a mask map (Unity): the .blend reads it once and splits it
    with a Separate Color node; the render equals the one from the separate maps."""
    images = {}
    graphs = {}
    for name, presets in (("plain", ()), ("gltf", ("gltf",)), ("unity", ("unity",))):
        folder = _export(tmp_path, name, *presets)
        out = tmp_path / f"{name}-out"
        _run(blender, str(folder), "-o", str(out), "--save", "scene.blend")
        images[name] = _image(out / "flat.png")
        graphs[name] = _readback(blender, out / "scene.blend")
    bsdf = "Principled BSDF"
    gltf = graphs["gltf"]["materials"]["gltf"]
    links = {tuple(link) for link in gltf["links"]}
    assert {
        ("ORM map", "Color", "Split ORM", "Color"),
        ("Split ORM", "Red", "Base x AO", "B"),
        ("Split ORM", "Green", bsdf, "Roughness"),
        ("Split ORM", "Blue", bsdf, "Metallic"),
    } <= links
    assert not {link for link in links if link[0] in ("ao map", "roughness map", "metallic map")}
    assert gltf["frames"] == ["Maps", "ORM split", "Relief", "Surface"]
    names = set(graphs["gltf"]["images"])
    assert "01_plank_floor_orm.png" in names and not names & {
        "ao.png",
        "roughness.png",
        "metallic.png",
    }
    assert graphs["gltf"]["images"]["01_plank_floor_orm.png"]["colour_space"] == "Non-Color"
    unity = {tuple(link) for link in graphs["unity"]["materials"]["unity"]["links"]}
    assert {
        ("Mask map", "Color", "Split mask map", "Color"),
        ("Split mask map", "Red", bsdf, "Metallic"),
        ("Split mask map", "Green", "Base x AO", "B"),
        ("Mask map", "Alpha", "roughness = 1 - A", "Value"),
        ("roughness = 1 - A", "Value", bsdf, "Roughness"),
    } <= unity
    # the same material: the packed channels carry the same 8-bit values as the maps
    assert np.abs(images["gltf"] - images["plain"]).mean() < 0.005
    assert np.abs(images["unity"] - images["plain"]).mean() < 0.005


def test_render_layouts_api(blender: Blender, tmp_path: Path) -> None:
    folder = _export(tmp_path, "maps")
    lines: list[str] = []
    paths = render_layouts(
        folder,
        ["staged"],
        tmp_path / "renders",
        size=64,
        samples=4,
        blender=blender.path,
        progress=lines.append,
    )
    assert paths == [tmp_path / "renders" / "staged.png"]
    assert _image(paths[0]).shape == (64, 64, 4) and written_by_matloom(paths[0])
    assert lines[-1].startswith("staged view 0 (1/1) in ")
