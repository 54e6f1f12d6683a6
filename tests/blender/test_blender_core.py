"""`matloom blender` without Blender: the layout table, jobs (with packed ORM / mask maps) and
the worker script's own rules. Failures with fake Blender executables are in
test_blender_failures.py, outputs in test_blender_outputs.py, real renders in
test_blender_render.py.
"""

from __future__ import annotations

import ast
import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from matloom.blender import layouts
from matloom.blender.job import (
    BlenderJobError,
    RenderOptions,
    build_job,
    load_source,
    planned_files,
    read_manifest,
)
from matloom.blender.runner import WORKER

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = ROOT / "docs" / "examples" / "01_plank_floor.mat"


# ------------------------------------------------------------------ the layout table


def test_flat_layout_matches_the_reference() -> None:
    flat = layouts.FLAT
    assert flat.samples == 64
    assert flat.world == "hdri" and flat.world_strength == 0.5 and flat.film_transparent
    assert flat.hdri is not None and flat.hdri.endswith("city.exr")
    assert flat.hdri.startswith("studiolights/")  # Blender's bundled file, not a missing one
    assert flat.camera.lens_mm == 50 and flat.camera.clip_start == 0.01
    assert flat.camera.rotation_deg == (0, 0, 0) and flat.camera.fit_ratio == 1.0
    assert flat.resolution == 512 and flat.n_views == 4
    assert flat.world_turn_deg == (0, -90, -180, -270)
    assert flat.lights == () and flat.props == ()


def test_staged_layout_matches_the_reference() -> None:
    staged = layouts.STAGED
    assert staged.samples == 160
    assert staged.world == "colour" and staged.world_colour == (210, 211, 214)
    assert not staged.film_transparent
    assert staged.panel_rotation_deg == (90, 0, 0) and staged.panel_location == (0, 0, 1.02)
    cam = staged.camera
    assert cam.rotation_deg == (72, 0, 26) and cam.target == (0, 0, 1.02)
    assert cam.radius == pytest.approx(math.sqrt(2) * 0.9) and cam.fit_ratio == 0
    assert staged.view_azimuths_deg == (0, -75, -45, -15, 15, 45)
    key, top = staged.lights
    assert (key.location, key.power_w, key.size, key.shadow) == ((-3, -3, 4), 900, 2.6, True)
    assert (top.location, top.power_w, top.size, top.shadow) == ((0, 0, 4.2), 220, 3.6, False)
    assert all(light.shape == "SQUARE" and light.spread_deg == 180 for light in staged.lights)
    props = {p.name: p for p in staged.props}
    assert props["back_sphere"].location == (1.5, 1.2, 0.8)
    assert props["back_sphere"].size == {"radius": 0.8}
    assert props["back_sphere"].colour == (205, 120, 55) and props["back_sphere"].roughness == 0.45
    cube = props["back_cube"]
    assert (cube.location, cube.rotation_deg, cube.size) == (
        (-1.9, 1.2, 0.65),
        (0, 0, 30),
        {"size": 1.3},
    )
    assert cube.colour == (70, 110, 200) and cube.roughness == 0.55
    assert props["front_sphere"].location == (-1.9, -2.6, 0.7)
    assert props["front_cone"].size == {"radius": 0.8, "depth": 1.5, "vertices": 3}
    torus = props["front_torus"]
    assert torus.location == (-2.8, -2.0, 0.9) and torus.rotation_deg == (80, 0, 20)
    assert torus.size == {"major_radius": 0.7, "minor_radius": 0.24}
    for name in ("front_sphere", "front_cone", "front_torus"):
        assert props[name].roughness == 0.4
    room = [p for p in staged.props if p.kind == "plane"]
    assert len(room) == 6 and all(p.roughness == 0.85 for p in room)
    assert props["ceiling"].location[2] == 4.5 and props["ceiling"].colour == (221, 222, 226)
    assert props["wall_back"].scale == (5.5, 2.25, 1.0)


def test_cameras_are_placed_as_the_reference_frames_them() -> None:
    half_fov = math.atan(18 / 50)
    flat = layouts.camera_for_view(layouts.FLAT, 0)
    assert flat["location"] == pytest.approx([0, 0, 1 / math.tan(half_fov)])
    staged = layouts.camera_for_view(layouts.STAGED, 0)
    distance = math.sqrt(2) * 0.9 / math.sin(half_fov)
    assert staged["distance"] == pytest.approx(distance)
    x, y, z = staged["location"]
    # 18 degrees down from the horizontal, swung 26 degrees from -Y towards +X
    assert (z - 1.02) / distance == pytest.approx(math.sin(math.radians(18)))
    assert math.degrees(math.atan2(x, -y)) == pytest.approx(26)
    swung = layouts.camera_for_view(layouts.STAGED, 1)
    assert swung["rotation_deg"] == [72, 0, 26 - 75]


# ------------------------------------------------------------------ jobs


def test_job_from_a_program(tmp_path: Path) -> None:
    source = load_source(str(PROGRAM), size=16)
    try:
        assert source.temp_dir is not None and (source.maps_dir / "material.json").is_file()
        options = RenderOptions(layouts=("flat", "staged"), size=16, samples=4, views="all")
        job = build_job(source, options, tmp_path)
    finally:
        source.cleanup()
    assert not Path(job["maps_dir"]).exists()  # the temporary render is gone
    assert job["maps"]["basecolor"]["colour_space"] == "sRGB" and job["maps"]["basecolor"]["alpha"]
    assert job["maps"]["roughness"]["colour_space"] == "Non-Color"
    assert job["maps"]["emissive"]["colour_space"] == "Linear Rec.709"
    assert job["maps"]["anisotropy_angle"]["scale"] == pytest.approx(1 / 360)  # the float copy
    assert job["maps"]["normal"]["file"].endswith("normal_gl.png")
    assert job["defaults"]["ior"] == 1.5
    assert job["surface"] == {
        "physical": False,
        "size": [2.0, 2.0],
        "object_scale": 1.0,
        "displacement_scale": 1.0,  # 2 / span, span 2
        "midlevel": 0.0,
    }
    assert [r["layout"] for r in job["renders"]] == ["flat"] * 4 + ["staged"] * 6
    assert job["layouts"]["flat"]["samples"] == 4 and job["layouts"]["staged"]["resolution"] == 16
    assert job["renders"][5]["output"] == str(tmp_path / "staged_view-1.png")
    json.dumps(job)  # plain JSON


def test_job_from_a_render_folder_with_a_physical_size(tmp_path: Path) -> None:
    out = tmp_path / "maps"
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "render", str(PROGRAM), "-o", str(out), "--size", "16"]
        + ["--unit-m", "0.5", "--constants-as-values"],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert res.returncode == 0, res.stderr
    source = load_source(str(out))
    assert source.temp_dir is None and source.name == "maps"
    job = build_job(source, RenderOptions(save="scene.blend"), tmp_path / "o")
    assert job["surface"]["physical"] and job["surface"]["size"] == [1.0, 1.0]
    assert job["surface"]["displacement_scale"] == 0.5  # metres per unit
    assert job["surface"]["object_scale"] == 2.0
    assert job["maps"]["metallic"] == {"file": None, "colour_space": "Non-Color", "constant": 0.0}
    assert job["save_blend"] == str(tmp_path / "o" / "scene.blend")
    assert planned_files(RenderOptions(layouts=("flat", "staged"), save="a.blend")) == [
        "flat.png",
        "staged.png",
        "a.blend",
    ]


def _export(tmp_path: Path, name: str, *extra: str, program: Path = PROGRAM) -> Path:
    out = tmp_path / name
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "render", str(program), "-o", str(out), "--size", "16"]
        + list(extra),
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert res.returncode == 0, res.stderr
    return out


def _packed(folder: Path, tmp_path: Path) -> Any:
    return build_job(load_source(str(folder)), RenderOptions(), tmp_path / "o")["packed"]


def test_packed_orm_and_mask_map_are_found(tmp_path: Path) -> None:
    assert _packed(_export(tmp_path, "plain"), tmp_path) is None
    both = _export(tmp_path, "both", "--preset", "unity", "--preset", "godot")
    packed = _packed(both, tmp_path)
    assert (packed["preset"], packed["role"]) == ("godot", "orm")  # ORM first, then the mask map
    assert packed["file"] == str(both.absolute() / "godot" / "01_plank_floor_orm.png")
    assert packed["channels"] == {
        "ao": {"channel": "R", "invert": False},
        "roughness": {"channel": "G", "invert": False},
        "metallic": {"channel": "B", "invert": False},
    }
    unity = _export(tmp_path, "unity", "--preset", "unity")
    packed = _packed(unity, tmp_path)
    assert (packed["preset"], packed["role"]) == ("unity", "maskmap")
    assert packed["channels"] == {
        "metallic": {"channel": "R", "invert": False},
        "ao": {"channel": "G", "invert": False},
        "roughness": {"channel": "A", "invert": True},  # smoothness = 1 - roughness
    }
    (unity / "unity" / "01_plank_floor_maskmap.png").unlink()
    with pytest.raises(BlenderJobError, match="maskmap.png is listed in material.json but miss"):
        _packed(unity, tmp_path)


def test_constant_orm_is_not_packed(tmp_path: Path) -> None:
    program = tmp_path / "flat.mat"
    program.write_text("Material(Layer(1).basecolor(200, 30, 30).roughness(0.4))\n")
    folder = _export(tmp_path, "gltf", "--preset", "gltf", program=program)
    assert _packed(folder, tmp_path) is None  # constant AO, roughness and metallic: values


def test_folder_without_manifest_is_a_clear_error(
    tmp_path: Path, matloom_cli: Any, one_line_error: Any
) -> None:
    (tmp_path / "basecolor.png").write_bytes(b"x")
    with pytest.raises(BlenderJobError, match="has no material.json"):
        read_manifest(tmp_path)
    res = matloom_cli("blender", str(tmp_path), "-o", str(tmp_path / "out"))
    line = one_line_error(res)
    assert "has no material.json" in line and "matloom render" in line
    assert res.returncode == 1 and not (tmp_path / "out").exists()


def test_bad_options_are_usage_errors(
    tmp_path: Path, matloom_cli: Any, one_line_error: Any
) -> None:
    res = matloom_cli("blender", str(PROGRAM), "-o", str(tmp_path), "--save", "../x.blend")
    assert res.returncode == 2 and ".blend" in one_line_error(res)
    both = matloom_cli("blender", str(PROGRAM), "-o", str(tmp_path / "x.png"), "--layout", "both")
    assert both.returncode == 2 and "names one image" in one_line_error(both)
    views = matloom_cli("blender", str(PROGRAM), "-o", str(tmp_path / "x.png"), "--views", "all")
    assert views.returncode == 2 and "give a folder for -o" in one_line_error(views)
    two = matloom_cli("blender", str(PROGRAM), str(PROGRAM), "-o", str(tmp_path / "x.png"))
    assert two.returncode == 2 and "2 sources" in one_line_error(two)
    assert not list(tmp_path.iterdir())


# ------------------------------------------------------------------ the worker script


WORKER_MODULES = sorted(WORKER.parent.glob("worker*.py"))


def test_worker_imports_only_bpy_and_the_standard_library() -> None:
    siblings = {path.stem for path in WORKER_MODULES}
    assert {"worker", "worker_common", "worker_material"} <= siblings
    allowed = set(sys.stdlib_module_names) | {"bpy", "bmesh", "mathutils", "__future__"}
    for path in WORKER_MODULES:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        imported = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                imported |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom):
                imported.add((node.module or "").split(".")[0])
        assert imported <= allowed | siblings, (path.name, imported - allowed - siblings)
        assert "matloom" not in imported
        names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
        assert not names & {"eval", "exec"}
        assert len(path.read_text(encoding="utf-8").splitlines()) < 600


def test_matloom_never_imports_bpy() -> None:
    code = (
        "import sys, matloom.blender.runner, matloom.blender.job, matloom.cli.blender_cmd;"
        "print('bpy' in sys.modules)"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert res.stdout.strip() == "False", res.stderr


def test_worker_without_bpy_reports_json(tmp_path: Path) -> None:
    res = subprocess.run(
        [sys.executable, str(WORKER), str(tmp_path / "job.json")], capture_output=True, text=True
    )
    if "bpy" in res.stdout and '"no_bpy"' not in res.stdout:
        pytest.skip("this Python has bpy")
    assert res.returncode == 3
    event = json.loads(res.stdout.strip().removeprefix("MATLOOM-JSON "))
    assert event["event"] == "error" and event["kind"] == "no_bpy"
