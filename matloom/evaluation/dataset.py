"""``matloom dataset``: a training set of materials built on the executor (docs/datasets.md).

Sources (:mod:`.dataset_sources`) give programs; each becomes K seed variants (variant 0 the
program with its omitted seeds made explicit, variants 1..K-1 every noise seed redrawn by
:func:`matloom.lang.seeds.seed_variants` from ``--seed``) at each size. Each (program text,
seed, size, unit_m, MatLoom version) is one content-addressed sample cell under ``samples/``
(:mod:`.dataset_sample`), so two sources that give the same program make one sample and a
rerun (``--resume``) skips finished cells. The driver then writes ``metadata.jsonl`` (and
``metadata.parquet`` with pyarrow), ``dropped.jsonl``, ``failed.jsonl`` and ``dataset.json``
as one batch of the output folder.

The output folder is a MatLoom :class:`~matloom.io.outdir.OutputFolder` (locked, foreign files
never replaced); ``samples/`` belongs to the dataset whose ``dataset.json`` MatLoom wrote there.
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.evaluation.cells import content_key, remove_stale_stages
from matloom.evaluation.dataset_filter import Condition, drop_reason, parse_conditions
from matloom.evaluation.dataset_sample import build_sample
from matloom.evaluation.dataset_sources import SourceProgram
from matloom.evaluation.executor import Executor, Outcome, ProgressCallback, Task
from matloom.io.outdir import OutputError, OutputFolder

MANIFEST = "dataset.json"
SAMPLES = "samples"
#: Metric families measured by default (material metrics, no weights).
DEFAULT_METRICS: tuple[str, ...] = ("seams", "pbr", "size")
FORMAT = ("matloom-dataset", 1)


class DatasetError(ValueError):
    """A dataset that cannot be built as asked; the message is one line."""


@dataclass(frozen=True)
class DatasetOptions:
    """How each source becomes samples."""

    variants: int = 1
    sizes: tuple[int, ...] = (512,)
    seed: int = 0
    filters: tuple[str, ...] = ()
    metrics: tuple[str, ...] = DEFAULT_METRICS
    backend: str = "auto"

    @property
    def conditions(self) -> tuple[Condition, ...]:
        return parse_conditions(self.filters)


@dataclass
class PlannedSample:
    """One sample to build: its key, the program variant and where it came from."""

    key: str
    source: SourceProgram
    text: str
    variant: int
    size: int
    options: DatasetOptions
    #: Other sources that gave the same sample (deduplicated into this one).
    duplicates: list[str] = field(default_factory=list)

    def spec(self) -> dict[str, Any]:
        """What the worker needs (plain data, picklable)."""
        s, o = self.source, self.options
        return {
            "text": self.text,
            "size": self.size,
            "unit_m": s.unit_m,
            "source": s.source,
            "source_id": s.source_id,
            "prompt": s.prompt,
            "entry": s.entry,
            "category": s.category,
            "variant": self.variant,
            "variant_seed": o.seed if self.variant else None,
            "labels": dict(s.labels),
            "metrics": list(o.metrics),
            "filters": [(c.column, c.op, c.value) for c in o.conditions],
            "backend": o.backend,
        }


@dataclass
class DatasetSummary:
    """What a build came to."""

    out: Path
    planned: int
    kept: int
    dropped: int
    failed: int
    skipped: int
    duplicates: int
    notes: list[str]


def canonical_text(text: str, where: str) -> str:
    """The program with its omitted noise seeds made explicit (program seed 0), as text."""
    from matloom.lang.api import parse
    from matloom.lang.diagnostics import ProgramError
    from matloom.lang.printer import format_program
    from matloom.lang.seeds import canonicalize_seeds

    try:
        program = parse(text)
    except ProgramError as err:
        first = next((d for d in err.diagnostics if d.is_error), None)
        message = first.message if first else str(err)
        raise DatasetError(f"{where}: not a valid program ({message})") from None
    return format_program(canonicalize_seeds(program, 0))


def plan_samples(sources: Sequence[SourceProgram], options: DatasetOptions) -> list[PlannedSample]:
    """Every sample of ``sources`` (variants x sizes), deduplicated by content key."""
    from matloom._version import __version__
    from matloom.lang.seeds import seed_variants

    if options.variants < 1:
        raise DatasetError("--variants must be at least 1")
    planned: dict[str, PlannedSample] = {}
    for src in sources:
        base = canonical_text(src.text, f"{src.source} {src.source_id}")
        texts = seed_variants(base, options.variants - 1, options.seed)
        texts += [base] * (options.variants - len(texts))  # a program without noise seeds
        for variant, text in enumerate(texts):
            for size in options.sizes:
                key = content_key("matloom-dataset-sample", text, 0, size, src.unit_m, __version__)
                if key in planned:
                    planned[key].duplicates.append(f"{src.source}:{src.source_id}#{variant}")
                    continue
                planned[key] = PlannedSample(key, src, text, variant, size, options)
    return list(planned.values())


def build_dataset(
    out: str | Path,
    sources: Sequence[SourceProgram],
    options: DatasetOptions,
    executor: Executor,
    *,
    resume: bool = False,
    on_progress: ProgressCallback | None = None,
    notify: Callable[[str], None] | None = None,
) -> DatasetSummary:
    """Build (or, with ``resume``, continue) the dataset of ``sources`` in ``out``."""
    conditions = options.conditions
    plan = plan_samples(sources, options)
    with OutputFolder(out) as folder:
        _claim(folder, resume, options)
        root = folder.path / SAMPLES
        root.mkdir(exist_ok=True)
        _reopen_dropped(root, plan, conditions)
        remove_stale_stages(root, [p.key for p in plan])  # a killed earlier run's half cells
        tasks = [Task(p.key, build_sample, (str(root), p.key, p.spec())) for p in plan]
        outcomes = executor.run(tasks, root, on_progress)
        return _finish(folder, plan, outcomes, options, conditions, notify)


def _claim(folder: OutputFolder, resume: bool, options: DatasetOptions) -> None:
    """Refuse a folder whose ``samples/`` is not this dataset's; record the build's start."""
    manifest = folder.path / MANIFEST
    ours = manifest.is_file() and folder.owns(MANIFEST)
    if manifest.exists() and not ours:
        folder.check_writable([MANIFEST])  # raises: a foreign dataset.json
    if ours and not resume:
        raise OutputError(
            f"{folder.path} already holds a dataset: pass --resume to continue it, "
            "or choose another -o"
        )
    samples = folder.path / SAMPLES
    if not ours and (samples.exists() or samples.is_symlink()):
        raise OutputError(
            f"{samples} exists and was not made by matloom dataset; MatLoom never writes "
            "into it: move it or choose another -o"
        )
    if ours:
        return
    start = {"format": FORMAT[0], "format_version": FORMAT[1], "status": "building"}
    start["options"] = _options_json(options)
    folder.write_bytes(MANIFEST, _json_bytes(start), group="dataset")


def _reopen_dropped(root: Path, plan: Sequence[PlannedSample], conds: Sequence[Condition]) -> None:
    """A sample an earlier filter dropped (its cell holds only ``cell.json``) that these
    filters keep is built again: its cell is removed."""
    for sample in plan:
        cell = root / sample.key
        row = _read_row(cell)
        if row is None or not row.get("dropped"):
            continue
        if drop_reason(row, conds) is None and [p.name for p in cell.iterdir()] == ["cell.json"]:
            shutil.rmtree(cell)


def _read_row(cell: Path) -> dict[str, Any] | None:
    try:
        return json.loads((cell / "cell.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _finish(
    folder: OutputFolder,
    plan: Sequence[PlannedSample],
    outcomes: Sequence[Outcome],
    options: DatasetOptions,
    conditions: Sequence[Condition],
    notify: Callable[[str], None] | None,
) -> DatasetSummary:
    """Gather the rows and write the metadata files and ``dataset.json`` as one batch."""
    root = folder.path / SAMPLES
    kept: list[dict[str, Any]] = []
    dropped: list[dict[str, Any]] = []
    failed: list[dict[str, Any]] = []
    notes: dict[str, None] = {}
    for sample, outcome in zip(plan, outcomes, strict=True):
        if not outcome.ok:
            failed.append(
                {
                    "key": sample.key,
                    "source_id": sample.source.source_id,
                    "variant": sample.variant,
                    "size": sample.size,
                    "error": outcome.error,
                }
            )
            continue
        row = outcome.result if outcome.result is not None else _read_row(root / sample.key)
        if row is None:
            failed.append({"key": sample.key, "error": "the cell has no readable cell.json"})
            continue
        row = dict(row)
        row["duplicates"] = list(sample.duplicates)
        notes.update(dict.fromkeys(row.pop("notes", [])))
        reason = row.get("dropped") or drop_reason(row, conditions)
        if reason:  # dropped now, or by an earlier, stricter filter
            dropped.append({**row, "dropped": reason})
        else:
            row.pop("dropped", None)
            row["path"] = f"{SAMPLES}/{sample.key}"
            kept.append(row)
    for note in notes:
        if notify is not None:
            notify(f"note: {note}")
    summary = DatasetSummary(
        folder.path,
        len(plan),
        len(kept),
        len(dropped),
        len(failed),
        sum(1 for o in outcomes if o.skipped),
        sum(len(p.duplicates) for p in plan),
        list(notes),
    )
    with folder.batch("dataset", marker=MANIFEST) as staging:
        _write_jsonl(staging / "metadata.jsonl", kept)
        _write_jsonl(staging / "dropped.jsonl", dropped)
        _write_jsonl(staging / "failed.jsonl", failed)
        parquet = write_parquet(staging / "metadata.parquet", kept)
        if not parquet and notify is not None:
            notify(
                "note: pyarrow is not installed: metadata.parquet not written "
                "(pip install 'matloom[dask]')"
            )
        manifest = {
            "format": FORMAT[0],
            "format_version": FORMAT[1],
            "status": "finished",
            "options": _options_json(options),
            "samples": summary.kept,
            "dropped": summary.dropped,
            "failed": summary.failed,
            "duplicates": summary.duplicates,
            "planned": summary.planned,
            "metadata": ["metadata.jsonl"] + (["metadata.parquet"] if parquet else []),
            "notes": list(notes),
        }
        (staging / MANIFEST).write_bytes(_json_bytes(manifest))
    return summary


def _options_json(options: DatasetOptions) -> dict[str, Any]:
    from matloom._version import __version__

    return {
        "variants": options.variants,
        "sizes": list(options.sizes),
        "seed": options.seed,
        "filters": list(options.filters),
        "metrics": list(options.metrics),
        "matloom_version": __version__,
    }


def _json_bytes(data: Any) -> bytes:
    return (json.dumps(data, indent=2, sort_keys=True) + "\n").encode("utf-8")


def _write_jsonl(path: Path, rows: Sequence[dict[str, Any]]) -> None:
    lines = [json.dumps(row, sort_keys=True, ensure_ascii=False) for row in rows]
    path.write_text("".join(line + "\n" for line in lines), encoding="utf-8")


def write_parquet(path: Path, rows: Sequence[dict[str, Any]]) -> bool:
    """The rows as a Parquet table (lists as JSON text); False when pyarrow is missing."""
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        return False
    columns: dict[str, None] = {}
    for row in rows:
        columns.update(dict.fromkeys(row))
    flat = [
        {
            c: (json.dumps(v) if isinstance(v, list | dict) else v)
            for c, v in ((c, row.get(c)) for c in columns)
        }
        for row in rows
    ]
    table = pa.Table.from_pylist(flat) if flat else pa.table({})
    pq.write_table(table, path)
    return True
