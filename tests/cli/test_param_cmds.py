"""`matloom params` and `matloom set`: the table, JSON, writing, clamping warnings and errors."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from matloom.cli.main import cli

TEXT = """View(0, 0, 4, 4)
Define(grout, 0.02)  # joint
Define(tiles, Bricks(mortar=0.08))
Material(
  Layer(1)
    .basecolor(200, 120, 80)
    .roughness(0.6),
  Layer(tiles)
    .roughness(0.3)
)
"""


def _run(*args: str | Path):  # noqa: ANN202
    return CliRunner().invoke(cli, [str(a) for a in args])


def _file(tmp_path: Path, text: str = TEXT) -> Path:
    path = tmp_path / "m.mat"
    path.write_text(text, encoding="utf-8")
    return path


def test_params_table_and_json(tmp_path: Path) -> None:
    path = _file(tmp_path)
    res = _run("params", path)
    assert res.exit_code == 0, res.output
    assert res.output.splitlines()[0].split() == [
        "address", "value", "unit", "range", "kind", "label", "affects",
    ]  # fmt: skip
    assert any(ln.startswith("define:tiles.Bricks.mortar") for ln in res.output.splitlines())
    res = _run("params", path, "--json")
    assert res.exit_code == 0, res.output
    data = json.loads(res.output)
    by = {d["address"]: d for d in data}
    assert by["layer:1.basecolor"]["value"] == [200, 120, 80]
    assert by["layer:1.roughness"] | {"affects": None} == {
        "address": "layer:1.roughness",
        "value": 0.6,
        "kind": "scalar",
        "low": 0.0,
        "high": 1.0,
        "unit": None,
        "label": "roughness",
        "affects": None,
        "line": 7,
        "col": 16,
        "metres": None,
    }
    assert by["layer:1.roughness"]["affects"] == ["roughness"]


def test_set_prints_without_writing(tmp_path: Path) -> None:
    path = _file(tmp_path)
    res = _run("set", path, "layer:2.roughness=0.9")
    assert res.exit_code == 0, res.output
    assert "    .roughness(0.9)\n)" in res.output
    assert path.read_text() == TEXT


def test_set_to_out_and_write(tmp_path: Path) -> None:
    path = _file(tmp_path)
    out = tmp_path / "out.mat"
    res = _run("set", path, "define:grout=0.04", "layer:1.basecolor=#0000ff", "-o", out)
    assert res.exit_code == 0, res.output
    new = out.read_text()
    assert "Define(grout, 0.04)  # joint" in new and ".basecolor(0, 0, 255)" in new
    assert path.read_text() == TEXT
    res = _run("set", path, "layer:1.basecolor=10,20,30", "--write")
    assert res.exit_code == 0, res.output
    assert ".basecolor(10, 20, 30)" in path.read_text()
    assert path.read_text().replace("10, 20, 30", "200, 120, 80") == TEXT


def test_set_clamps_with_a_warning_on_stderr(tmp_path: Path) -> None:
    path = _file(tmp_path)
    res = CliRunner().invoke(cli, ["set", str(path), "layer:1.roughness=3"])
    assert res.exit_code == 0
    assert "warning: layer:1.roughness: 3 is outside [0, 1]; clamped to 1" in res.stderr
    assert ".roughness(1)," in res.stdout


def test_set_errors_are_one_line_exit_2(tmp_path: Path) -> None:
    path = _file(tmp_path)
    for args in (
        ["define:grot=1"],
        ["layer:1.basecolor=0.5"],
        ["layer:1.roughness"],
        ["layer:1.roughness=soft"],
        ["define:grout=1", "--write", "-o", str(tmp_path / "x.mat")],
    ):
        res = _run("set", path, *args)
        assert res.exit_code == 2, (args, res.output)
        lines = [ln for ln in res.output.splitlines() if ln.strip()]
        assert len(lines) == 1 and "Traceback" not in res.output, res.output
    res = _run("set", path, "define:grot=1")
    assert "unknown parameter 'define:grot'; close: define:grout" in res.output
    assert path.read_text() == TEXT


def test_params_on_a_broken_program_exits_2(tmp_path: Path) -> None:
    res = _run("params", _file(tmp_path, "Material(Layer(1).roughness(nope))\n"))
    assert res.exit_code == 2 and "Traceback" not in res.output


def test_params_on_a_library_entry_uses_its_labels() -> None:
    path = next(Path(__file__).resolve().parents[2].glob("matloom/library/entries/*/mars*.mat"))
    res = _run("params", path, "--json")
    assert res.exit_code == 0, res.output
    labels = {d["address"]: d["label"] for d in json.loads(res.output)}
    assert labels["define:rough"] == "roughness" and labels["define:dust"] == "dust colour"
