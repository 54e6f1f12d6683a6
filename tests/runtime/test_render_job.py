"""The one render job (matloom.runtime): a folder and a memory sink get the same files, the job
refuses what cannot run before any work (naming the field at fault), and the CLI's --preset
choices are the preset registry."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from matloom.io.encode import Encoding
from matloom.io.presets import PRESETS
from matloom.runtime.job import RenderJob, RenderJobError, plan_render
from matloom.runtime.run import evaluate_job, run_render
from matloom.runtime.sinks import FolderSink, MemorySink

PROGRAM = (
    "View(0, 0, 2, 1, unit_m=0.25)\n"
    "Define(n, fBm(octaves=2, base_freq=5, to_01=True))\n"
    "Material(Layer(1).basecolor(120 + n * 50, 60, 40).roughness(0.5 + n * 0.2).height(n * 0.01))\n"
)


def _job(**changes: object) -> RenderJob:
    fields: dict[str, object] = {
        "program": PROGRAM,
        "width": 24,
        "height": 12,
        "name": "m",
        "presets": ("gltf",),
    }
    fields.update(changes)
    return RenderJob(**fields)  # type: ignore[arg-type]


def test_memory_and_folder_sinks_get_the_same_files(tmp_path: Path) -> None:
    job = _job(previews=("preview", "tiled"), encoding=Encoding(bits=16, normals=("gl", "dx")))
    folder = run_render(job, FolderSink(tmp_path / "out"))
    sink = MemorySink()
    memory = run_render(job, sink)
    on_disk = {
        p.relative_to(tmp_path / "out").as_posix(): p.read_bytes()
        for p in sorted((tmp_path / "out").rglob("*"))
        if p.is_file() and not p.name.startswith(".")
    }
    assert sink.files == on_disk
    assert memory.root is None and folder.root == (tmp_path / "out").absolute()
    assert memory.files == folder.files
    assert list(folder.files)[:3] == ["program", "preview", "preview_tiled"]
    assert folder.files["manifest"] == "material.json" and "preset:gltf" in folder.files
    assert memory.manifest == folder.manifest
    assert set(folder.timings) == {"evaluate", "preview", "write", "total"}


def test_notes_come_in_order_and_are_kept(tmp_path: Path) -> None:
    heard: list[str] = []
    result = run_render(_job(unit_m=0.5), MemorySink(), notify=heard.append)
    assert heard == result.notes
    assert heard[0] == "note: omitted noise seeds made explicit from program seed 0"
    assert heard[1].startswith("note: --unit-m 0.5 replaces the program's View unit_m=0.25")


def test_the_text_is_recorded_as_given_unless_the_job_changes_it() -> None:
    seeded = plan_render(_job()).text
    assert seeded is not None and "seed=" in seeded  # omitted seeds made explicit
    assert plan_render(_job(program=seeded)).text == seeded
    tileable = plan_render(_job(program=seeded, tileable=True))
    assert tileable.text is not None and "tileable=True" in tileable.text


def test_the_view_is_widened_for_square_texels() -> None:
    plan = plan_render(_job(width=20, height=20))
    assert plan.view_note is None and plan.view == (0.0, 0.0, 2.0, 1.0)
    wide = plan_render(_job(width=40, height=20, program=PROGRAM.replace("2, 1", "1, 1")))
    assert wide.view == (-0.5, 0.0, 1.5, 1.0) and wide.view_note is not None
    kept = plan_render(_job(width=40, height=20, stretch=True))
    assert kept.view == (0.0, 0.0, 2.0, 1.0)


@pytest.mark.parametrize(
    ("changes", "field", "words"),
    [
        ({"ao_radius": 1e9}, "ao_radius", "texels"),
        ({"unit_m": 1e-12}, "unit_m", "physical size"),
        ({"unit_m": 0.0}, "unit_m", "finite number of metres"),
        ({"program": PROGRAM.replace("0.25", "1e-12")}, "program_unit_m", "physical size"),
        ({"program": "Material(Layer(1).bogus(1))"}, "program", "bogus"),
        ({"presets": ("nope",)}, "presets", "nope"),
        ({"map_names": ("nope",)}, "map_names", "nope"),
        ({"previews": ("nope",)}, "previews", "nope"),
    ],
)
def test_refusals_name_the_field_before_any_work(
    tmp_path: Path, changes: dict[str, object], field: str, words: str
) -> None:
    with pytest.raises(RenderJobError, match=words) as caught:
        run_render(_job(**changes), FolderSink(tmp_path / "out"))
    assert caught.value.field == field
    assert isinstance(caught.value, ValueError)
    assert not (tmp_path / "out").exists()


def test_given_maps_are_not_evaluated_again(tmp_path: Path) -> None:
    job = _job(program=plan_render(_job()).text)  # (given maps, a text is recorded as it is)
    maps = evaluate_job(job)
    first = run_render(job, FolderSink(tmp_path / "a"), maps=maps)
    again = run_render(job, FolderSink(tmp_path / "b"))
    assert "evaluate" not in first.timings and "evaluate" in again.timings
    assert first.manifest["files"] == again.manifest["files"]


def test_cli_preset_choices_are_the_registry() -> None:
    from matloom.cli.engine_cmds import render_cmd
    from matloom.cli.library_cmd import render_entry_cmd

    for command in (render_cmd, render_entry_cmd):
        (option,) = [p for p in command.params if p.name == "presets"]
        assert list(option.type.choices) == list(PRESETS)  # type: ignore[attr-defined]


def test_the_preset_registry_imports_no_writer() -> None:
    code = (
        "import sys, matloom.io.presets as p; "
        "print(sorted(m for m in sys.modules if m.startswith('matloom.io.presets.')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
