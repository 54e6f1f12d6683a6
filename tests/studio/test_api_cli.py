"""``matloom studio``'s command line and workspace choice (no server started here)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from matloom.cli.main import cli


def test_without_the_extra_the_command_says_what_to_install(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(sys.modules, "uvicorn", None)  # import uvicorn -> ImportError
    result = CliRunner().invoke(cli, ["studio", "--no-browser"])
    assert result.exit_code == 1
    assert "pip install 'matloom[studio]'" in result.output
    assert len(result.output.strip().splitlines()) == 1 and "Traceback" not in result.output


def test_bad_targets_get_one_line(tmp_path: Path) -> None:
    pytest.importorskip("starlette", reason="the studio needs the [studio] extra (starlette)")
    pytest.importorskip("uvicorn", reason="the studio needs the [studio] extra (uvicorn)")
    notes = tmp_path / "notes.txt"
    notes.write_text("x")
    for target, words in ((tmp_path / "missing.mat", "no such"), (notes, "not a program")):
        result = CliRunner().invoke(cli, ["studio", str(target), "--no-browser"])
        assert result.exit_code == 1 and words in result.output, result.output


def test_workspaces(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from matloom.studio.workspace import DEMO_FOLDER, Workspace

    monkeypatch.chdir(tmp_path)
    ws = Workspace.open(None)  # no argument: ./matloom-studio/ with a copy of the demo
    assert ws.root == (tmp_path / DEMO_FOLDER).resolve() and ws.opened
    copy = ws.root / ws.opened
    copy.write_text("# mine\nMaterial(Layer(1))\n")
    assert Workspace.open(None).opened == ws.opened
    assert copy.read_text().startswith("# mine")  # an edited copy is kept
    folder = Workspace.open(str(ws.root))
    assert folder.root == ws.root and folder.opened == ws.opened
    one = Workspace.open(str(copy))
    assert one.root == ws.root and one.opened == copy.name
    empty = tmp_path / "empty"
    empty.mkdir()
    assert Workspace.open(str(empty)).opened is None


@pytest.mark.parametrize("host", ["0.0.0.0", "::"])
def test_listening_on_every_address_is_refused_in_one_line(
    host: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["studio", "--host", host, "--no-browser"])
    assert result.exit_code != 0
    assert "every address" in result.output and len(result.output.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []  # no demo workspace made
