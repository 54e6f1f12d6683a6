"""Every shell command block of the README and docs/*.md runs: each ``matloom ...`` line goes
through the real command line (a subprocess) in a temporary folder and must exit 0.

A block is a command block when one of its lines starts with ``matloom`` (its info string may
be empty, ``sh``, ``bash``, ``console`` or ``shell``). The files it names that exist in the
repository (``matloom/examples/bricks_quickstart.mat``) are copied into the folder first. A
block that needs what a test machine lacks says so in its info string, and only then is it
left out: ```` ```sh no-run: needs Blender ````. The reason must name a network server, a
model or Blender.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = sorted([ROOT / "README.md", *(ROOT / "docs").glob("*.md")])
_BLOCK = re.compile(r"^```([^\n]*)\n(.*?)^```", re.MULTILINE | re.DOTALL)
_SHELLS = {"", "sh", "bash", "console", "shell"}
#: what a block may be left out for
_REASONS = ("network", "server", "model", "blender")


def _commands(body: str) -> list[list[str]]:
    """The argument lists of a block's lines (``\\``-continued lines joined, comments and a
    leading ``$ `` prompt dropped)."""
    out = []
    for line in body.replace("\\\n", " ").splitlines():
        line = line.strip().removeprefix("$ ")
        if line and not line.startswith("#"):
            out.append(shlex.split(line, comments=True))
    return out


def command_blocks(path: Path) -> list[tuple[int, str, list[list[str]]]]:
    """(line, info string, commands) of each command block of ``path``."""
    text = path.read_text(encoding="utf-8")
    found = []
    for match in _BLOCK.finditer(text):
        info, body = match.group(1).strip(), match.group(2)
        if info.split(" ", 1)[0] not in _SHELLS:
            continue
        if not any(
            ln.strip().removeprefix("$ ").startswith("matloom ") for ln in body.splitlines()
        ):
            continue
        found.append((text[: match.start()].count("\n") + 1, info, _commands(body)))
    return found


def _blocks() -> list[tuple[Path, int, str, list[list[str]]]]:
    return [(p, line, info, cmds) for p in DOCS for line, info, cmds in command_blocks(p)]


def _ids(block: tuple[Path, int, str, list[list[str]]]) -> str:
    return f"{block[0].name}:{block[1]}"


def _copy_inputs(argv: list[str], folder: Path) -> None:
    for arg in argv:
        source = ROOT / arg
        if not arg.startswith("-") and source.is_file() and ROOT in source.resolve().parents:
            target = folder / arg
            if not target.exists():
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(source, target)


def test_the_docs_have_command_blocks() -> None:
    blocks = _blocks()
    assert any(p.name == "README.md" for p, *_ in blocks)
    assert sum(1 for *_, info, _ in blocks if "no-run" not in info) >= 3


@pytest.mark.parametrize("block", _blocks(), ids=_ids)
def test_command_block_runs(block: tuple[Path, int, str, list[list[str]]], tmp_path: Path) -> None:
    path, line, info, commands = block
    where = f"{path.name}:{line}"
    if "no-run" in info:
        reason = info.split("no-run", 1)[1].strip(" :")
        assert any(word in reason.lower() for word in _REASONS), (
            f"{where}: a block is left out only when it needs a network server, a model or "
            f"Blender, and its info string says which (got {info!r})"
        )
        pytest.skip(f"{where}: {reason}")
    home = tmp_path / "home"
    home.mkdir()
    env = {
        **os.environ,
        "PYTHONPATH": str(ROOT),
        "HOME": str(home),  # no user config: the commands see what a new user sees
        "XDG_CONFIG_HOME": str(home / ".config"),
        "MATLOOM_BACKEND": "numpy",  # the same maps; no kernel compilation in the test
    }
    for argv in commands:
        assert argv[0] == "matloom", f"{where}: a command block runs matloom only: {argv}"
        _copy_inputs(argv, tmp_path)
        result = subprocess.run(
            [sys.executable, "-m", "matloom", *argv[1:]],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=600,
            check=False,
        )
        shown = f"{where}: {shlex.join(argv)}\n{result.stdout[-2000:]}\n{result.stderr[-2000:]}"
        assert result.returncode == 0, shown
        assert "Traceback" not in result.stderr, shown
