"""``matloom check`` and ``matloom render --tileable`` on tileable programs with extreme values
(issue "Reliability, third pass" #7): a valid result or the project's diagnostics, never a
traceback.

Sizes and frequencies that give more cells per View period than a lattice can wrap (or a count
past the float range), and Scales that put the View's periods past the float range, are valid
programs: check warns W009 (they do not repeat with the View) and render writes the maps. An
invalid value (a non-finite integer) is an error diagnostic and exit 2. The registry-wide fuzz
is tests/engine/test_fuzz_tileable.py.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from matloom.cli.main import cli

TILEABLE = "View(0, 0, 1, 1, tileable=True)"
PLAIN = "View(0, 0, 2, 1)"

#: Fields that are valid but cannot repeat with the View (W009), with the View they are in.
NOT_TILEABLE = [
    (TILEABLE, "Bricks(brick_width=1e-320)"),
    (TILEABLE, 'Bricks(brick_height=5e-324, axis="column")'),
    (TILEABLE, "Bricks(offset=1e308)"),
    (TILEABLE, 'Bricks(offset=-1.7976931348623157e308, output="cell_value", seed=4)'),
    (TILEABLE, "Scale(Bricks(), 1e-320, 1)"),
    (TILEABLE, "Scale(fBm(seed=2), 1, 5e-324)"),
    ("View(0, 0, 1e30, 1, tileable=True)", "Hash(X() * 1e300, Y(), seed=3)"),
    (TILEABLE, "Weave(base_freq_y=1e308)"),
    (TILEABLE, "fBm(base_freq=1e308, seed=1)"),
    (TILEABLE, "fBm(base_freq=1e6, lacunarity=1e300, octaves=3, seed=1)"),
    (TILEABLE, "Worley(base_freq=1e300, seed=1)"),
    (TILEABLE, "Worley(base_freq_x=3, base_freq_y=-1e30, seed=1)"),
    (TILEABLE, "Tile(Fill(Ellipse(0, 0, 0.3, 0.3)), 1e-320, 1, seed=5)"),
    (TILEABLE, "Tile(Fill(Ellipse(0, 0, 0.3, 0.3)), 0.5, 0.5, offset=1e308, seed=5)"),
]


def invoke(*args: str | Path) -> Result:
    return CliRunner().invoke(cli, [str(a) for a in args])


def write(tmp_path: Path, view: str, field: str) -> Path:
    path = tmp_path / "p.mat"
    path.write_text(f"{view}\nMaterial(Layer(1).basecolor(90, 60, 40).height({field}))\n")
    return path


def assert_no_traceback(result: Result, exit_code: int) -> None:
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(
        result.exception
    )
    assert "Traceback" not in result.output
    assert result.exit_code == exit_code, result.output


@pytest.mark.parametrize(("view", "field"), NOT_TILEABLE)
def test_check_warns_that_it_cannot_repeat(tmp_path: Path, view: str, field: str) -> None:
    result = invoke("check", write(tmp_path, view, field))
    assert_no_traceback(result, 0)
    assert "W009" in result.stderr


@pytest.mark.parametrize(("view", "field"), NOT_TILEABLE)
def test_render_tileable_writes_the_maps(tmp_path: Path, view: str, field: str) -> None:
    out = tmp_path / "out"
    program = write(tmp_path, view.replace(", tileable=True", ""), field)
    result = invoke("render", program, "-o", out, "--size", "8", "--tileable")
    assert_no_traceback(result, 0)
    assert "W009" in result.stderr
    manifest = json.loads((out / "material.json").read_text())
    assert manifest["maps"]


@pytest.mark.parametrize("field", ["Weave(over=(2 ** 1024))", "Bricks(brick_width=0)"])
def test_an_invalid_value_is_a_diagnostic(tmp_path: Path, field: str) -> None:
    program = write(tmp_path, TILEABLE, field)
    result = invoke("check", program)
    assert_no_traceback(result, 2)
    assert "error E05" in result.stderr
    result = invoke("render", write(tmp_path, PLAIN, field), "-o", tmp_path / "o", "--tileable")
    assert_no_traceback(result, 2)
    assert not (tmp_path / "o").exists()
