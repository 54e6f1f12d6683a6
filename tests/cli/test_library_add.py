"""`matloom library add` and `matloom generate --library`: a program or a generate run becomes a
user library entry (checked, tileability measured, parameters labelled), which search and the
offline author then use (docs/library.md, "Your own library")."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from matloom.author.records import RecordStore
from matloom.cli.main import cli
from matloom.library import load_entry
from matloom.library.labels import entry_labels
from matloom.library.user import ENV

#: a tileable program with one colour slot, a roughness and a name-only scalar
TILEABLE = """View(0, 0, 4, 4)
Define(glaze_r, 40)
Define(glaze_g, 120)
Define(glaze_b, 200)
Define(grout_r, 220)
Define(grout_g, 220)
Define(grout_b, 215)
Define(rough, 0.35)
Define(speckle_amount, 0.2)
Define(spots, fBm(octaves=2, base_freq=4, to_01=True, seed=3))
Material(
  Layer(1).basecolor(glaze_r * (1 - speckle_amount * spots), glaze_g, glaze_b).roughness(rough)
    .height(spots * 0.1),
  Layer(0.1).basecolor(grout_r, grout_g, grout_b).roughness(0.9).height(0)
)
"""
#: a gradient across the View: it cannot repeat
GRADIENT = """View(0, 0, 1, 1)
Material(Layer(1).basecolor(X() * 255, 30, 30).roughness(0.5).height(0))
"""
FAST = ["--critique-size", "48", "--select-size", "48", "--sweep-size", "32"]
FAST += ["--export-size", "32", "--stats-grid", "32", "--sweep-jobs", "1"]


def run(*args: str, env: dict[str, str] | None = None) -> Result:
    return CliRunner().invoke(cli, list(args), env=env)


def one_line_error(res: Result) -> str:
    assert res.exit_code != 0
    assert (
        "Traceback" not in res.output
        and res.exception is None
        or isinstance(res.exception, SystemExit)
    )
    lines = [ln for ln in res.output.strip().splitlines() if ln.startswith("Error:")]
    assert len(lines) == 1, res.output
    return lines[0]


@pytest.fixture(autouse=True)
def _no_env_library(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(ENV, raising=False)


@pytest.fixture
def program(tmp_path: Path) -> Path:
    path = tmp_path / "glaze.mat"
    path.write_text(TILEABLE, encoding="utf-8")
    return path


def add(program: Path, lib: Path, *extra: str, name: str = "zorblax-glaze") -> Result:
    return run(
        "library", "add", str(program), "--name", name, "--tags", "zorblax,glaze,tile",
        "--to", str(lib), *extra,
    )  # fmt: skip


def test_add_writes_a_checked_labelled_entry_that_search_finds_first(
    program: Path, tmp_path: Path
) -> None:
    lib = tmp_path / "lib"
    res = add(program, lib, "--category", "tiles", "--size-m", "0.6")
    assert res.exit_code == 0, res.output
    path = lib / "zorblax-glaze.mat"
    assert str(path) in res.output and "tileable: yes" in res.output
    entry = load_entry(path)
    assert entry.tileable and entry.category == "tiles" and entry.size_m == 0.6
    assert entry.colours == ("glaze", "grout") and entry.roles == {"grout": "grout"}
    assert entry.scalars == {"rough": "roughness", "speckle_amount": "other"}
    labels = entry_labels(entry)
    assert labels["define:glaze"] == "glaze colour" and labels["define:grout"] == "grout colour"
    assert labels["define:speckle_amount"] == "speckle amount"
    view = entry.program.splitlines()[0]  # made tileable (its corner may move off a seam)
    assert view.startswith("View(") and view.endswith(", tileable=True)")
    check = run("library", "check", "--library", str(lib))
    assert check.exit_code == 0 and "1 of 1 passed" in check.output, check.output
    found = run("library", "search", "zorblax", "glaze", "tile", "--library", str(lib))
    lines = [ln for ln in found.output.splitlines() if ln.strip()[:2].rstrip(".").isdigit()]
    assert "zorblax-glaze" in lines[0] and len(lines) > 1  # ranked with the built-in tiles
    assert str(lib.resolve()) in lines[0]


def test_tileability_is_measured_honestly(tmp_path: Path) -> None:
    program = tmp_path / "gradient.mat"
    program.write_text(GRADIENT, encoding="utf-8")
    res = add(program, tmp_path / "lib", "--category", "paper", name="red-gradient")
    assert res.exit_code == 0, res.output
    assert "tileable: no (X() is used non-periodically" in res.output
    entry = load_entry(tmp_path / "lib" / "red-gradient.mat")
    assert not entry.tileable and "tileable=True" not in entry.program
    assert entry.colours == () and "size_m 1 (the View has no unit_m" in res.output


def test_warnings_are_printed_and_unused_defines_are_no_slots(tmp_path: Path) -> None:
    program = tmp_path / "unused.mat"
    program.write_text(
        "View(0, 0, 1, 1)\nDefine(unused, 3)\nDefine(rough, 0.4)\n"
        "Material(Layer(1).basecolor(200, 30, 30).roughness(rough).height(0))\n",
        encoding="utf-8",
    )
    res = add(program, tmp_path / "lib", "--category", "paper", name="plain-red")
    assert res.exit_code == 0, res.output
    assert "warning W001: Define 'unused' is never used" in res.output
    assert load_entry(tmp_path / "lib" / "plain-red.mat").scalars == {"rough": "roughness"}


def test_the_category_is_guessed_from_the_closest_entry(program: Path, tmp_path: Path) -> None:
    res = add(program, tmp_path / "lib", "--description", "Glazed ceramic wall tiles")
    assert res.exit_code == 0, res.output
    assert load_entry(tmp_path / "lib" / "zorblax-glaze.mat").category in ("tiles", "ceramic")
    assert "--category to choose" in res.output


def test_refusals(program: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    lib = tmp_path / "lib"
    bad = tmp_path / "bad.mat"
    bad.write_text("View(0, 0, 1, 1)\nMaterial(Layer(1).basecolor(nope))\n", encoding="utf-8")
    assert "error E" in one_line_error(add(bad, lib))
    assert not lib.exists()
    assert add(program, lib).exit_code == 0
    first = (lib / "zorblax-glaze.mat").read_text(encoding="utf-8")
    assert "already exists; pass --force" in one_line_error(add(program, lib))
    res = add(program, lib, "--force", "--description", "Replaced")
    assert res.exit_code == 0, res.output
    assert (lib / "zorblax-glaze.mat").read_text(encoding="utf-8") != first
    for name in ("Zorblax", "../escape", "a_b", "-x", "x" * 65):
        assert "--name" in one_line_error(add(program, lib, name=name))
    no_target = run("library", "add", str(program), "--name", "x", "--tags", "y")
    assert f"give --to DIR (or --library DIR, or set {ENV})" in one_line_error(no_target)
    neither = run("library", "add", "--name", "x", "--tags", "y", "--to", str(lib))
    assert neither.exit_code == 2 and "PROGRAM or --from-run" in neither.output
    not_a_run = run(
        "library", "add", "--from-run", str(tmp_path), "--name", "x", "--tags", "y",
        "--to", str(lib),
    )  # fmt: skip
    assert "no record.json" in one_line_error(not_a_run)


def test_the_target_is_the_first_library_then_the_variable(program: Path, tmp_path: Path) -> None:
    first, env_dir = tmp_path / "first", tmp_path / "env"
    first.mkdir()
    res = add_no_to(program, "--library", str(first), env={ENV: str(env_dir)})
    assert res.exit_code == 0, res.output
    assert (first / "zorblax-glaze.mat").is_file()
    res = add_no_to(program, env={ENV: str(env_dir)})
    assert res.exit_code == 0, res.output
    assert (env_dir / "zorblax-glaze.mat").is_file()


def add_no_to(program: Path, *extra: str, env: dict[str, str] | None = None) -> Result:
    return run(
        "library", "add", str(program), "--name", "zorblax-glaze", "--tags", "zorblax",
        "--category", "tiles", *extra, env=env,
    )  # fmt: skip


def test_generate_with_a_user_library_picks_the_matching_entry(
    program: Path, tmp_path: Path
) -> None:
    lib = tmp_path / "lib"
    assert add(program, lib, "--category", "tiles").exit_code == 0
    out = tmp_path / "run"
    res = run("generate", "zorblax glaze tiles", "-o", str(out), "--library", str(lib), *FAST)
    assert res.exit_code == 0, res.output
    record = RecordStore.load(out).record
    assert record.settings.library_dirs == (str(lib.resolve()),)
    assert "entry: zorblax-glaze [tiles]" in (record.library_explanation or "")
    without = run("generate", "zorblax glaze tiles", "-o", str(tmp_path / "plain"), *FAST)
    assert without.exit_code == 0
    assert "zorblax-glaze" not in json.dumps(
        RecordStore.load(tmp_path / "plain").record.programs[0].authored
    )
    with_env = run(
        "generate", "zorblax glaze tiles", "-o", str(tmp_path / "env"), *FAST, env={ENV: str(lib)}
    )
    assert with_env.exit_code == 0
    assert "zorblax-glaze" in (RecordStore.load(tmp_path / "env").record.library_explanation or "")


def test_generate_with_a_bad_user_library_is_one_line(tmp_path: Path) -> None:
    lib = tmp_path / "lib"
    lib.mkdir()
    (lib / "broken.mat").write_text("# ---\n# description = 1\n", encoding="utf-8")
    res = run("generate", "red brick", "-o", str(tmp_path / "run"), "--library", str(lib))
    assert "broken.mat" in one_line_error(res)
    assert not (tmp_path / "run").exists()


def test_a_generate_run_is_accepted_into_a_user_library(tmp_path: Path) -> None:
    out = tmp_path / "run"
    prompt = "weathered teak deck boards"
    assert run("generate", prompt, "-o", str(out), *FAST).exit_code == 0
    lib = tmp_path / "lib"
    res = run(
        "library", "add", "--from-run", str(out), "--name", "our-teak-deck",
        "--tags", "teak,deck,house", "--to", str(lib),
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    entry = load_entry(lib / "our-teak-deck.mat")
    assert entry.description == prompt
    assert entry.tileable and entry.category == "wood"
    final = RecordStore.load(out).record.final
    assert final is not None and "View(" in entry.program
    assert entry.colours and "roughness" in entry.scalars.values()
    found = run("library", "search", "teak", "deck", "house", "--library", str(lib))
    assert "our-teak-deck" in found.output.splitlines()[0]
