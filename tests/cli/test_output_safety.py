"""Every command that writes keeps the user's files: the reproducers of the reliability review.

`render -o .` once deleted the working directory; two renders into one folder mixed their
files; a killed render left a complete-looking folder. These tests run the real CLI.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import random
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from matloom.cli.main import cli
from matloom.io import png
from matloom.io.outdir import STAGING_PREFIX, OutputFolder

ROOT = Path(__file__).resolve().parents[2]
PROGRAM_A = (ROOT / "matloom" / "examples" / "bricks_quickstart.mat").read_text()
PROGRAM_B = (ROOT / "matloom" / "examples" / "black_ceramic_tiles.mat").read_text()


def matloom(*args: str, cwd: Path | None = None, **kw: object) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=600,
        **kw,  # type: ignore[arg-type]
    )


def snapshot(folder: Path) -> dict[str, bytes]:
    """Every visible file under ``folder`` (relative name -> bytes)."""
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not any(part.startswith(".") for part in p.relative_to(folder).parts)
    }


def one_line_error(res: subprocess.CompletedProcess[str]) -> str:
    assert res.returncode != 0
    assert "Traceback" not in res.stderr
    lines = [line for line in res.stderr.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("Error:")]
    assert len(errors) == 1, res.stderr
    return errors[0]


def assert_complete_or_incomplete(folder: Path) -> bool:
    """A folder with material.json must hold exactly the files it lists (no mix)."""
    manifest_path = folder / "material.json"
    if not manifest_path.exists():
        return False
    manifest = json.loads(manifest_path.read_text())
    for name, digest in manifest["files"].items():
        data = (folder / name).read_bytes()
        assert hashlib.sha256(data).hexdigest() == digest, f"{name} is from another render"
    return True


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A user's project folder: a program, notes and a sub-folder."""
    (tmp_path / "prog.mat").write_text(PROGRAM_A)
    (tmp_path / "notes.txt").write_text("my notes")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "thesis.tex").write_text("\\section{precious}")
    return tmp_path


def test_render_into_the_working_directory_keeps_everything(project: Path) -> None:
    before = snapshot(project)
    res = matloom("render", "prog.mat", "-o", ".", "--size", "32", cwd=project)
    assert res.returncode == 0, res.stderr
    after = snapshot(project)
    assert {k: after[k] for k in before} == before  # nothing of the user's changed
    assert "basecolor.png" in after and "material.json" in after
    assert assert_complete_or_incomplete(project)
    again = matloom("render", "prog.mat", "-o", ".", "--size", "32", "--maps", "ao", cwd=project)
    assert again.returncode == 0, again.stderr
    assert {k: snapshot(project)[k] for k in before} == before


def test_render_into_a_folder_with_foreign_files(project: Path) -> None:
    out = project / "sub"
    res = matloom("render", "prog.mat", "-o", str(out), "--size", "16", cwd=project)
    assert res.returncode == 0, res.stderr
    assert (out / "thesis.tex").read_text() == "\\section{precious}"
    (out / "roughness.png").unlink()
    (out / "roughness.png").write_bytes(b"an artist's hand-painted map")
    before = snapshot(project)
    res = matloom("render", "prog.mat", "-o", str(out), "--size", "16", cwd=project)
    assert "roughness.png, not written by MatLoom" in one_line_error(res)
    assert snapshot(project) == before


def test_render_into_an_existing_file(project: Path) -> None:
    res = matloom("render", "prog.mat", "-o", "notes.txt", cwd=project)
    assert "is a file" in one_line_error(res)
    assert (project / "notes.txt").read_text() == "my notes"


def test_render_into_a_read_only_folder() -> None:
    base = Path(tempfile.mkdtemp(prefix="matloom-ro-"))
    try:
        base.chmod(0o755)
        (base / "prog.mat").write_text(PROGRAM_A)
        (base / "prog.mat").chmod(0o644)
        read_only = base / "ro"
        read_only.mkdir()
        read_only.chmod(0o555)
        prefix: list[str] = []
        if os.geteuid() == 0:  # root ignores permission bits: run as nobody
            assert shutil.which("setpriv"), "util-linux setpriv is needed to drop root"
            prefix = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        res = subprocess.run(
            [*prefix, sys.executable, "-m", "matloom", "render", str(base / "prog.mat"), "-o"]
            + [str(read_only), "--size", "8"],
            capture_output=True,
            text=True,
            env=env,
            timeout=120,
        )
        assert "permission denied" in one_line_error(res)
        assert list(read_only.iterdir()) == []
    finally:
        (base / "ro").chmod(0o755)
        shutil.rmtree(base)


def test_full_disk_mid_render_changes_nothing(
    project: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = project / "out"
    ok = CliRunner().invoke(
        cli, ["render", str(project / "prog.mat"), "-o", str(out), "--size", "16"]
    )
    assert ok.exit_code == 0, ok.output
    before = snapshot(out)

    def disk_full(*args: object, **kwargs: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(png, "write_grey8", disk_full)
    (project / "prog.mat").write_text(PROGRAM_B)
    res = CliRunner().invoke(cli, ["render", str(project / "prog.mat"), "-o", str(out)])
    assert res.exit_code == 1
    assert res.output.strip().splitlines()[-1].endswith("no space left on device")
    assert snapshot(out) == before
    assert not [p for p in out.iterdir() if p.name.startswith(STAGING_PREFIX)]


def test_a_locked_folder_fails_clearly_and_is_untouched(project: Path) -> None:
    out = project / "out"
    out.mkdir()
    (out / "keep.txt").write_text("k")
    with OutputFolder(out):  # another MatLoom process holds the folder
        res = matloom("render", "prog.mat", "-o", str(out), "--size", "8", cwd=project)
    assert "being written by another MatLoom process" in one_line_error(res)
    assert snapshot(out) == {"keep.txt": b"k"}


def test_concurrent_renders_never_mix(project: Path) -> None:
    (project / "b.mat").write_text(PROGRAM_B)
    out = project / "out"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for _ in range(6):
        procs = [
            subprocess.Popen(
                [sys.executable, "-m", "matloom", "render", name, "-o", str(out), "--size", "128"],
                cwd=project,
                env=env,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
            )
            for name in ("prog.mat", "b.mat")
        ]
        results = [(p.wait(timeout=300), p.stderr.read()) for p in procs]  # type: ignore[union-attr]
        for code, err in results:
            assert "Traceback" not in err
            assert code == 0 or "another MatLoom process" in err, err
        assert any(code == 0 for code, _ in results)
        assert assert_complete_or_incomplete(out)  # complete, and every file from one render
    assert (project / "notes.txt").read_text() == "my notes"


def test_sigkill_at_random_moments_of_a_2048_render(project: Path) -> None:
    (project / "b.mat").write_text(PROGRAM_B)
    out = project / "out"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    rng = random.Random(20261124)
    for k in range(20):
        program = ("prog.mat", "b.mat")[k % 2]
        proc = subprocess.Popen(
            [sys.executable, "-m", "matloom", "render", program, "-o", str(out), "--size", "2048"],
            cwd=project,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        time.sleep(rng.uniform(0.3, 3.5))
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=60)
        assert_complete_or_incomplete(out)
        assert (project / "notes.txt").read_text() == "my notes"
    res = matloom("render", "prog.mat", "-o", str(out), "--size", "64", cwd=project)
    assert res.returncode == 0, res.stderr
    assert assert_complete_or_incomplete(out)
    leftovers = [p.name for p in out.iterdir() if ".tmp-" in p.name or STAGING_PREFIX in p.name]
    assert leftovers == []  # the killed runs' staging folders were cleaned up
    assert {"notes.txt", "prog.mat", "sub/thesis.tex"} <= set(snapshot(project))


def test_preview_never_overwrites_a_foreign_file(project: Path) -> None:
    photo = project / "photo.png"
    photo.write_bytes(b"\x89PNG\r\n\x1a\nnot MatLoom's")
    res = matloom("preview", "prog.mat", "-o", "photo.png", "--size", "16", cwd=project)
    assert "not written by MatLoom" in one_line_error(res)
    assert photo.read_bytes() == b"\x89PNG\r\n\x1a\nnot MatLoom's"
    ok = matloom("preview", "prog.mat", "-o", "swatch.png", "--size", "16", cwd=project)
    again = matloom("preview", "prog.mat", "-o", "swatch.png", "--size", "8", cwd=project)
    assert ok.returncode == 0 and again.returncode == 0, again.stderr
    assert png.read_png(project / "swatch.png").shape[:2] == (8, 8)


def test_sweep_and_seeds_keep_foreign_files(project: Path) -> None:
    (project / "sub" / "best.mat").write_text("mine")
    res = matloom("sweep", "prog.mat", "-k", "2", "--size", "16", "-o", "sub", cwd=project)
    assert "best.mat" in one_line_error(res)
    assert (project / "sub" / "best.mat").read_text() == "mine"
    ok = matloom("seeds", "prog.mat", "-k", "2", "-o", "sub", cwd=project)
    assert ok.returncode == 0, ok.stderr
    assert (project / "sub" / "variant_0000.mat").exists()
    assert (project / "sub" / "thesis.tex").exists() and (project / "sub" / "best.mat").exists()


def test_generate_refuses_to_overwrite_a_users_program(project: Path) -> None:
    (project / "run").mkdir()
    (project / "run" / "material.mat").write_text("my own program")
    res = matloom("generate", "red brick wall", "-o", "run", cwd=project)
    assert res.returncode != 0 and "Traceback" not in res.stderr
    assert "material.mat" in res.stderr and "not written by MatLoom" in res.stderr
    assert (project / "run" / "material.mat").read_text() == "my own program"


def test_gallery_keeps_foreign_files(project: Path) -> None:
    prompts = project / "prompts.json"
    prompts.write_text(json.dumps([{"id": "a", "text": "red brick"}]))
    res = matloom("gallery", str(prompts), "-o", "sub", "--size", "32", cwd=project)
    assert res.returncode == 0, res.stderr
    assert (project / "sub" / "thesis.tex").exists() and (project / "sub" / "index.html").exists()


def test_render_never_deletes_through_a_symlinked_subfolder(project: Path) -> None:
    """Issue 22, defect 1: an old-style manifest listing ``sub/thesis.tex`` with ``sub`` a
    symlink to the user's folder made ``render`` adopt the thesis and delete it as stale."""
    out = project / "out"
    out.mkdir()
    (out / "sub").symlink_to(project / "sub")
    manifest = {"format": "matloom-material", "maps": [{"file": "sub/thesis.tex"}]}
    (out / "material.json").write_text(json.dumps(manifest))
    res = matloom("render", "prog.mat", "-o", "out", "--size", "16", cwd=project)
    assert res.returncode == 0, res.stderr
    assert (project / "sub" / "thesis.tex").read_text() == "\\section{precious}"
    assert "sub/thesis.tex" not in json.loads((out / ".matloom-files.json").read_text())["files"]


def test_fmt_write_keeps_mode_and_symlink(tmp_path: Path) -> None:
    real = tmp_path / "real.mat"
    real.write_text("Material(Layer(1).roughness(0.5))\n")
    real.chmod(0o600)
    link = tmp_path / "link.mat"
    link.symlink_to(real)
    res = matloom("fmt", "--write", str(link))
    assert res.returncode == 0, res.stderr
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert stat.S_IMODE(real.stat().st_mode) == 0o600
    assert real.read_text().startswith("Material(")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.mat", "real.mat"]
