"""Lazily loaded subcommands: a missing command module reads as "No such command"; a missing
dependency of a command is one line naming the module and the extra to install."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner

from matloom.cli import main as cli_main

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def fake_command(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):  # noqa: ANN201
    """``fake_command(body)``: register ``matloom fake`` as a new module holding ``body``."""
    monkeypatch.syspath_prepend(str(tmp_path))

    def make(body: str) -> str:
        module = f"matloom_test_fake_cmd_{len(list(tmp_path.iterdir()))}"
        (tmp_path / f"{module}.py").write_text(
            "import click\n" + body + "\n@click.command()\ndef cmd() -> None:\n    pass\n"
        )
        monkeypatch.setitem(cli_main.COMMANDS, "fake", f"{module}:cmd")
        monkeypatch.delitem(sys.modules, module, raising=False)
        return module

    return make


def _run(*args: str):  # noqa: ANN202
    return CliRunner().invoke(cli_main.cli, list(args))


def _one_line(output: str) -> str:
    assert "Traceback" not in output, output
    lines = [line for line in output.splitlines() if line.strip()]
    assert len(lines) == 1, output
    return lines[0]


def test_unknown_command_and_missing_command_module_are_no_such_command(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    res = _run("no-such-command")
    assert res.exit_code == 2 and "No such command 'no-such-command'" in res.output
    monkeypatch.setitem(cli_main.COMMANDS, "fake", "matloom.cli.no_such_module:cmd")
    res = _run("fake")
    assert res.exit_code == 2 and "No such command 'fake'" in res.output
    monkeypatch.setitem(cli_main.COMMANDS, "fake", "matloom_no_such_package.cmds:cmd")
    assert "No such command 'fake'" in _run("fake").output


def test_missing_optional_dependency_names_the_module_and_the_extra(
    fake_command, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "open_clip", None)  # import raises ModuleNotFoundError
    fake_command("import open_clip")
    res = _run("fake")
    assert res.exit_code == 1
    assert _one_line(res.output) == (
        "Error: `matloom fake` needs the module 'open_clip', which is not installed: "
        "install the extra: pip install 'matloom[clip]'"
    )
    assert "fake" not in _run("--help").output  # left out of the command list, help works


def test_missing_other_dependency_is_one_line(fake_command) -> None:
    fake_command("import matloom_test_no_such_dependency.sub")
    res = _run("fake")
    assert res.exit_code == 1
    line = _one_line(res.output)
    assert "needs the module 'matloom_test_no_such_dependency'" in line
    assert "reinstall matloom" in line


def test_broken_import_inside_a_dependency_is_one_line(fake_command) -> None:
    fake_command("from matloom.cli.main import no_such_name")
    res = _run("fake")
    assert res.exit_code == 1
    assert "could not be loaded (cannot import name 'no_such_name'" in _one_line(res.output)


def test_a_working_fake_command_loads(fake_command) -> None:
    fake_command("")
    assert _run("fake").exit_code == 0
    assert "fake" in _run("--help").output


def test_every_extra_named_is_an_extra_of_the_project() -> None:
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"
    ]
    assert set(cli_main.EXTRAS.values()) <= set(extras)
    assert {"fast", "llm", "interop", "clip"} <= set(cli_main.EXTRAS.values())
