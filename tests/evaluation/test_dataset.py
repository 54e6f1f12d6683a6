"""`matloom dataset` on the inline executor: samples, variants, masks, parameters, the same
bytes as `matloom render`, resume, deduplication, filters and the output-folder rules."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from matloom.cli.main import cli
from matloom.evaluation.dataset import DatasetOptions, build_dataset, plan_samples
from matloom.evaluation.dataset_filter import FilterError, drop_reason, parse_condition
from matloom.evaluation.dataset_sources import SourceProgram, folder_sources, library_sources
from matloom.evaluation.executor import InlineExecutor
from matloom.io.outdir import OutputError
from matloom.io.png import read_png

ENTRIES = ["brick-herringbone-path", "coir-doormat"]
SIZE = 32


def _rows(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.read_text().splitlines()]


def _cells(out: Path) -> list[Path]:
    return sorted(p for p in (out / "samples").iterdir())


def test_filter_parsing() -> None:
    cond = parse_condition(" pbr.plausible >= 0.8 ")
    assert (cond.column, cond.op, cond.value) == ("pbr.plausible", ">=", 0.8)
    assert parse_condition("seam_ratio.max<1.5").holds(1.2)
    assert not parse_condition("seam_ratio.max<1.5").holds(float("nan"))
    for bad in ("pbr.plausible", "pbr.plausible >= high", "1x>=2", "a=>1", "a>=nan"):
        with pytest.raises(FilterError):
            parse_condition(bad)
    conds = [parse_condition("a>=1"), parse_condition("b!=0"), parse_condition("tileable==1")]
    assert drop_reason({"a": 1, "b": 2, "tileable": True}, conds) is None
    assert drop_reason({"a": 0.5, "tileable": False}, conds) == (
        "a>=1 (was 0.5); b!=0 (no value); tileable==1 (was 0)"
    )


def test_dataset_inline_end_to_end(tmp_path: Path) -> None:
    out = tmp_path / "ds"
    sources = library_sources(ENTRIES)
    options = DatasetOptions(variants=2, sizes=(SIZE,))
    summary = build_dataset(out, sources, options, InlineExecutor())
    assert (summary.planned, summary.kept, summary.failed, summary.skipped) == (4, 4, 0, 0)
    rows = _rows(out / "metadata.jsonl")
    assert [(r["entry"], r["variant"]) for r in rows] == [
        (ENTRIES[0], 0),
        (ENTRIES[0], 1),
        (ENTRIES[1], 0),
        (ENTRIES[1], 1),
    ]
    assert len(_cells(out)) == 4
    for row in rows:
        cell = out / row["path"]
        assert row["size"] == SIZE and row["unit_m"] > 0 and row["tileable"] is True
        assert set(row["files"]) == {
            p.relative_to(cell).as_posix()
            for p in cell.rglob("*")
            if p.is_file() and p.name != "cell.json"
        }
        assert {
            "basecolor.png",
            "normal_gl.png",
            "roughness.png",
            "height.exr",
            "material.json",
            "material.mat",
            "preview.png",
            "params.json",
        } <= set(row["files"])
        assert row["seam_ratio.max"] == max(
            v
            for k, v in row.items()
            if k.startswith("seam_ratio.")
            and k != "seam_ratio.max"
            and k != "seam_ratio.tiles"
            and v is not None
        )
        assert row["seam_ratio.max"] < 2.0  # tileable library entries repeat
    # a variant is the program with its seeds redrawn: same text but for seed literals
    first, second = (out / rows[0]["path"] / "material.mat", out / rows[1]["path"] / "material.mat")
    import re

    strip = re.compile(r"seed=-?\d+")
    assert first.read_text() != second.read_text()
    assert strip.sub("", first.read_text()) == strip.sub("", second.read_text())
    maps = [read_png(out / r["path"] / "basecolor.png") for r in rows[:2]]
    assert not np.array_equal(*maps)
    # params.json is `matloom params --json` of the entry (with its labels)
    entry_file = next(Path("matloom/library/entries").glob(f"*/{ENTRIES[0]}.mat"))
    res = CliRunner().invoke(cli, ["params", "--json", str(entry_file)])
    want = json.loads(res.stdout)
    got = json.loads((out / rows[0]["path"] / "params.json").read_text())
    assert [p["address"] for p in got] == [p["address"] for p in want]
    assert [p["label"] for p in got] == [p["label"] for p in want]
    manifest = json.loads((out / "dataset.json").read_text())
    assert manifest["status"] == "finished" and manifest["samples"] == 4


def test_masks_compose_to_the_coverage(tmp_path: Path) -> None:
    """The visible shares of the layers sum to the composite coverage; each alpha mask is the
    layer's own coverage."""
    from matloom.engine.evaluate import evaluate

    text = (
        "Material(\n"
        "  Layer(1).basecolor(127, 127, 127),\n"
        "  Layer(fBm(base_freq=4, to_01=True, seed=3)).basecolor(255, 0, 0),\n"
        "  Layer(0.25).basecolor(0, 0, 255)\n"
        ")\n"
    )
    src = tmp_path / "progs"
    src.mkdir()
    (src / "three.mat").write_text(text)
    out = tmp_path / "ds"
    build_dataset(
        out, folder_sources(src), DatasetOptions(sizes=(SIZE,), metrics=()), InlineExecutor()
    )
    (row,) = _rows(out / "metadata.jsonl")
    masks = out / row["path"] / "masks"
    assert sorted(p.name for p in masks.iterdir()) == [
        f"{kind}_{i:02d}.png" for kind in ("alpha", "visible") for i in (1, 2, 3)
    ]
    read = {p.stem: read_png(p).astype(np.float64) / 65535 for p in masks.iterdir()}
    assert np.allclose(read["alpha_01"], 1) and np.allclose(read["alpha_03"], 0.25, atol=1e-4)
    noise = read["alpha_02"]
    assert noise.std() > 0.05  # the noise layer's own coverage varies
    assert np.allclose(read["visible_03"], 0.25, atol=1e-4)
    assert np.allclose(read["visible_02"], noise * 0.75, atol=2e-4)
    total = read["visible_01"] + read["visible_02"] + read["visible_03"]
    coverage = evaluate(text, SIZE, SIZE).alpha
    assert np.allclose(total, coverage, atol=5e-4)


def test_same_bytes_as_render(tmp_path: Path) -> None:
    out = tmp_path / "ds"
    build_dataset(
        out,
        library_sources(ENTRIES[:1]),
        DatasetOptions(sizes=(SIZE,), metrics=()),
        InlineExecutor(),
    )
    (row,) = _rows(out / "metadata.jsonl")
    cell = out / row["path"]
    rendered = tmp_path / "render"
    res = CliRunner().invoke(
        cli,
        [
            "render",
            str(cell / "material.mat"),
            "-o",
            str(rendered),
            "--size",
            str(SIZE),
            "--unit-m",
            str(row["unit_m"]),
        ],
    )
    assert res.exit_code == 0, res.output
    names = [n for n in row["files"] if n.endswith((".png", ".exr")) and "/" not in n]
    assert len(names) >= 10
    for name in names:
        assert (cell / name).read_bytes() == (rendered / name).read_bytes(), name
    ours = json.loads((cell / "material.json").read_text())
    theirs = json.loads((rendered / "material.json").read_text())
    assert ours["files"] == theirs["files"]  # every file's SHA-256


def test_resume_dedup_filter_and_folder_rules(tmp_path: Path) -> None:
    out = tmp_path / "ds"
    entry = library_sources(ENTRIES[:1])
    same = SourceProgram("folder", "copy.mat", entry[0].text, unit_m=entry[0].unit_m)
    options = DatasetOptions(sizes=(SIZE,), metrics=("seams",))
    assert len(plan_samples([*entry, same], options)) == 1  # one program, one sample
    summary = build_dataset(out, [*entry, same], options, InlineExecutor())
    assert (summary.kept, summary.duplicates) == (1, 1)
    (row,) = _rows(out / "metadata.jsonl")
    assert row["duplicates"] == ["folder:copy.mat#0"]
    stamp = (out / row["path"] / "basecolor.png").stat().st_mtime_ns
    with pytest.raises(OutputError, match="already holds a dataset"):
        build_dataset(out, entry, options, InlineExecutor())
    # a stricter filter on resume: the cell is skipped (not rebuilt) and the row dropped
    strict = DatasetOptions(sizes=(SIZE,), metrics=("seams",), filters=("seam_ratio.max<=0.01",))
    again = build_dataset(out, entry, strict, InlineExecutor(), resume=True)
    assert (again.skipped, again.kept, again.dropped) == (1, 0, 1)
    assert (out / row["path"] / "basecolor.png").stat().st_mtime_ns == stamp
    (gone,) = _rows(out / "dropped.jsonl")
    assert gone["dropped"].startswith("seam_ratio.max<=0.01 (was ")
    assert _rows(out / "metadata.jsonl") == []
    # a new sample that fails the filter keeps only its row
    other = library_sources(ENTRIES[1:])
    third = build_dataset(out, other, strict, InlineExecutor(), resume=True)
    assert third.dropped == 1 and third.skipped == 0
    (dropped,) = _rows(out / "dropped.jsonl")
    assert [p.name for p in (out / "samples" / dropped["key"]).iterdir()] == ["cell.json"]
    # without the filter it is built again (its reopened cell), the other one skipped
    fourth = build_dataset(out, [*entry, *other], options, InlineExecutor(), resume=True)
    assert (fourth.kept, fourth.skipped, fourth.dropped) == (2, 1, 0)
    assert (out / "samples" / dropped["key"] / "basecolor.png").is_file()


def test_foreign_samples_folder_is_refused(tmp_path: Path) -> None:
    out = tmp_path / "mine"
    (out / "samples").mkdir(parents=True)
    (out / "samples" / "notes.txt").write_text("mine")
    with pytest.raises(OutputError, match="not made by matloom dataset"):
        build_dataset(
            out, library_sources(ENTRIES[:1]), DatasetOptions(sizes=(SIZE,)), InlineExecutor()
        )
    assert (out / "samples" / "notes.txt").read_text() == "mine"
    assert not (out / "dataset.json").exists()


def test_cli_dataset_inline(tmp_path: Path) -> None:
    progs = tmp_path / "progs"
    progs.mkdir()
    (progs / "a.mat").write_text("Material(Layer(1).basecolor(50, 100, 150).roughness(0.5))\n")
    out = tmp_path / "ds"
    args = [
        "dataset",
        "--programs",
        str(progs),
        "--size",
        "16",
        "--size",
        "24",
        "--scheduler",
        "inline",
        "-o",
        str(out),
    ]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    assert "2 samples in" in res.stderr
    rows = _rows(out / "metadata.jsonl")
    assert sorted(r["size"] for r in rows) == [16, 24]
    assert read_png(out / rows[0]["path"] / "basecolor.png").shape[:2] == (rows[0]["size"],) * 2
    res = CliRunner().invoke(cli, [*args, "--resume"])
    assert res.exit_code == 0 and "2 samples in" in res.stderr and "(2 already there" in res.stderr
    for bad, message in (
        (["dataset", "-o", str(out)], "give a source"),
        ([*args, "--filter", "pbr.plausible>>1"], "is not a number"),
        (
            [
                "dataset",
                "--entries",
                "no-such-entry",
                "--scheduler",
                "inline",
                "-o",
                str(tmp_path / "x"),
            ],
            "no library entry 'no-such-entry'",
        ),
    ):
        res = CliRunner().invoke(cli, bad)
        assert res.exit_code != 0 and message in res.output, res.output
        assert "Traceback" not in res.output


def test_dataset_takes_entries_from_a_user_library(tmp_path: Path) -> None:
    """``--library DIR`` adds a user library's entries to the sources, as for ``generate``."""
    program = tmp_path / "teal.mat"
    program.write_text("Material(Layer(1).basecolor(20, 128, 128).roughness(0.3))\n")
    mine = tmp_path / "mine"
    added = CliRunner().invoke(
        cli,
        ["library", "add", str(program), "--name", "house-teal", "--tags", "teal,plastic",
         "--description", "house teal plastic", "--to", str(mine)],
    )  # fmt: skip
    assert added.exit_code == 0, added.output
    out = tmp_path / "ds"
    args = ["dataset", "--entries", "house-teal", "--size", "16", "--scheduler", "inline"]
    res = CliRunner().invoke(cli, [*args, "-o", str(out)])
    assert res.exit_code != 0 and "house-teal" in res.output  # not in the built-in library
    res = CliRunner().invoke(cli, [*args, "--library", str(mine), "-o", str(out)])
    assert res.exit_code == 0, res.output
    rows = _rows(out / "metadata.jsonl")
    assert [r["entry"] for r in rows] == ["house-teal"]
    assert "basecolor(20, 128, 128)" in (out / rows[0]["path"] / "material.mat").read_text()
