"""`matloom library search|show|list|render|check`."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

import matloom.library.checks as checks
from matloom.cli.main import cli
from matloom.library import library
from matloom.library.coverage import coverage_table


def run(*args: str) -> tuple[int, str]:
    res = CliRunner().invoke(cli, ["library", *args])
    return res.exit_code, res.output


def test_search_prints_ranked_candidates() -> None:
    code, out = run("search", "cracked", "desert", "mud", "--top", "3")
    assert code == 0
    lines = [ln for ln in out.splitlines() if ln.strip()[:2].rstrip(".").isdigit()]
    assert len(lines) == 3
    assert "cracked-earth" in lines[0]


def test_search_without_a_match_fails() -> None:
    code, _ = run("search", "zorblax")
    assert code == 1


def test_show_prints_the_file() -> None:
    code, out = run("show", "cobblestone")
    assert code == 0
    assert "# description = " in out and "Material(" in out


def test_show_unknown_name_is_an_error() -> None:
    code, out = run("show", "cobblestones")
    assert code != 0
    assert "no library entry" in out and "cobblestone" in out


def test_list_and_stats() -> None:
    code, out = run("list", "--category", "tiles")
    assert code == 0
    assert "square-tiles" in out and "cobblestone" not in out
    code, out = run("list", "--stats")
    assert code == 0
    assert out.strip() == coverage_table(library())


def test_render_writes_maps_with_physical_size(tmp_path: Path) -> None:
    out = tmp_path / "r"
    code, text = run("render", "cobblestone", "-o", str(out), "--size", "32")
    assert code == 0, text
    manifest = json.loads((out / "material.json").read_text())
    entry = library().entry("cobblestone")
    assert abs(manifest["physical_size"]["width_m"] - entry.size_m) < 1e-3
    assert (out / "basecolor.png").exists() and (out / "preview.png").exists()
    assert manifest["tileable"] is True


def test_check_named_entries() -> None:
    code, out = run("check", "cobblestone", "square-tiles", "--size", "48")
    assert code == 0, out


def test_check_evaluates_at_128_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    code, out = run("check", "--help")
    assert code == 0 and "--size" in out and "128" in out
    sizes: list[int] = []
    real = checks.evaluate_problems

    def spy(program, size, tileable):  # noqa: ANN001, ANN202
        sizes.append(size)
        return real(program, size, tileable)

    monkeypatch.setattr(checks, "evaluate_problems", spy)
    code, out = run("check", "cobblestone")
    assert code == 0, out
    assert sizes == [128]
