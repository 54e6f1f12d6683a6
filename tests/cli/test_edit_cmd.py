"""`matloom edit` offline: the files it writes, the history, --undo, and what it refuses."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from matloom.cli.main import cli

TILES = (
    Path(__file__).resolve().parents[2] / "matloom/examples/black_ceramic_tiles.mat"
).read_text()


@pytest.fixture(autouse=True)
def _no_config(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv("MATLOOM_CONFIG", str(tmp_path / "none.toml"))


def run(*args: str) -> object:
    return CliRunner().invoke(cli, ["edit", *args, "--size", "32"])


def _versions(path: Path) -> list[str | None]:
    data = json.loads(path.with_name(path.name + ".history.json").read_text())
    return [v["request"] for v in data["versions"]]


def test_edit_writes_program_report_diff_and_previews(tmp_path: Path) -> None:
    src = tmp_path / "tiles.mat"
    src.write_text(TILES)
    res = CliRunner().invoke(cli, ["edit", str(src), "wider grout", "--json"])  # 256 x 256
    assert res.exit_code == 0, res.output
    out = tmp_path / "tiles.edited.mat"
    assert "mortar=0.04" in out.read_text()
    assert src.read_text() == TILES
    record = json.loads(res.stdout)
    assert record["request"] == "wider grout" and record["mode"] == "rules"
    assert record["changed"][0]["address"] == "define:tileMask.Bricks.mortar"
    assert record["locality"]["leaks"] == [] and "basecolor" in record["locality"]["changed"]
    folder = tmp_path / "tiles.edited.edit"
    assert json.loads((folder / "edit.json").read_text())["request"] == "wider grout"
    diff = (folder / "edit.diff").read_text()
    assert "-Define(tileMask, Bricks(brick_width=0.5" in diff and "mortar=0.04" in diff
    png = (folder / "before_after.png").read_bytes()
    assert png.startswith(b"\x89PNG")
    assert int.from_bytes(png[16:20], "big") == 2 * 256 + 4  # before | after
    assert int.from_bytes(png[20:24], "big") == 2 * 256 + 4  # flat above, lit below


def test_edits_chain_and_undo_restores(tmp_path: Path) -> None:
    src = tmp_path / "tiles.mat"
    src.write_text(TILES)
    out = tmp_path / "tiles.edited.mat"
    assert run(str(src), "wider grout").exit_code == 0
    first = out.read_text()
    res = run(str(out), "blue glaze")  # an edited program: edited in place, history appended
    assert res.exit_code == 0, res.output
    assert "(40 + (glazeRipple * 6))" in out.read_text() and "mortar=0.04" in out.read_text()
    assert _versions(out) == [None, "wider grout", "blue glaze"]
    res = CliRunner().invoke(cli, ["edit", str(out), "--undo"])
    assert res.exit_code == 0, res.output
    assert out.read_text() == first
    assert _versions(out) == [None, "wider grout"]
    assert CliRunner().invoke(cli, ["edit", str(out), "--undo"]).exit_code == 0
    assert out.read_text() == TILES
    res = CliRunner().invoke(cli, ["edit", str(out), "--undo"])
    assert res.exit_code == 2 and "nothing to undo" in res.output


def test_hand_edit_is_kept_as_a_version(tmp_path: Path) -> None:
    src = tmp_path / "tiles.mat"
    src.write_text(TILES)
    out = tmp_path / "tiles.edited.mat"
    assert run(str(src), "wider grout").exit_code == 0
    res = CliRunner().invoke(cli, ["edit", str(out), "--undo"])
    assert res.exit_code == 0
    out.write_text(out.read_text().replace(".coat(0.95)", ".coat(0.9)"))  # by hand
    res = CliRunner().invoke(cli, ["edit", str(out), "--undo"])
    assert res.exit_code == 2 and "changed since its last edit" in res.output
    res = run(str(out), "rougher")  # a file with a history is edited in place
    assert res.exit_code == 0, res.output
    assert _versions(out) == [None, None, "rougher"]


def test_never_overwrites_a_foreign_file(tmp_path: Path) -> None:
    src = tmp_path / "tiles.mat"
    src.write_text(TILES)
    mine = tmp_path / "tiles.edited.mat"
    mine.write_text("# my own file\n")
    res = run(str(src), "wider grout")
    assert res.exit_code == 2 and "not written by matloom edit" in res.output
    assert mine.read_text() == "# my own file\n"
    res = run(str(src), "wider grout", "-o", str(tmp_path / "other.mat"))
    assert res.exit_code == 0 and (tmp_path / "other.mat").exists()


def test_refusal_is_one_line_with_parameters(tmp_path: Path) -> None:
    src = tmp_path / "tiles.mat"
    src.write_text(TILES)
    res = run(str(src), "make it fluffy")
    assert res.exit_code == 2
    assert res.output.count("\n") == 1 and "parameters it could change" in res.output
    assert "Traceback" not in res.output
    assert not (tmp_path / "tiles.edited.mat").exists()


def test_python_api(tmp_path: Path) -> None:
    import matloom

    result = matloom.edit(TILES, "darker grout", size=32)
    assert result.report.ok and result.report.changes[0].address == "layer:1.basecolor.base"
    with pytest.raises(ValueError, match="cannot edit"):
        matloom.edit(TILES, "make it sing", size=32)
