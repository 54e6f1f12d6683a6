"""A final material with NaN/inf maps is warned about (stderr and record) and replaced by the
best round whose maps are all finite."""

from __future__ import annotations

import json
from pathlib import Path

import matloom
from author.chat_server import ChatServer
from author.conftest import Script, example_program
from author.test_generate_e2e import generate
from matloom.author.records import validate_record_file
from matloom.author.stages.finite import nonfinite_texels

FINITE = example_program(0)
NAN_ROUGHNESS = """View(0, 0, 2, 2)
Material(
  Layer(1)
    .basecolor(200, 120, 80)
    .roughness(Sqrt(-1))
)"""
NAN_COLOUR = "Material(Layer(1).basecolor(Log(-1), 120, 80).roughness(0.5))"
EXPORT = 32  # FAST_FLAGS' --export-size


def critic_scores(*scores: int) -> list[str]:
    return [json.dumps({"match_score": s, "differences": [], "suggestions": []}) for s in scores]


def test_nan_last_round_falls_back_to_the_best_finite_round(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.generator.extend(f"<material>{p}</material>" for p in (FINITE, NAN_ROUGHNESS))
    script.critic.extend(critic_scores(40, 90))  # the critic prefers the NaN round
    result = generate(server, tmp_path / "run", "--rounds", "1", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.selection.method == "critic" and record.selection.index == 1
    assert "Sqrt(-1)" in record.programs[1].text
    (warning,) = record.warnings
    assert f"P1 has {EXPORT * EXPORT:,} texel(s) with NaN" in warning
    assert "exported P0 instead" in warning
    assert f"warning: {warning}" in result.stderr
    assert record.final.program_index == 0 and record.final.nonfinite_texels == 0
    assert (tmp_path / "run" / "material.mat").read_text().strip() == record.programs[0].text
    manifest = json.loads((tmp_path / "run" / "material.json").read_text())
    assert manifest["nonfinite_values"] == {}


def test_all_rounds_nan_is_exported_with_a_warning(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.default_generator = lambda body: f"<material>{NAN_COLOUR}</material>"
    result = generate(server, tmp_path / "run", "--rounds", "1", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    (warning,) = record.warnings
    assert "no round has all-finite maps" in warning and "warning:" in result.stderr
    assert record.final.nonfinite_texels == EXPORT * EXPORT


def test_finite_run_has_no_warning(server: ChatServer, tmp_path: Path) -> None:
    result = generate(server, tmp_path / "run", "--rounds", "1", "--json")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.warnings == [] and record.final.nonfinite_texels == 0
    assert json.loads(result.stdout)["warnings"] == [] and "warning" not in result.stderr


def test_nonfinite_texels_counts_texels_not_values() -> None:
    maps = matloom.evaluate(NAN_COLOUR, 8, 8)  # one NaN channel of the RGB basecolor
    assert nonfinite_texels(maps) == 64
    maps.roughness[0, :3] = float("inf")
    assert nonfinite_texels(maps) == 64
    assert nonfinite_texels(matloom.evaluate(FINITE, 8, 8)) == 0
