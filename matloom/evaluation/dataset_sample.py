"""One dataset sample, built on a worker: :func:`build_sample` is the executor task.

A sample is one content-addressed cell ``samples/<key>/`` written through
:func:`~matloom.evaluation.cells.commit_cell` (staged, renamed into place once):

* the files ``matloom render`` writes for the program at the sample's size, byte for byte
  (the maps, ``material.json``, ``material.mat``, ``preview.png``), made by the same
  :class:`~matloom.runtime.job.RenderJob` and :func:`~matloom.runtime.run.run_render`;
* ``params.json``: the exposed parameters (what ``matloom params --json`` prints; a library
  entry's with its front matter's labels);
* ``masks/alpha_NN.png`` (16-bit grey): layer NN's own coverage (its ``alpha``, 1-based, bottom
  layer first), and ``masks/visible_NN.png`` (16-bit grey): its share of the composite,
  ``alpha_NN * prod(1 - alpha_above)`` (the weights the "over" rule gives its channels);
* ``cell.json``: the metadata row (prompt, entry, seed, size, unit_m, tileable, seam ratios,
  material metrics, files).

A sample that fails a ``--filter`` condition keeps only ``cell.json`` (its row and the reason
it was dropped), so a rerun does not build it again.
"""

from __future__ import annotations

import json
import math
import shutil
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from matloom.evaluation.cells import commit_cell
from matloom.evaluation.dataset_filter import Condition, drop_reason

#: The metadata row's columns besides the metrics, in order.
BASE_COLUMNS: tuple[str, ...] = (
    "key",
    "source",
    "source_id",
    "prompt",
    "entry",
    "category",
    "variant",
    "variant_seed",
    "seed",
    "size",
    "unit_m",
    "tileable",
    "layers",
)


def build_sample(root: str, key: str, spec: dict[str, Any]) -> dict[str, Any]:
    """The executor task: write sample ``key`` under ``root`` (see the module docstring) and
    return its row. ``spec`` is a :meth:`PlannedSample.spec
    <matloom.evaluation.dataset.PlannedSample.spec>`."""
    return commit_cell(Path(root), key, lambda stage: write_sample(stage, key, spec))


def render_job(spec: dict[str, Any]):  # noqa: ANN201 - a RenderJob
    """The render job of a sample: what ``matloom render material.mat --size N`` runs."""
    from matloom.runtime.job import RenderJob

    size = int(spec["size"])
    return RenderJob(
        spec["text"],
        size,
        size,
        unit_m=spec.get("unit_m"),
        previews=("preview",),
        backend=spec.get("backend", "auto"),
    )


def write_sample(stage: Path, key: str, spec: dict[str, Any]) -> dict[str, Any]:
    """Write one sample's files into ``stage``; its metadata row."""
    from matloom.runtime.job import plan_render
    from matloom.runtime.run import run_render
    from matloom.runtime.sinks import MemorySink

    job = render_job(spec)
    sink = MemorySink()
    result = run_render(job, sink)
    for rel, data in sink.files.items():
        target = stage / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    plan = plan_render(job)
    manifest = result.manifest
    row: dict[str, Any] = {name: spec.get(name) for name in BASE_COLUMNS}
    row.update(
        key=key,
        seed=0,
        tileable=bool(manifest.get("tileable", False)),
        layers=len(plan.program.layers) if plan.program is not None else 0,
    )
    if row["unit_m"] is None:
        row["unit_m"] = _manifest_unit_m(manifest)
    row.update(_seam_columns(result.maps))
    params = _params_json(spec)
    (stage / "params.json").write_text(params, encoding="utf-8")
    row["params"] = len(json.loads(params))
    _write_masks(stage / "masks", plan, job)
    notes: list[str] = []
    row.update(_metric_columns(spec, stage, result.maps, notes))
    conditions = [Condition(*c) for c in spec.get("filters", ())]
    reason = drop_reason(row, conditions)
    row = {k: _finite(v) for k, v in row.items()}
    row["files"] = sorted(p.relative_to(stage).as_posix() for p in stage.rglob("*") if p.is_file())
    if notes:
        row["notes"] = notes
    if reason is not None:
        for child in stage.iterdir():  # a dropped sample keeps only its row
            shutil.rmtree(child) if child.is_dir() else child.unlink()
        row["dropped"] = reason
        row["files"] = []
    return row


def _manifest_unit_m(manifest: dict[str, Any]) -> float | None:
    physical = manifest.get("physical_size") or {}
    value = manifest.get("unit_m", physical.get("unit_m") if isinstance(physical, dict) else None)
    return float(value) if isinstance(value, int | float) else None


def _finite(value: Any) -> Any:
    """JSON-safe: a NaN or infinite float becomes None (null)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _seam_columns(maps: Any) -> dict[str, float]:
    """``seam_ratio.<map>`` for every exported map and ``seam_ratio.max`` (as the manifest
    computes them, also for a render that is not tileable)."""
    from matloom.engine.tiling import seam_ratio
    from matloom.io.export import MAP_SPECS

    out: dict[str, float] = {}
    for spec in MAP_SPECS:
        source = spec.sources[0] if spec.sources else None
        if source is not None and hasattr(maps, source):
            out[f"seam_ratio.{spec.name}"] = round(
                float(seam_ratio(getattr(maps, source), spec.period)), 4
            )
    finite = [v for v in out.values() if not math.isnan(v)]
    out["seam_ratio.max"] = max(finite) if finite else math.nan
    return out


def _params_json(spec: dict[str, Any]) -> str:
    """``matloom params --json`` of the sample's program (with the entry's labels, if any)."""
    from matloom.lang.params import list_params

    params = list_params(spec["text"], spec.get("labels") or {})
    return json.dumps([p.to_json() for p in params], indent=2) + "\n"


def _write_masks(folder: Path, plan: Any, job: Any) -> None:
    """Per-layer coverage (``alpha_NN.png``) and visible share (``visible_NN.png``)."""
    from matloom.engine.evaluate import evaluate
    from matloom.io.png import write_grey16

    program = plan.program
    if program is None or not program.layers:
        return
    folder.mkdir()
    alphas = []
    for layer in program.layers:  # the layer alone, its channels left out: its clamped alpha
        alone = replace(program, layers=(replace(layer, channels=()),))
        maps = evaluate(alone, job.width, job.height, backend=job.backend, view=plan.view)
        alphas.append(np.nan_to_num(np.asarray(maps.alpha, dtype=np.float64), nan=0.0))
    above = np.ones_like(alphas[0])
    visible = [np.zeros_like(a) for a in alphas]
    for index in range(len(alphas) - 1, -1, -1):  # top layer first
        visible[index] = alphas[index] * above
        above = above * (1.0 - alphas[index])
    for index, (alpha, share) in enumerate(zip(alphas, visible, strict=True), start=1):
        write_grey16(folder / f"alpha_{index:02d}.png", alpha)
        write_grey16(folder / f"visible_{index:02d}.png", share)


def _metric_columns(
    spec: dict[str, Any], stage: Path, maps: Any, notes: list[str]
) -> dict[str, float]:
    """The material metrics of ``spec["metrics"]`` (registry families), measured on the
    sample's own maps; a family that is not registered adds a note instead."""
    from matloom.evaluation.metrics.base import MetricUnavailableError, Sample

    try:
        from matloom.evaluation.metrics.registry import get_metric
    except ImportError as err:  # the registry is not there: the rows have no metric columns
        notes.append(f"metrics not measured: {err}")
        return {}
    sample = Sample(
        id=str(spec.get("source_id")),
        prompt=str(spec.get("prompt") or ""),
        program=spec["text"],
        images={"quick": stage / "preview.png"},
        size=int(spec["size"]),
        maps=maps,
    )
    out: dict[str, float] = {}
    for family in spec.get("metrics", ()):
        try:
            metric = get_metric(family)
        except MetricUnavailableError as err:
            notes.append(f"metric {family} not measured: {err}")
            continue
        try:
            values = metric.score([sample])[0]
        except MetricUnavailableError as err:
            notes.append(f"metric {family} not measured: {err}")
            continue
        errors = getattr(metric, "errors", None)
        if errors:
            notes.extend(f"metric {family}: {e}" for e in errors.values())
        out.update({k: float(v) for k, v in values.items()})
    return out
