"""Where `matloom blender` puts its images: a folder, a single `-o out.png`, a batch of sources
with `--jobs`, and the Python API `matloom.blender.render_layouts`.

A fake Blender (conftest.py) renders each view as a flat-colour PNG, so these run anywhere;
the same paths with a real Blender are in test_blender_render.py.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from matloom.blender import BlenderError, render_layouts
from matloom.io.png import read_png, written_by_matloom

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = ROOT / "docs" / "examples" / "01_plank_floor.mat"
SECOND = ROOT / "docs" / "examples" / "02_pebbles.mat"
Fake = Callable[..., Path]


def _export(tmp_path: Path, name: str = "maps", program: Path = PROGRAM) -> Path:
    out = tmp_path / name
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "render", str(program), "-o", str(out), "--size", "16"],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert res.returncode == 0, res.stderr
    return out


def test_single_png(tmp_path: Path, fake_blender: Fake, matloom_cli: Any) -> None:
    fake = fake_blender()
    target = tmp_path / "renders" / "plank.png"
    args = ["blender", str(PROGRAM), "--layout", "staged", "-o", str(target), "--size", "16"]
    res = matloom_cli(*args, "--blender", str(fake))
    assert res.returncode == 0, res.stderr
    assert res.stdout.split() == [str(target)]
    assert sorted(p.name for p in target.parent.iterdir()) == ["plank.png"]  # nothing else
    assert written_by_matloom(target)  # re-encoded by MatLoom: its own file from now on
    assert read_png(target).shape == (16, 16, 4)
    again = matloom_cli(*args, "--blender", str(fake))  # replaces its own file
    assert again.returncode == 0, again.stderr
    # --save puts the .blend beside the image, recorded in the folder's index
    saved = matloom_cli(*args, "--save", "scene.blend", "--blender", str(fake))
    assert saved.returncode == 0, saved.stderr
    assert saved.stdout.split() == [str(target), str(target.parent / "scene.blend")]
    assert (target.parent / "scene.blend").read_bytes() == b"BLENDER-v500 fake"
    assert (target.parent / ".matloom-files.json").is_file()


def test_single_png_refuses_a_foreign_blend(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any
) -> None:
    (tmp_path / "scene.blend").write_bytes(b"an artist's scene")
    fake = fake_blender()
    target = tmp_path / "x.png"
    args = ["-o", str(target), "--save", "scene.blend", "--blender", str(fake)]
    res = matloom_cli("blender", str(PROGRAM), *args)
    line = one_line_error(res)
    assert "scene.blend" in line and "never overwrites" in line
    assert (tmp_path / "scene.blend").read_bytes() == b"an artist's scene"
    assert not (tmp_path / "x.png").exists()


def test_batch_of_sources_with_jobs(tmp_path: Path, fake_blender: Fake, matloom_cli: Any) -> None:
    fake = fake_blender()
    maps = _export(tmp_path, "exported")
    out = tmp_path / "out"
    res = matloom_cli(
        "blender",
        str(PROGRAM),
        str(SECOND),
        str(maps),
        str(PROGRAM),
        "--layout",
        "both",
        "--jobs",
        "2",
        "-o",
        str(out),
        "--size",
        "16",
        "--blender",
        str(fake),
    )
    assert res.returncode == 0, res.stderr
    folders = ["01_plank_floor", "01_plank_floor-2", "02_pebbles", "exported"]
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == folders
    for name in folders:
        assert sorted(p.name for p in (out / name).iterdir()) == ["flat.png", "staged.png"]
        assert written_by_matloom(out / name / "staged.png")
    # progress: one line per view and one per finished material, counted
    assert res.stderr.count(" view 0 (") == 16  # started and done, 2 layouts x 4 sources
    done = [line for line in res.stderr.splitlines() if line.startswith("[")]
    assert sorted(line.split("]")[0] for line in done) == ["[1/4", "[2/4", "[3/4", "[4/4"]
    assert "rendered 4 of 4 material(s)" in res.stderr


def test_batch_reports_each_failure(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any, one_line_error: Any
) -> None:
    fake = fake_blender(
        "if 'pebbles' in job['name']:\n    os.kill(os.getpid(), signal.SIGSEGV)\n"
        "render_all()\nemit('done', seconds=0.01)\n"
    )
    out = tmp_path / "out"
    args = ["-o", str(out), "--size", "16", "--jobs", "2", "--blender", str(fake)]
    res = matloom_cli("blender", str(PROGRAM), str(SECOND), *args)
    assert "killed by SIGSEGV" in one_line_error(res)
    assert "failed: " in res.stderr and "rendered 1 of 2 material(s)" in res.stderr
    assert (out / "01_plank_floor" / "flat.png").is_file()  # the other material is kept
    assert not (out / "02_pebbles").exists()


# ------------------------------------------------------------------ the Python API


def test_render_layouts(tmp_path: Path, fake_blender: Fake) -> None:
    maps = _export(tmp_path)
    lines: list[str] = []
    out = tmp_path / "renders"
    paths = render_layouts(
        maps,
        ["flat", "staged"],
        out,
        size=16,
        samples=2,
        blender=str(fake_blender()),
        progress=lines.append,
    )
    assert paths == [out / "flat.png", out / "staged.png"]
    assert all(written_by_matloom(p) and read_png(p).shape == (16, 16, 4) for p in paths)
    assert lines == [
        "flat view 0 (1/2) rendering",
        "flat view 0 (1/2) in 0.0 s",
        "staged view 0 (2/2) rendering",
        "staged view 0 (2/2) in 0.0 s",
    ]
    assert sorted(p.name for p in out.iterdir()) == ["flat.png", "staged.png"]
    # again: its own files are replaced; views="all" names each view
    views = render_layouts(maps, ["both"], out, size=16, blender=str(fake_blender()), views="all")
    assert [p.name for p in views][:2] == ["flat_view-0.png", "flat_view-1.png"]
    assert len(views) == 4 + 6


@pytest.mark.parametrize(
    ("case", "message"),
    [
        ("no manifest", "has no material.json"),
        ("program file", "not a folder exported by `matloom render`"),
        ("bad layout", "unknown layout"),
        ("foreign file", "not written by MatLoom"),
        ("crash", "killed by SIGSEGV"),
        ("missing blender", "Blender not found"),
    ],
)
def test_render_layouts_errors_are_one_line(
    tmp_path: Path, fake_blender: Fake, case: str, message: str
) -> None:
    maps = _export(tmp_path)
    out = tmp_path / "renders"
    blender = str(fake_blender())
    layouts = ["flat"]
    source: Path = maps
    if case == "no manifest":
        source = tmp_path / "empty"
        source.mkdir()
    elif case == "program file":
        source = PROGRAM
    elif case == "bad layout":
        layouts = ["side"]
    elif case == "foreign file":
        out.mkdir()
        (out / "flat.png").write_bytes(b"mine")
    elif case == "crash":
        blender = str(fake_blender("os.kill(os.getpid(), signal.SIGSEGV)\n", name="crashes"))
    elif case == "missing blender":
        blender = str(tmp_path / "no-blender")
    with pytest.raises(BlenderError, match=message) as info:
        render_layouts(source, layouts, out, size=16, blender=blender)
    assert "\n" not in str(info.value)
    if case == "foreign file":
        assert (out / "flat.png").read_bytes() == b"mine"
    else:
        assert not out.exists()


def test_one_layout_after_the_other_keeps_both(
    tmp_path: Path, fake_blender: Fake, matloom_cli: Any
) -> None:
    """`--layout flat` then `--layout staged` into one folder: both images stay (each layout is
    its own install group); re-rendering flat replaces only flat.png."""
    fake = fake_blender()
    out = tmp_path / "out"
    for layout in ("flat", "staged", "flat"):
        res = matloom_cli(
            "blender",
            str(PROGRAM),
            "--layout",
            layout,
            "-o",
            str(out),
            "--size",
            "16",
            "--blender",
            str(fake),
        )
        assert res.returncode == 0, res.stderr
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == [
        "flat.png",
        "staged.png",
    ]
