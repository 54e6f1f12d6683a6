"""``matloom generate --blender-layouts``: the final material is rendered in Blender's layouts
into the run folder and recorded; a Blender failure is a recorded warning, not a lost run."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path


def _generate(
    env: dict[str, str], out: Path, blender: Path | None, *extra: str
) -> subprocess.CompletedProcess[str]:
    env = dict(env)
    if blender is not None:
        env["MATLOOM_BLENDER"] = str(blender)
    return subprocess.run(
        [sys.executable, "-m", "matloom", "generate", "red brick wall", "-o", str(out),
         "--quiet", "--blender-size", "32", *extra],
        capture_output=True, text=True, env=env, timeout=300,
    )  # fmt: skip


def test_final_material_rendered_in_both_layouts(
    tmp_path: Path, fake_blender: Callable[..., Path], cli_environment: dict[str, str]
) -> None:
    run = _generate(
        cli_environment, tmp_path / "run", fake_blender(), "--blender-layouts", "flat,staged"
    )
    assert run.returncode == 0, run.stderr
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert record["settings"]["blender_layouts"] == ["flat", "staged"]
    assert record["blender"]["files"] == ["blender/flat.png", "blender/staged.png"]
    assert record["blender"]["error"] is None
    for name in ("flat", "staged"):
        assert (tmp_path / "run" / "blender" / f"{name}.png").read_bytes()[
            :8
        ] == b"\x89PNG\r\n\x1a\n"


def test_missing_blender_is_a_recorded_warning(
    tmp_path: Path, cli_environment: dict[str, str]
) -> None:
    run = _generate(
        cli_environment, tmp_path / "run", tmp_path / "no-such-blender", "--blender-layouts", "both"
    )
    assert run.returncode == 0, run.stderr
    assert "Blender renders skipped" in run.stderr and "Traceback" not in run.stderr
    record = json.loads((tmp_path / "run" / "record.json").read_text())
    assert record["blender"]["error"] and record["blender"]["files"] == []
    assert (tmp_path / "run" / "material.json").is_file()


def test_unknown_layout_is_a_usage_error(tmp_path: Path, cli_environment: dict[str, str]) -> None:
    run = _generate(cli_environment, tmp_path / "run", None, "--blender-layouts", "flat,orbit")
    assert run.returncode == 2 and "unknown layout 'orbit'" in run.stderr
    assert not (tmp_path / "run").exists()
