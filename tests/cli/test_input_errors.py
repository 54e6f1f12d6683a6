"""Every CLI input error is one ``Error:`` line on stderr and a non-zero exit, never a traceback
(issue "Reliability" #4, #11, #13, #16).

Bad option values are click usage errors (exit 2) naming the option and the allowed range;
programs past the float range are diagnostics (exit 2). Most cases run in-process through
click's runner; the reproducers of the issue also run as a user runs them (``python -m``).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from matloom.cli.main import cli

REPO = Path(__file__).resolve().parents[2]
PROGRAM = "View(0, 0, 10, 10)\nMaterial(Layer(1).basecolor(200, 0, 0).height(fBm(seed=3)))\n"
HUGE = "9" * 350


@pytest.fixture
def program(tmp_path: Path) -> Path:
    path = tmp_path / "p.mat"
    path.write_text(PROGRAM, encoding="utf-8")
    return path


def invoke(*args: str | Path) -> Result:
    return CliRunner().invoke(cli, [str(a) for a in args])


def assert_one_line_error(result: Result, *words: str, exit_code: int = 2) -> str:
    """Exit ``exit_code``, no exception escaped, exactly one ``Error:`` line containing
    ``words``; returns that line."""
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(
        result.exception
    )
    assert result.exit_code == exit_code, result.output
    assert "Traceback" not in result.output
    errors = [line for line in result.stderr.splitlines() if line.startswith("Error:")]
    assert len(errors) == 1, result.stderr
    for word in words:
        assert word in errors[0], errors[0]
    return errors[0]


# ---------------------------------------------------------------------------- #11: tracebacks
@pytest.mark.parametrize("value", ["-1", "nan", "inf", "-inf", "abc"])
def test_render_ao_radius_must_be_finite_and_non_negative(
    program: Path, tmp_path: Path, value: str
) -> None:
    result = invoke("render", program, "-o", tmp_path / "out", "--size", "8", "--ao-radius", value)
    assert_one_line_error(result, "--ao-radius")
    assert not (tmp_path / "out").exists()


def test_render_ao_radius_wider_than_the_largest_image_is_refused(
    program: Path, tmp_path: Path
) -> None:
    out = tmp_path / "out"
    result = invoke("render", program, "-o", out, "--size", "8", "--ao-radius", "1e300")
    assert_one_line_error(result, "--ao-radius", "8192 texels")


@pytest.mark.parametrize("grid", ["0", "-3", "1"])
def test_stats_grid_below_two_is_refused(program: Path, grid: str) -> None:
    assert_one_line_error(invoke("stats", program, "--grid", grid), "--grid", "2<=x<=8192")


@pytest.mark.parametrize("light", ["nan,nan", "inf,0", "0,inf", "1", "1,2,3", "a,b", "0,91"])
def test_preview_light_must_be_two_finite_angles(program: Path, tmp_path: Path, light: str) -> None:
    result = invoke("preview", program, "-o", tmp_path / "p.png", "--size", "8", "--light", light)
    assert_one_line_error(result, "--light")


def test_sweep_size_zero_is_a_usage_error_not_a_zero_division(program: Path) -> None:
    assert_one_line_error(invoke("sweep", program, "-k", "2", "--size", "0"), "--size")


def test_sweep_unknown_scorer_is_one_line(program: Path) -> None:
    result = invoke(
        "sweep", program, "-k", "1", "--size", "8", "--scorer", "nosuch", "--prompt", "x"
    )
    assert_one_line_error(result, "nosuch", exit_code=1)


# ---------------------------------------------------------------------------- #13: nonsense sizes
@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--width", "0", "--height", "16"], "--width"),
        (["--width", "16", "--height", "-1"], "--height"),
        (["--size", "0"], "--size"),
        (["--size", "9000"], "--size"),
    ],
)
def test_render_sizes_must_be_1_to_8192(
    program: Path, tmp_path: Path, args: list[str], option: str
) -> None:
    result = invoke("render", program, "-o", tmp_path / "out", *args)
    assert_one_line_error(result, option, "1<=x<=8192")


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--size", "0"], "--size"),
        (["--tile", "0"], "--tile"),
        (["--tile", "9"], "--tile"),
        (["--size", "2000", "--tile", "8"], "--tile"),  # a 16000-pixel image
        (["--backend", "cuda"], "--backend"),
    ],
)
def test_preview_sizes_tiles_and_backend(
    program: Path, tmp_path: Path, args: list[str], option: str
) -> None:
    result = invoke("preview", program, "-o", tmp_path / "p.png", *args)
    assert_one_line_error(result, option)
    assert not (tmp_path / "p.png").exists()


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["-k", "-5"], "--variants"),
        (["-k", "20000"], "--variants"),
        (["-k", "2", "--top", "0"], "--top"),
        (["-k", "2", "--jobs", "-1"], "--jobs"),
    ],
)
def test_sweep_counts(program: Path, args: list[str], option: str) -> None:
    assert_one_line_error(invoke("sweep", program, "--size", "8", *args), option)


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--count", "0"], "--count"),
        (["--count", "-1"], "--count"),
        (["--layers", "0"], "--layers"),
        (["--layers", "100000"], "--layers"),
        (["--defines", "-1"], "--defines"),
    ],
)
def test_random_counts(args: list[str], option: str) -> None:
    assert_one_line_error(invoke("random", *args), option)


def test_seeds_negative_variants(program: Path) -> None:
    assert_one_line_error(invoke("seeds", program, "-k", "-1"), "--variants", "0<=x<=10000")


def test_valid_values_still_work(program: Path, tmp_path: Path) -> None:
    result = invoke("preview", program, "-o", tmp_path / "p.png", "--size", "8", "--light", "10,20")
    assert result.exit_code == 0, result.output
    result = invoke("render", program, "-o", tmp_path / "r", "--size", "8", "--ao-radius", "0.5")
    assert result.exit_code == 0, result.output
    assert invoke("random", "--count", "2", "--layers", "1").exit_code == 0


# ---------------------------------------------------------------------------- gallery inputs
@pytest.mark.parametrize(
    ("content", "words"),
    [
        ("{}", "empty object"),
        ("[1, 2]", "prompt 0"),
        ('"x"', "a string"),
        ('{"prompts": 5}', "a number"),
        ('[{"id": "a"}]', '"text"'),
        ('[{"text": "   "}]', "empty"),
        ('[{"text": "oak", "id": [1]}]', '"id"'),
        ('[{"text": "oak", "source": 3}]', '"source"'),
        ('[{"id": "a", "text": "x"}, {"id": "a", "text": "y"}]', "same id 'a'"),
        ("[]", "no prompts"),
        ("nope", "not valid JSON"),
        ("[" + "9" * 5000 + "]", "not usable JSON"),
    ],
)
def test_gallery_prompt_file_errors(tmp_path: Path, content: str, words: str) -> None:
    prompts = tmp_path / "prompts.json"
    prompts.write_text(content, encoding="utf-8")
    result = invoke("gallery", prompts, "-o", tmp_path / "g")
    assert_one_line_error(result, "PROMPTS_FILE", words)
    assert not (tmp_path / "g").exists()


@pytest.mark.parametrize(
    ("args", "option"), [(["--size", "1"], "--size"), (["--columns", "0"], "--columns")]
)
def test_gallery_option_ranges(tmp_path: Path, args: list[str], option: str) -> None:
    prompts = tmp_path / "prompts.json"
    prompts.write_text(json.dumps(["oak planks"]), encoding="utf-8")
    assert_one_line_error(invoke("gallery", prompts, "-o", tmp_path / "g", *args), option)


# ---------------------------------------------------------------------------- as a user runs it
def run_cli(*args: str | Path) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(REPO), env.get("PYTHONPATH")) if p)
    return subprocess.run(
        [sys.executable, "-m", "matloom", *map(str, args)],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
        check=False,
    )


def test_reproducers_in_a_real_process(tmp_path: Path) -> None:
    """#4: a 350-digit integer; #16: an overflowing View; #11: a negative AO radius."""
    huge = tmp_path / "huge.mat"
    huge.write_text(f"Material(Layer(1).height({HUGE}))\n", encoding="utf-8")
    view = tmp_path / "view.mat"
    view.write_text("View(-1e308, -1e308, 1e308, 1e308)\nMaterial(Layer(1))\n", encoding="utf-8")
    for args, code in [
        (("check", huge), "E003"),
        (("fmt", huge), "E003"),
        (("render", huge, "-o", tmp_path / "a", "--size", "8"), "E003"),
        (("check", view), "E061"),
        (("render", view, "-o", tmp_path / "b", "--size", "8"), "E061"),
    ]:
        result = run_cli(*args)
        assert result.returncode == 2, (args, result.stderr)
        assert "Traceback" not in result.stderr and code in result.stderr, result.stderr
    result = run_cli(
        "render", huge.with_name("none.mat"), "-o", tmp_path / "c", "--ao-radius", "-1"
    )
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert [line for line in result.stderr.splitlines() if line.startswith("Error:")] == [
        "Error: Invalid value for '--ao-radius': -1 is not a finite number in the range x>=0"
    ]
