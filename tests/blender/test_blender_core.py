"""`matloom blender` without Blender: the layout table, jobs, the runner's errors, the worker.

Blender itself is replaced by small fake executables written here (crash, wrong version, error
event, a kill after a partial write); the real renders are in test_blender_render.py.
"""

from __future__ import annotations

import ast
import json
import math
import os
import stat
import subprocess
import sys
import textwrap
from pathlib import Path

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
from matloom.blender.runner import (
    WORKER,
    Blender,
    BlenderError,
    check_version,
    find_blender,
    run_worker,
)
from matloom.io.outdir import STAGING_PREFIX

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


def test_folder_without_manifest_is_a_clear_error(tmp_path: Path) -> None:
    (tmp_path / "basecolor.png").write_bytes(b"x")
    with pytest.raises(BlenderJobError, match="has no material.json"):
        read_manifest(tmp_path)
    res = _matloom("blender", str(tmp_path), "-o", str(tmp_path / "out"))
    line = _one_line_error(res)
    assert "has no material.json" in line and "matloom render" in line
    assert res.returncode == 1 and not (tmp_path / "out").exists()


def test_bad_options_are_usage_errors(tmp_path: Path) -> None:
    res = _matloom("blender", str(PROGRAM), "-o", str(tmp_path), "--save", "../x.blend")
    assert res.returncode == 2 and ".blend" in _one_line_error(res)


# ------------------------------------------------------------------ finding and running Blender


def _fake(tmp_path: Path, body: str, name: str = "blender") -> Path:
    """An executable Python script standing in for Blender."""
    path = tmp_path / name
    path.write_text(f"#!{sys.executable}\n" + textwrap.dedent(body))
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


VERSION_42 = """
import json, os, signal, sys, time
if sys.argv[1:] == ["--version"]:
    print("Blender 4.2.3 LTS\\n\\tbuild date: 2024")
    sys.exit(0)
job = json.load(open(sys.argv[-1]))
"""


def test_missing_blender_says_how_to_get_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    with pytest.raises(BlenderError, match="make blender-venv"):
        find_blender(str(tmp_path / "nowhere" / "blender"))
    monkeypatch.setattr("matloom.blender.runner.project_venvs", lambda: [])
    with pytest.raises(BlenderError, match=r"Blender not found; install Blender 4\.2"):
        find_blender(None, env={"PATH": str(tmp_path)})
    res = _matloom(
        "blender", str(PROGRAM), "-o", str(tmp_path / "o"), "--blender", str(tmp_path / "nope")
    )
    assert "blender.org" in _one_line_error(res)


def test_discovery_order(tmp_path: Path) -> None:
    exe = _fake(tmp_path, VERSION_42)
    python = _fake(tmp_path, VERSION_42, name="python3.11")
    assert find_blender(str(python)).kind == "bpy"
    assert find_blender(None, env={"MATLOOM_BLENDER": str(exe)}).kind == "blender"
    found = find_blender(None, env={"MATLOOM_BLENDER_PYTHON": str(exe), "PATH": ""})
    assert found.kind == "bpy" and found.origin == "MATLOOM_BLENDER_PYTHON"
    assert find_blender(None, env={"PATH": str(tmp_path)}).path == str(exe)


def test_wrong_version_and_not_blender(tmp_path: Path) -> None:
    old = _fake(tmp_path, 'print("Blender 3.6.5")\n', name="old")
    with pytest.raises(BlenderError, match=r"Blender 3\.6\.5; MatLoom needs 4\.2"):
        check_version(Blender(str(old), "blender", "test"))
    other = _fake(tmp_path, 'print("hello")\n', name="other")
    with pytest.raises(BlenderError, match="does not look like Blender"):
        check_version(Blender(str(other), "blender", "test"))
    assert check_version(Blender(str(_fake(tmp_path, VERSION_42)), "blender", "t"))[:2] == (4, 2)


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("os.kill(os.getpid(), signal.SIGSEGV)\n", "killed by SIGSEGV"),
        (
            "print('boom: out of memory'); sys.exit(3)\n",
            r"exited with status 3 \(.*\); last output: boom",
        ),
        (
            "print('MATLOOM-JSON ' + json.dumps({'event': 'error', 'message': 'no GPU memory'}))\n"
            "sys.exit(1)\n",
            "Blender: no GPU memory",
        ),
        ("sys.exit(0)\n", "exited without finishing the job"),
    ],
)
def test_worker_failures_are_one_clear_line(tmp_path: Path, body: str, message: str) -> None:
    fake = _fake(tmp_path, VERSION_42 + body)
    job = tmp_path / "job.json"
    job.write_text("{}")
    with pytest.raises(BlenderError, match=message) as info:
        run_worker(Blender(str(fake), "blender", "test"), job)
    assert "\n" not in str(info.value)


def test_killed_render_leaves_no_half_written_png(tmp_path: Path) -> None:
    """A Blender killed after writing part of an image: nothing appears under the final name,
    the staging folder is cleaned, the user's file is untouched, and the error is one line."""
    fake = _fake(
        tmp_path,
        VERSION_42
        + """
out = job["renders"][0]["output"]
with open(out, "wb") as handle:
    handle.write(b"\\x89PNG\\r\\n\\x1a\\n half")
os.kill(os.getpid(), signal.SIGKILL)
""",
    )
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    res = _matloom("blender", str(PROGRAM), "-o", str(out), "--size", "16", "--blender", str(fake))
    assert "killed by SIGKILL" in _one_line_error(res)
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == ["notes.txt"]
    assert not [p for p in out.iterdir() if p.name.startswith(STAGING_PREFIX)]
    assert (out / "notes.txt").read_text() == "mine"


def test_a_foreign_file_is_never_overwritten(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "flat.png").write_bytes(b"an artist's file")
    fake = _fake(tmp_path, VERSION_42)
    res = _matloom("blender", str(PROGRAM), "-o", str(out), "--size", "16", "--blender", str(fake))
    assert "never overwrites" in _one_line_error(res)
    assert (out / "flat.png").read_bytes() == b"an artist's file"


# ------------------------------------------------------------------ the worker script


def test_worker_imports_only_bpy_and_the_standard_library() -> None:
    tree = ast.parse(WORKER.read_text(encoding="utf-8"))
    allowed = set(sys.stdlib_module_names) | {"bpy", "bmesh", "mathutils", "__future__"}
    imported = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            imported |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add((node.module or "").split(".")[0])
    assert imported <= allowed, imported - allowed
    assert "matloom" not in imported
    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    assert not names & {"eval", "exec"}


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


# ------------------------------------------------------------------ helpers


def _matloom(*args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for var in ("MATLOOM_BLENDER", "MATLOOM_BLENDER_PYTHON"):
        env.pop(var, None)
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )


def _one_line_error(res: subprocess.CompletedProcess[str]) -> str:
    assert res.returncode != 0, res.stderr
    assert "Traceback" not in res.stderr, res.stderr
    errors = [line for line in res.stderr.splitlines() if line.startswith("Error:")]
    assert len(errors) == 1, res.stderr
    return errors[0]
