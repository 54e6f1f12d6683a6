"""Engine exports carry the material's name, not `material`: a run folder's `material.mat`
re-rendered with a preset takes the name `generate` recorded in its `material.json`."""

from __future__ import annotations

import json
import os
from pathlib import Path

from click.testing import CliRunner

from matloom.cli.main import cli

PROGRAM = "Material(Layer(1).basecolor(200, 100, 50).roughness(X()))\n"


def _render(program: Path, out: Path, *extra: str) -> list[str]:
    result = CliRunner().invoke(
        cli,
        ["render", str(program), "--size", "16", "--no-preview", "--preset", "unreal", "-o",
         str(out), *extra],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    return sorted(os.listdir(out / "unreal"))


def test_offline_generate_then_render_names_exports_after_the_request(tmp_path: Path) -> None:
    run = tmp_path / "run"
    result = CliRunner().invoke(
        cli, ["generate", "red brick wall", "-o", str(run), "--export-size", "32", "--quiet"]
    )
    assert result.exit_code == 0, result.output
    name = json.loads((run / "material.json").read_text())["name"]
    assert name and name != "material"
    files = _render(run / "material.mat", tmp_path / "out")
    assert files and all(f"_{name}_" in f for f in files if f.startswith("T_")), files
    assert not any("T_material_" in f for f in files), files


def test_render_records_its_name_and_a_rerender_keeps_it(tmp_path: Path) -> None:
    source = tmp_path / "copper_sheet.mat"
    source.write_text(PROGRAM)
    first = tmp_path / "first"
    _render(source, first)
    assert json.loads((first / "material.json").read_text())["name"] == "copper_sheet"
    (first / "material.mat").write_text(PROGRAM)
    files = _render(first / "material.mat", tmp_path / "second")
    assert any("copper_sheet" in f for f in files), files


def test_a_symlinked_manifest_is_not_read(tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere.json"
    elsewhere.write_text(json.dumps({"name": "stolen"}))
    run = tmp_path / "run"
    run.mkdir()
    (run / "material.mat").write_text(PROGRAM)
    (run / "material.json").symlink_to(elsewhere)
    files = _render(run / "material.mat", tmp_path / "out")
    assert not any("stolen" in f for f in files), files
    assert any("_material_" in f for f in files), files


def test_an_explicit_name_wins(tmp_path: Path) -> None:
    run = tmp_path / "run"
    run.mkdir()
    (run / "material.mat").write_text(PROGRAM)
    (run / "material.json").write_text(json.dumps({"name": "recorded"}))
    files = _render(run / "material.mat", tmp_path / "out", "--name", "chosen")
    assert any("chosen" in f for f in files) and not any("recorded" in f for f in files)
