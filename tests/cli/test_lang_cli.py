"""The language commands of the CLI: ``matloom check``, ``matloom fmt`` and ``matloom seeds``.

The CLI runs in a subprocess (``python -m matloom``) exactly as a user runs it.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import matloom

REPO = Path(__file__).resolve().parents[2]
PARITY = REPO / "tests" / "data" / "parity"
BROKEN = "Material(\n  Layer(1).roughness(fBm(octaves=2.5, seed=1))\n)\n"
WARNS = "Define(unused, X())\nMaterial(Layer(1).roughness(0.5))\n"


def run_cli(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(REPO), env.get("PYTHONPATH")) if p)
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        input=stdin,
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
        check=False,
    )


@pytest.fixture
def files(tmp_path: Path) -> dict[str, Path]:
    out = {}
    for name, text in {"broken": BROKEN, "warns": WARNS}.items():
        out[name] = tmp_path / f"{name}.mat"
        out[name].write_text(text, encoding="utf-8")
    for name in ("tile", "brick", "seedless"):
        out[name] = tmp_path / f"{name}.mat"
        shutil.copy(PARITY / f"{name}.mat", out[name])
    return out


# ---------------------------------------------------------------------------- check
def test_check_clean_program_exits_0(files: dict[str, Path]) -> None:
    result = run_cli("check", str(files["tile"]))
    assert result.returncode == 0, result.stderr
    assert "0 error(s), 0 warning(s)" in result.stderr


def test_check_warnings_exit_0_or_1_with_strict(files: dict[str, Path]) -> None:
    relaxed = run_cli("check", str(files["warns"]))
    assert relaxed.returncode == 0
    assert "W001" in relaxed.stderr and relaxed.stdout == ""
    strict = run_cli("check", "--strict", str(files["warns"]))
    assert strict.returncode == 1
    assert "W001" in strict.stderr


def test_check_errors_exit_2_with_diagnostics_on_stderr(files: dict[str, Path]) -> None:
    result = run_cli("check", str(files["broken"]))
    assert result.returncode == 2
    assert f"{files['broken']}:2:34: error E052" in result.stderr
    assert "^^^" in result.stderr  # caret excerpt
    assert result.stdout == ""


def test_check_reports_the_worst_of_several_files(files: dict[str, Path]) -> None:
    result = run_cli(
        "check", "--strict", str(files["tile"]), str(files["warns"]), str(files["broken"])
    )
    assert result.returncode == 2
    assert "3 file(s): 1 error(s), 1 warning(s)" in result.stderr


def test_check_json_and_stdin(files: dict[str, Path]) -> None:
    result = run_cli("check", "--json", "-", stdin=BROKEN)
    assert result.returncode == 2
    report = json.loads(result.stdout)
    assert report[0]["errors"] == 1
    assert report[0]["diagnostics"][0]["code"] == "E052"


# ---------------------------------------------------------------------------- fmt
def test_fmt_prints_the_reference_canonical_text(files: dict[str, Path]) -> None:
    result = run_cli("fmt", str(files["brick"]))
    assert result.returncode == 0, result.stderr
    assert result.stdout == (PARITY / "brick.canonical.mat").read_text(encoding="utf-8") + "\n"


def test_fmt_check(files: dict[str, Path]) -> None:
    assert run_cli("fmt", "--check", str(files["tile"])).returncode == 0  # already canonical
    not_canonical = run_cli("fmt", "--check", str(files["brick"]))
    assert not_canonical.returncode == 1 and not_canonical.stdout == ""
    assert run_cli("fmt", "--check", str(files["broken"])).returncode == 2


def test_fmt_write_is_atomic_and_canonical(files: dict[str, Path]) -> None:
    target = files["brick"]
    before = set(target.parent.iterdir())
    result = run_cli("fmt", "--write", str(target))
    assert result.returncode == 0, result.stderr
    written = target.read_text(encoding="utf-8")
    assert written == (PARITY / "brick.canonical.mat").read_text(encoding="utf-8") + "\n"
    assert set(target.parent.iterdir()) == before  # no temporary file left behind
    assert run_cli("fmt", "--check", str(target)).returncode == 0


def test_fmt_write_leaves_a_broken_file_untouched(files: dict[str, Path]) -> None:
    result = run_cli("fmt", "--write", str(files["broken"]))
    assert result.returncode == 2
    assert "E052" in result.stderr
    assert files["broken"].read_text(encoding="utf-8") == BROKEN


def test_fmt_inline(files: dict[str, Path]) -> None:
    result = run_cli("fmt", "--inline", str(files["tile"]))
    assert result.returncode == 0, result.stderr
    assert "Define(" not in result.stdout and "tileMask" not in result.stdout
    inlined = matloom.parse(result.stdout)
    assert inlined.defines == () and result.stdout.count("Bricks(") == 3


def test_fmt_inline_of_seedless_named_noise_renders_the_same_maps(
    files: dict[str, Path], tmp_path: Path
) -> None:
    # `seedless.mat` uses Define(n, fBm(...)) without a seed four times: the printed program
    # must render bit for bit what the file renders (`render` with its default program seed)
    result = run_cli("fmt", "--inline", str(files["seedless"]))
    assert result.returncode == 0, result.stderr
    inlined = tmp_path / "inlined.mat"
    inlined.write_text(result.stdout, encoding="utf-8")
    hashes = []
    for path in (files["seedless"], inlined):
        out = tmp_path / f"render-{path.stem}"
        rendered = run_cli("render", str(path), "-o", str(out), "--size", "32", "--format", "exr")
        assert rendered.returncode == 0, rendered.stderr
        manifest = json.loads((out / "material.json").read_text(encoding="utf-8"))
        maps = {m["file"] for m in manifest["maps"] if m.get("file")}
        hashes.append({f: h for f, h in manifest["files"].items() if f in maps})
    assert len(hashes[0]) >= 14 and hashes[0] == hashes[1]


# ---------------------------------------------------------------------------- seeds
def test_seeds_prints_original_and_three_variants(files: dict[str, Path]) -> None:
    result = run_cli("seeds", str(files["tile"]), "--variants", "3")
    assert result.returncode == 0, result.stderr
    headers = re.findall(r"^# variant (\d+)", result.stdout, flags=re.MULTILINE)
    assert headers == ["0", "1", "2", "3"]
    programs = [
        p.strip() for p in re.split(r"^# variant .*$", result.stdout, flags=re.M) if p.strip()
    ]
    assert len(programs) == 4
    original = (PARITY / "tile.canonical.mat").read_text(encoding="utf-8")
    assert programs[0] == original
    masked = re.sub(r"seed=\d+", "seed=N", original)
    for variant in programs[1:]:
        assert variant != original
        assert re.sub(r"seed=\d+", "seed=N", variant) == masked
        matloom.parse(variant)


def test_seeds_writes_four_files(files: dict[str, Path], tmp_path: Path) -> None:
    out_dir = tmp_path / "variants"
    result = run_cli("seeds", str(files["seedless"]), "--variants", "3", "-o", str(out_dir))
    assert result.returncode == 0, result.stderr
    written = sorted(p.name for p in out_dir.iterdir() if not p.name.startswith("."))
    assert written == [f"variant_{i:04d}.mat" for i in range(4)]
    texts = [(out_dir / name).read_text(encoding="utf-8") for name in written]
    assert len(set(texts)) == 4
    for text in texts:  # seedless noise was made explicit before the variants were drawn
        assert "W003" not in {d.code for d in matloom.check(text)}
        assert len(re.findall(r"seed=\d+", text)) == 4


def test_seeds_refuses_a_broken_program(files: dict[str, Path]) -> None:
    result = run_cli("seeds", str(files["broken"]), "--variants", "2")
    assert result.returncode == 2
    assert "E052" in result.stderr
