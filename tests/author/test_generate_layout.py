"""`generate` installs its final material in the folder layout `render` writes, through the run
folder's staged, never-deleting writer."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner, Result

from author.conftest import FAST_FLAGS
from matloom.author.records import validate_record_file
from matloom.cli.main import cli
from matloom.io.outdir import INDEX_NAME

RUN_FILES = {"record.json", INDEX_NAME}


def invoke(*args: str) -> Result:
    return CliRunner().invoke(cli, list(args))


def material_files(folder: Path) -> set[str]:
    return {
        p.relative_to(folder).as_posix()
        for p in folder.rglob("*")
        if p.is_file() and p.name not in RUN_FILES and not p.name.startswith(".")
    }


def test_generate_and_render_write_the_same_layout(tmp_path: Path) -> None:
    run = tmp_path / "run"
    run.mkdir()
    (run / "notes.txt").write_text("mine")
    result = invoke("generate", "oak planks", "-o", str(run), "--scorer", "none", *FAST_FLAGS)
    assert result.exit_code == 0, result.stderr
    rendered = tmp_path / "rendered"
    size = FAST_FLAGS[FAST_FLAGS.index("--export-size") + 1]
    again = invoke("render", str(run / "material.mat"), "-o", str(rendered), "--size", size)
    assert again.exit_code == 0, again.stderr

    assert material_files(run) - {"notes.txt"} == material_files(rendered)
    assert not (run / "maps").exists() and (run / "notes.txt").read_text() == "mine"
    ours = json.loads((run / "material.json").read_text())
    theirs = json.loads((rendered / "material.json").read_text())
    assert sorted(ours["files"]) == sorted(theirs["files"])
    assert [m["file"] for m in ours["maps"]] == [m["file"] for m in theirs["maps"]]
    assert (run / "material.mat").read_bytes() == (rendered / "material.mat").read_bytes()
    assert (run / "preview.png").read_bytes() == (rendered / "preview.png").read_bytes()
    record = validate_record_file(run / "record.json")
    assert record.final.files["manifest"] == "material.json"
    assert record.final.files["basecolor"] == "basecolor.png"


def test_a_foreign_map_file_stops_the_run_before_any_work(tmp_path: Path) -> None:
    run = tmp_path / "run"
    run.mkdir()
    (run / "basecolor.png").write_bytes(b"an artist's texture")
    result = invoke("generate", "oak planks", "-o", str(run), "--scorer", "none", *FAST_FLAGS)
    assert result.exit_code == 1 and "basecolor.png" in result.stderr
    assert "Traceback" not in result.stderr and "unexpected" not in result.stderr
    assert (run / "basecolor.png").read_bytes() == b"an artist's texture"
    assert not (run / "record.json").exists()
