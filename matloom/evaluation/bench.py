"""``matloom bench``: the paper's benchmark as a command.

Every prompt x system x run is a cell, content-addressed by (prompt, system settings, seed,
preview size, MatLoom version) and authored through the executor into ``DIR/cells/<key>``;
Blender renders (flat, staged) go to ``DIR/renders/<key>``; scores are cached per cell x metric
(:mod:`.bench_scores`). A rerun (or ``--resume``) skips everything already there. The plan is
kept in ``DIR/bench.json`` so the report can be rebuilt (``bench collect``) without the
prompts file or the config. Outputs: ``results.csv``, ``summary.json``, ``report.html``.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.evaluation.bench_cells import PREVIEW_NAME, PROGRAM_NAME, CellSpec, RenderSpec
from matloom.evaluation.bench_scores import read_all, score_missing
from matloom.evaluation.bench_spec import (
    PAPER_SEEDS,
    BenchInputError,
    BenchPrompt,
    System,
    one_line,
    parse_seeds,
    parse_system,
    read_bench_prompts,
)
from matloom.evaluation.cells import content_key, remove_stale_stages
from matloom.evaluation.executor import Outcome, Progress, Task, make_executor
from matloom.evaluation.metrics.base import Metric, MetricUnavailableError, Sample
from matloom.evaluation.metrics.registry import get_metric, metric_names
from matloom.evaluation.stats import Row
from matloom.io.outdir import OutputFolder

PLAN_NAME = "bench.json"
CELLS_DIR = "cells"
RENDERS_DIR = "renders"
LAYOUTS = ("quick", "flat", "staged")
BLENDER_LAYOUTS = ("flat", "staged")
#: The default metrics: the material metrics that need no weights (those registered here).
DEFAULT_METRICS = ("seams", "pbr", "relight", "size", "authoring")
#: The metric computing all of them at once (used by default when registered).
ALL_MATERIAL = "material"

Say = Callable[[str], None]


@dataclass
class BenchOptions:
    """A bench request (the CLI's flags)."""

    out: Path
    prompts_file: Path | None = None
    systems: Sequence[str] = ()
    runs: int = 3
    seeds: str = ",".join(map(str, PAPER_SEEDS))
    metrics: Sequence[str] | None = None
    #: Options per metric family (``--metric-option judge.profile=NAME``).
    metric_options: dict[str, dict[str, str]] = field(default_factory=dict)
    layouts: Sequence[str] = LAYOUTS
    contrasts: Sequence[str] = ()
    scheduler: str | None = None
    workers: int = 1
    jobs: int = 1
    llm_slots: int = 4
    size: int = 512
    blender_size: int = 512
    #: Cycles samples per Blender render (None: each layout's own, the paper's 64 flat, 160 staged).
    blender_samples: int | None = None
    blender: str | None = None
    config_file: str | None = None
    profile: str | None = None
    resume: bool = False
    resamples: int = 10_000


@dataclass
class BenchOutcome:
    """What a bench run came to."""

    out: Path
    cells: dict[str, int]
    rows: int
    notes: list[str] = field(default_factory=list)
    summary: dict[str, Any] = field(default_factory=dict)


def require_bench_extra() -> None:
    """BenchInputError unless scipy and matplotlib (the ``[bench]`` extra) are importable."""
    import importlib.util

    missing = [m for m in ("scipy", "matplotlib") if importlib.util.find_spec(m) is None]
    if missing:
        raise BenchInputError(
            f"matloom bench needs {' and '.join(missing)}: pip install 'matloom[bench]'"
        )


def _plan(opts: BenchOptions, say: Say) -> tuple[list[BenchPrompt], list[System], dict[str, Any]]:
    from matloom.author.config import ConfigError, load_config_file

    stored = _read_plan(opts.out) if opts.resume else None
    if opts.prompts_file is not None:
        prompts = read_bench_prompts(opts.prompts_file)
    elif stored is not None:
        prompts = [BenchPrompt(**p) for p in stored["prompts"]]
    else:
        raise BenchInputError("give a PROMPTS file (or --resume a bench folder holding one)")
    specs = list(opts.systems) or [
        f"{s['name']}={s['spec']}" for s in (stored or {}).get("systems", [])
    ]
    if not specs:
        raise BenchInputError("give at least one --system NAME=SPEC (e.g. --system lib=library)")
    try:
        data = load_config_file(opts.config_file)
    except ConfigError as err:
        raise BenchInputError(one_line(err)) from None
    systems = [parse_system(s, data, opts.profile) for s in specs]
    names = [s.name for s in systems]
    if len(set(names)) != len(names):
        raise BenchInputError(f"system names must differ: {', '.join(names)}")
    return prompts, systems, stored or {}


def parse_contrasts(given: Sequence[str], names: Sequence[str]) -> list[tuple[str, str]]:
    """``A-B`` contrasts between named systems (default: the first system against each other)."""
    if not given:
        return [(names[0], other) for other in names[1:]]
    pairs = []
    for text in given:
        found = [
            (text[:i], text[i + 1 :])
            for i, ch in enumerate(text)
            if ch == "-" and text[:i] in names and text[i + 1 :] in names
        ]
        if len(found) != 1 or found[0][0] == found[0][1]:
            raise BenchInputError(
                f"--contrast {text!r}: give A-B with two different systems of {', '.join(names)}"
            )
        pairs.append(found[0])
    return pairs


def resolve_metrics(
    names: Sequence[str] | None,
    say: Say,
    options: dict[str, dict[str, str]] | None = None,
) -> tuple[list[Metric], list[str]]:
    """The metrics to score; an unknown name is an error, an unavailable one a note."""
    known = metric_names()
    explicit = names is not None
    if explicit:
        wanted = list(names)
    elif ALL_MATERIAL in known:  # the five families from one evaluation per cell
        wanted = [ALL_MATERIAL]
    else:
        wanted = [m for m in DEFAULT_METRICS if m in known]
    metrics, notes = [], []
    for name in wanted:
        if name.split(":", 1)[0] not in known:
            raise BenchInputError(
                f"unknown metric {name!r} (metrics: {', '.join(known) or 'none'})"
            )
        try:
            metrics.append(get_metric(name, (options or {}).get(name.split(":", 1)[0])))
        except MetricUnavailableError as err:
            note = f"metric {name} skipped: {one_line(err)}"
            notes.append(note)
            say(note)
    return metrics, notes


def cell_key(prompt: str, system: System, seed: int, size: int, version: str) -> str:
    return content_key(prompt, system.identity(), seed, {"preview_size": size}, version)


def run_bench(
    opts: BenchOptions, say: Say = print, on_progress: Callable[[Progress], None] | None = None
) -> BenchOutcome:
    """Author, render, score and report a bench (see the module docstring)."""
    from matloom._version import __version__

    require_bench_extra()
    bad = [layout for layout in opts.layouts if layout not in LAYOUTS]
    if bad:
        raise BenchInputError(f"--layouts: unknown {', '.join(bad)} (choose {', '.join(LAYOUTS)})")
    prompts, systems, stored = _plan(opts, say)
    seeds = (
        parse_seeds(opts.seeds, opts.runs)
        if opts.prompts_file or not stored
        else (tuple(stored["seeds"]))
    )
    pairs = parse_contrasts(opts.contrasts, [s.name for s in systems])
    unknown = sorted(set(opts.metric_options) - set(metric_names()))
    if unknown:
        raise BenchInputError(f"--metric-option: unknown metric {', '.join(unknown)}")
    metrics, notes = resolve_metrics(opts.metrics, say, opts.metric_options)
    _check_folder(opts.out)
    cells = []
    specs: dict[str, tuple[CellSpec, bool]] = {}
    for p in prompts:
        for system in systems:
            for run, seed in enumerate(seeds):
                key = cell_key(p.text, system, seed, opts.size, __version__)
                cells.append(
                    {"prompt_id": p.id, "system": system.name, "run": run, "seed": seed, "key": key}
                )
                config = None
                if system.config is not None:
                    config = system.config.model_copy(update={"seed": seed}).model_dump(mode="json")
                spec = CellSpec(
                    p.text, system.name, system.spec, seed, opts.size, __version__, config
                )
                specs.setdefault(key, (spec, system.uses_llm))
    plan = {
        "format": "matloom-bench",
        "version": 1,
        "matloom_version": __version__,
        "prompts": [vars(p) for p in prompts],
        "systems": [{"name": s.name, "spec": s.spec} for s in systems],
        "seeds": list(seeds),
        "size": opts.size,
        "contrasts": [list(p) for p in pairs],
        "cells": cells,
    }
    with OutputFolder(opts.out) as folder:
        folder.write_bytes(PLAN_NAME, json.dumps(plan, indent=1).encode("utf-8"))
        root = Path(folder.path)
        remove_stale_stages(root / CELLS_DIR, list(specs))  # the folder is locked: all dead
        from matloom.evaluation.bench_cells import author_cell

        tasks = [
            Task(key, author_cell, (str(root / CELLS_DIR), key, spec), uses_llm=llm)
            for key, (spec, llm) in specs.items()
        ]
        executor = make_executor(
            opts.scheduler, workers=opts.workers, jobs=opts.jobs, llm_slots=opts.llm_slots
        )
        try:
            outcomes = executor.run(tasks, root / CELLS_DIR, on_progress)
            failed = [o for o in outcomes if not o.ok]
            for o in failed[:5]:
                say(f"cell {o.key} failed: {o.error}")
            notes += _render(opts, root, [o for o in outcomes if o.ok], executor, say)
        finally:
            executor.close()
        notes += _score(root, metrics, prompts, opts, say)
        summary = write_report(root, folder, notes=notes, resamples=opts.resamples)
    counts = summary["cells"]
    return BenchOutcome(opts.out, counts, summary["rows"], notes, summary)


def _read_plan(out: Path) -> dict[str, Any] | None:
    path = out / PLAN_NAME
    if not path.is_file():
        raise BenchInputError(f"--resume: {out} holds no bench ({PLAN_NAME} is missing)")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        raise BenchInputError(f"{path} is not a bench plan: {one_line(err)}") from None
    if not isinstance(data, dict) or data.get("format") != "matloom-bench":
        raise BenchInputError(f"{path} is not a bench plan")
    return data


def _check_folder(out: Path) -> None:
    if out.exists() and not out.is_dir():
        raise BenchInputError(f"-o {out} is a file; give a folder")
    if out.is_dir() and any(out.iterdir()) and not (out / PLAN_NAME).is_file():
        raise BenchInputError(f"-o {out} is not empty and holds no bench; choose another folder")


def _render(
    opts: BenchOptions, root: Path, done: list[Outcome], executor: Any, say: Say
) -> list[str]:
    """Blender renders of the finished cells in the layouts asked for, when Blender is here."""
    wanted = [layout for layout in opts.layouts if layout in BLENDER_LAYOUTS]
    if not wanted or not done:
        return []
    from matloom.blender.runner import BlenderError, check_version, find_blender

    try:
        check_version(find_blender(opts.blender))
    except BlenderError as err:
        note = f"Blender layouts {', '.join(wanted)} skipped: {one_line(err)}"
        say(note)
        return [note]
    from matloom.evaluation.bench_cells import render_cell

    samples = f"s{opts.blender_samples}" if opts.blender_samples else ""
    tasks = [
        Task(
            f"{o.key}.{layout}{opts.blender_size}{samples}",
            render_cell,
            (
                str(root / RENDERS_DIR),
                f"{o.key}.{layout}{opts.blender_size}{samples}",
                RenderSpec(
                    str(root / CELLS_DIR / o.key),
                    layout,
                    opts.blender_size,
                    opts.blender,
                    opts.blender_samples,
                ),
            ),
        )
        for o in done
        for layout in wanted
    ]
    remove_stale_stages(root / RENDERS_DIR, [t.key for t in tasks])
    failed = [o for o in executor.run(tasks, root / RENDERS_DIR) if not o.ok]
    if failed:
        note = f"{len(failed)} Blender renders failed (first: {failed[0].error})"
        say(note)
        return [note]
    return []


def cell_images(root: Path, key: str, size: int | None = None) -> dict[str, Path]:
    """The images of a finished cell by layout: the quick preview, and Blender renders."""
    images = {"quick": root / CELLS_DIR / key / PREVIEW_NAME}
    renders = root / RENDERS_DIR
    if renders.is_dir():
        for folder in renders.glob(f"{key}.*"):
            for layout in BLENDER_LAYOUTS:
                if (
                    folder.name.startswith(f"{key}.{layout}")
                    and (folder / f"{layout}.png").is_file()
                ):
                    images[layout] = folder / f"{layout}.png"
    return {k: v for k, v in images.items() if v.is_file()}


def _samples(root: Path, prompts: Sequence[BenchPrompt], opts: BenchOptions) -> list[Sample]:
    plan = json.loads((root / PLAN_NAME).read_text(encoding="utf-8"))
    seen: set[str] = set()
    out = []
    for c in plan["cells"]:
        key = c["key"]
        folder = root / CELLS_DIR / key
        if key in seen or not folder.is_dir():
            continue
        seen.add(key)
        summary = json.loads((folder / "cell.json").read_text(encoding="utf-8"))
        images = {k: v for k, v in cell_images(root, key).items() if k in opts.layouts}
        record = {
            k: summary[k]
            for k in ("seconds", "prompt_tokens", "completion_tokens", "model_calls", "author")
            if k in summary
        }
        out.append(
            Sample(
                id=key,
                prompt=summary["prompt"],
                program=(folder / PROGRAM_NAME).read_text(encoding="utf-8"),
                images=images,
                size=opts.size,
                record=record,
            )
        )
    return out


def _score(
    root: Path,
    metrics: Sequence[Metric],
    prompts: Sequence[BenchPrompt],
    opts: BenchOptions,
    say: Say,
) -> list[str]:
    if not metrics:
        return []
    samples = _samples(root, prompts, opts)
    notes = []
    for metric in metrics:
        try:
            n = score_missing(root, metric, samples)
        except MetricUnavailableError as err:
            notes.append(f"metric {metric.name} skipped: {one_line(err)}")
            say(notes[-1])
            continue
        except Exception as err:  # noqa: BLE001 - one metric's failure must not lose the bench
            notes.append(f"metric {metric.name} failed: {type(err).__name__}: {one_line(err)}")
            say(notes[-1])
            continue
        if n:
            say(f"scored {n} cells with {metric.name}")
    return notes


def write_report(
    root: Path, folder: OutputFolder, *, notes: Sequence[str] = (), resamples: int = 10_000
) -> dict[str, Any]:
    """Rebuild ``results.csv``, ``summary.json`` and ``report.html`` from the plan, the cells
    and every cached score; return the summary."""
    from matloom.evaluation.report import (
        ReportInput,
        report_html,
        results_csv,
        summarize,
        summary_json,
    )

    plan = _read_plan(root)
    assert plan is not None
    prompts = {p["id"]: (p["text"], p["source"]) for p in plan["prompts"]}
    scores = read_all(root)
    rows: list[Row] = []
    images: dict[tuple[str, str, int], Path] = {}
    done = failed = 0
    for c in plan["cells"]:
        key = c["key"]
        if not (root / CELLS_DIR / key).is_dir():
            failed += 1
            continue
        done += 1
        found = cell_images(root, key)
        quick = found.get("flat") or found.get("quick")
        if quick is not None:
            images[(c["prompt_id"], c["system"], c["run"])] = quick
        source = prompts[c["prompt_id"]][1]
        for metric, value in sorted(scores.get(key, {}).items()):
            rows.append(
                Row(c["prompt_id"], source, c["system"], c["run"], c["seed"], metric, value)
            )
    data = ReportInput(
        prompts=prompts,
        systems=[s["name"] for s in plan["systems"]],
        seeds=tuple(plan["seeds"]),
        rows=rows,
        pairs=[(a, b) for a, b in plan["contrasts"]],
        images=images,
        cells={"total": len(plan["cells"]), "done": done, "missing": failed},
        notes=list(notes),
        resamples=resamples,
    )
    summary = summarize(data)
    folder.write_bytes("results.csv", results_csv(rows))
    folder.write_bytes("summary.json", summary_json(summary))
    folder.write_bytes("report.html", report_html(data, summary))
    return summary
