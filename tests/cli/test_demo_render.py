"""`matloom demo`, `matloom render`, `matloom preview`, `matloom sweep` end to end (subprocess)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TILE = ROOT / "tests" / "data" / "parity" / "tile.mat"


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=600,
    )


def test_demo_writes_everything_it_prints(tmp_path):
    out = tmp_path / "demo"
    res = run("demo", "-o", str(out), "--size", "64")
    assert res.returncode == 0, res.stderr
    paths = [
        line.split(None, 1)[1]
        for line in res.stdout.splitlines()
        if line.strip().startswith(("program", "preview", "record"))
    ]
    assert len(paths) >= 2 + 3 * 3
    for p in paths:
        assert Path(p.strip()).exists(), p
    again = run("demo", "-o", str(out), "--size", "64")
    assert again.returncode == 0, again.stderr


def test_render_exports_maps_and_manifest(tmp_path):
    out = tmp_path / "maps"
    res = run("render", str(TILE), "-o", str(out), "--size", "48", "--format", "png16")
    assert res.returncode == 0, res.stderr
    manifest = json.loads((out / "material.json").read_text())
    assert manifest["width"] == 48
    for name in (
        "basecolor.png",
        "normal_gl.png",
        "ao.png",
        "height.exr",
        "height16.png",
        "preview.png",
        "material.mat",
    ):
        assert (out / name).exists(), name


def test_render_rejects_unknown_map_and_bad_program(tmp_path):
    res = run("render", str(TILE), "-o", str(tmp_path / "x"), "--maps", "basecolor,shininess")
    assert res.returncode != 0 and "shininess" in res.stderr
    bad = tmp_path / "bad.mat"
    bad.write_text("Material(Layer(1).roughnes(0.5))")
    res = run("render", str(bad), "-o", str(tmp_path / "y"))
    assert res.returncode == 2 and "did you mean" in res.stderr
    assert not (tmp_path / "y").exists()


def test_render_reports_nonfinite_texels(tmp_path):
    prog = tmp_path / "nan.mat"
    prog.write_text(
        "Material(\n  Layer(1)\n    .roughness(Sqrt(X() - 0.5))\n    .height(Log(X() - 0.5))\n)"
    )
    res = run("render", str(prog), "-o", str(tmp_path / "n"), "--size", "16")
    assert res.returncode == 0, res.stderr
    assert "non-finite" in res.stderr


def test_preview_tile_and_sweep_cli(tmp_path):
    png = tmp_path / "p.png"
    res = run(
        "preview", str(TILE), "-o", str(png), "--size", "32", "--tile", "2", "--light", "30,40"
    )
    assert res.returncode == 0, res.stderr
    from PIL import Image

    assert Image.open(png).size == (64, 64)
    res = run("sweep", str(TILE), "-k", "3", "--size", "32", "--json", "-o", str(tmp_path / "s"))
    assert res.returncode == 0, res.stderr
    report = json.loads(res.stdout)
    assert report["candidates"] == 4
    assert (tmp_path / "s" / "best.mat").exists()
