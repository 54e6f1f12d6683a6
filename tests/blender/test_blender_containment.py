"""`matloom blender` reads only what the user pointed at, keeps its outputs apart and leaks no
temporary folder (issue 22, defects 4, 10 and 17). None of these needs Blender: the checks run
before Blender starts, and a fake Blender stands in where a whole run is needed.
"""

from __future__ import annotations

import hashlib
import json
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import matloom
from matloom.blender import tempdirs
from matloom.blender.job import (
    BlenderJobError,
    RenderOptions,
    build_job,
    check_source,
    load_source,
)
from matloom.runtime.export import export_maps

SECRET = b"-----BEGIN OPENSSH PRIVATE KEY-----\nnot for a .blend\n"
PROGRAM = "Material(Layer(1).basecolor(200, 30, 30).roughness(X()))\n"

#: A fake Blender that "packs" like Blender does: the saved .blend holds every image's bytes.
PACKS_EVERY_IMAGE = """
render_all()
images = [m["file"] for m in job["maps"].values() if m.get("file")]
if job.get("packed"):
    images.append(job["packed"]["file"])
with open(job["save_blend"], "wb") as handle:
    for path in images:
        handle.write(open(path, "rb").read())
emit("done", seconds=0.01)
"""


def export(folder: Path, *presets: str) -> Path:
    """A small folder as `matloom render` writes it (in-process, 8x8)."""
    maps = matloom.evaluate(matloom.parse(PROGRAM), 8, 8)
    export_maps(maps, folder, program_text=PROGRAM, presets=list(presets), name="m")
    return folder


def edit_manifest(folder: Path, map_name: str, file: str, listed: bytes | None = SECRET) -> None:
    """Point ``map_name`` at ``file``; list it with the SHA-256 of ``listed`` (an attacker
    can list the right hash of a file whose content they know)."""
    manifest = json.loads((folder / "material.json").read_text())
    for entry in manifest["maps"]:
        if entry["name"] == map_name:
            entry["file"] = file
    if listed is not None:
        manifest["files"][file] = hashlib.sha256(listed).hexdigest()
    (folder / "material.json").write_text(json.dumps(manifest))


@pytest.fixture
def secret(tmp_path: Path) -> Path:
    (tmp_path / "secret").mkdir()
    key = tmp_path / "secret" / "id_rsa"
    key.write_bytes(SECRET)
    return key


def refused(folder: Path, match: str) -> None:
    """Both the early check and the job builder refuse ``folder`` with ``match``."""
    with pytest.raises(BlenderJobError, match=match):
        check_source(str(folder))
    with pytest.raises(BlenderJobError, match=match):
        build_job(load_source(str(folder)), RenderOptions(save="x.blend"), folder.parent / "o")


# ------------------------------------------------------------------ defect 4: containment


def test_map_paths_out_of_the_folder_are_refused(tmp_path: Path, secret: Path) -> None:
    folder = export(tmp_path / "dir")
    edit_manifest(folder, "basecolor", "../secret/id_rsa")
    refused(folder, "outside the folder")
    edit_manifest(folder, "basecolor", str(secret))
    refused(folder, "outside the folder")


def test_symlinked_maps_and_sub_folders_are_refused(tmp_path: Path, secret: Path) -> None:
    folder = export(tmp_path / "dir")
    (folder / "key.png").symlink_to(secret)
    edit_manifest(folder, "basecolor", "key.png")
    refused(folder, "through a symlink")
    packed = export(tmp_path / "packed", "gltf")
    orm = next((packed / "gltf").glob("*_orm.png"))
    (tmp_path / "secret" / orm.name).write_bytes(SECRET)
    manifest = json.loads((packed / "material.json").read_text())
    manifest["files"][f"gltf/{orm.name}"] = hashlib.sha256(SECRET).hexdigest()
    (packed / "material.json").write_text(json.dumps(manifest))
    for path in (packed / "gltf").iterdir():
        path.unlink()
    (packed / "gltf").rmdir()
    (packed / "gltf").symlink_to(tmp_path / "secret")
    refused(packed, "through a symlink")


def test_unlisted_or_changed_files_are_refused(tmp_path: Path) -> None:
    folder = export(tmp_path / "dir")
    (folder / "extra.png").write_bytes(SECRET)
    edit_manifest(folder, "basecolor", "extra.png", listed=None)
    refused(folder, "not listed with its SHA-256")
    edit_manifest(folder, "basecolor", "extra.png", listed=b"other bytes")
    refused(folder, "its SHA-256 differs")


def test_a_symlinked_manifest_is_not_read(tmp_path: Path) -> None:
    folder = export(tmp_path / "dir")
    (folder / "material.json").rename(tmp_path / "elsewhere.json")
    (folder / "material.json").symlink_to(tmp_path / "elsewhere.json")
    with pytest.raises(BlenderJobError, match="is a symlink"):
        check_source(str(folder))


def test_an_untouched_export_is_accepted(tmp_path: Path) -> None:
    folder = export(tmp_path / "dir", "gltf")
    check_source(str(folder))
    job = build_job(load_source(str(folder)), RenderOptions(), tmp_path / "o")
    assert job["maps"]["basecolor"]["file"] == str(folder.absolute() / "basecolor.png")
    assert job["packed"] is None or Path(job["packed"]["file"]).is_file()


def test_saved_blend_never_holds_a_file_from_outside(
    tmp_path: Path, secret: Path, fake_blender: Any, matloom_cli: Any, one_line_error: Any
) -> None:
    """The attack end to end: with a Blender that packs every image it loads, the .blend would
    carry the key; the folder is refused before Blender starts instead."""
    folder = export(tmp_path / "dir")
    edit_manifest(folder, "basecolor", "../secret/id_rsa")
    fake = fake_blender(PACKS_EVERY_IMAGE)
    out = tmp_path / "out"
    res = matloom_cli(
        "blender", str(folder), "--save", "x.blend", "-o", str(out), "--blender", str(fake)
    )
    assert "outside the folder" in one_line_error(res)
    assert not (out / "x.blend").exists()
    assert all(
        SECRET not in p.read_bytes() for p in tmp_path.rglob("*") if p.is_file() and p != secret
    )


# ------------------------------------------------------------------ defect 10: one name, two files


def test_save_material_blend_with_save_material_only_is_refused(
    tmp_path: Path, matloom_cli: Any, one_line_error: Any
) -> None:
    options = RenderOptions(save="material.blend", save_material_only=True)
    with pytest.raises(BlenderJobError, match="would both write material.blend"):
        options.validate()
    RenderOptions(save="scene.blend", save_material_only=True).validate()  # no clash
    program = tmp_path / "p.mat"
    program.write_text(PROGRAM)
    out = tmp_path / "out"
    res = matloom_cli(
        "blender", str(program), "-o", str(out), "--save", "material.blend", "--save-material-only"
    )
    assert res.returncode == 2 and "both write material.blend" in one_line_error(res)
    assert not out.exists()  # refused before any work


# ------------------------------------------------------------------ defect 17: stale temp folders


def _dead_folder(root: Path, env: dict[str, str]) -> Path:
    """A temporary folder whose process was SIGKILLed while using it."""
    code = (
        "import os, signal, tempfile\n"
        f"tempfile.tempdir = {str(root)!r}\n"
        "from matloom.blender.tempdirs import TempDir\n"
        "t = TempDir()\n"
        "(t.path / 'maps.exr').write_bytes(b'x' * 1000)\n"
        "print(t.path, flush=True)\n"
        "os.kill(os.getpid(), signal.SIGKILL)\n"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert res.returncode == -signal.SIGKILL, res.stderr
    return Path(res.stdout.strip())


def test_stale_temp_folders_are_removed_and_nothing_else(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, cli_environment: dict[str, str]
) -> None:
    root = tmp_path / "tmp"
    root.mkdir()
    dead = _dead_folder(root, cli_environment)
    outside = tmp_path / "keep.txt"
    outside.write_text("keep")
    (dead / "link").symlink_to(outside)
    unmarked = root / "matloom-blender-user"  # the user's own folder of that name: no marker
    unmarked.mkdir()
    (unmarked / "notes").write_text("mine")
    target = tmp_path / "target"  # a symlink of that name to a folder that looks stale
    target.mkdir()
    (target / tempdirs.MARKER).write_text("")
    (root / "matloom-blender-link").symlink_to(target)
    fake_marker = root / "matloom-blender-fake"  # a symlinked marker
    fake_marker.mkdir()
    (fake_marker / tempdirs.MARKER).symlink_to(outside)
    monkeypatch.setattr("tempfile.tempdir", str(root))
    monkeypatch.setattr(tempdirs, "_cleaned", True)  # the explicit call below does the work
    with tempdirs.TempDir() as live:
        assert tempdirs.clean_stale(root) == [dead]
        assert live.is_dir()  # in use (locked): kept
    assert not live.exists()
    assert outside.read_text() == "keep" and (unmarked / "notes").read_text() == "mine"
    assert (target / tempdirs.MARKER).exists() and fake_marker.is_dir()


def test_a_killed_blender_run_leaks_nothing_after_the_next_run(
    tmp_path: Path, fake_blender: Any, cli_environment: dict[str, str]
) -> None:
    """SIGKILL to MatLoom mid-render leaves its temporary folders; the next run removes them."""
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    program = tmp_path / "p.mat"
    program.write_text(PROGRAM)
    env = {**cli_environment, "TMPDIR": str(tmp)}
    kills_matloom = (
        "import os, signal\nos.kill(int(os.environ['MATLOOM_PARENT_PID']), signal.SIGKILL)\n"
    )
    for body, expect_ok in ((kills_matloom, False), ("render_all()\nemit('done')\n", True)):
        fake = fake_blender(body)
        res = subprocess.run(
            [
                sys.executable,
                "-m",
                "matloom",
                "blender",
                str(program),
                "-o",
                str(tmp_path / "out"),
                "--size",
                "8",
                "--blender",
                str(fake),
            ],
            capture_output=True,
            text=True,
            env=env,
            timeout=300,
        )
        assert (res.returncode == 0) == expect_ok, res.stderr
        if not expect_ok:
            assert [p.name for p in tmp.iterdir() if p.name.startswith("matloom-blender-")]
    assert [p.name for p in tmp.iterdir() if p.name.startswith("matloom-blender-")] == []
