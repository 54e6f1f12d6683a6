"""Run a :class:`~matloom.runtime.job.RenderJob` into a :class:`~matloom.runtime.sinks.Sink`.

:func:`run_render` is the one render-to-files job: it plans the job (every refusal before any
work), reserves the sink (a folder is locked and checked), evaluates the program under the
session's lock, shades the previews, and writes the maps, the presets, the previews,
``material.mat`` and ``material.json`` (listing every file with its SHA-256, written last)
into one staged batch of the sink.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from matloom.engine.session import Session, default_session
from matloom.runtime.job import (
    PREVIEWS,
    PROGRAM_FILE,
    Notify,
    RenderJob,
    RenderPlan,
    plan_render,
)
from matloom.runtime.sinks import Sink

if TYPE_CHECKING:
    import numpy as np

    from matloom.engine.evaluate import EvalStats
    from matloom.engine.maps import MaterialMaps


@dataclass
class RenderResult:
    """What :func:`run_render` made."""

    maps: MaterialMaps
    #: material.json's content (with its ``files`` list).
    manifest: dict[str, Any]
    #: Each written file by role (``program``, ``preview``, ``preview_tiled``, one per map,
    #: ``<map>_float``, ``height16``, ``preset:<name>`` for a preset's folder, ``manifest``),
    #: relative to :attr:`root`, ``/``-separated.
    files: dict[str, str]
    #: The folder the files were delivered to (None for a sink off this file system).
    root: Path | None
    #: Per map, how many source values were NaN or +-inf (only maps with at least one).
    nonfinite_counts: dict[str, int] = field(default_factory=dict)
    #: Divisions by exactly 0 the evaluation met (each returned 0).
    zero_divisions: int = 0
    #: Every note and warning said, in order (planning's, then the non-finite counts and the
    #: zero divisions).
    notes: list[str] = field(default_factory=list)
    #: Seconds spent: ``evaluate`` (absent when the maps were given), ``preview``, ``write``
    #: and ``total``.
    timings: dict[str, float] = field(default_factory=dict)


def run_render(
    job: RenderJob,
    sink: Sink,
    session: Session | None = None,
    *,
    maps: MaterialMaps | None = None,
    notify: Notify | None = None,
) -> RenderResult:
    """Evaluate ``job`` (unless its ``maps`` are given) and deliver its files to ``sink``.

    Engine work runs in ``session`` (default: :func:`~matloom.engine.session.default_session`)
    under its lock. ``notify`` hears every note as it comes (the planning notes before any
    work). Raises :class:`~matloom.runtime.job.RenderJobError` for a job that cannot run,
    :class:`~matloom.engine.limits.LimitError` for one over the limits (both before any file
    is written), and what the sink raises (:class:`~matloom.io.outdir.OutputError` for a
    folder)."""
    from matloom.engine.evaluate import EvalStats

    start = time.perf_counter()
    notes: list[str] = []

    def say(line: str) -> None:
        notes.append(line)
        if notify is not None:
            notify(line)

    session = session or default_session()
    plan = plan_render(job, maps, say, session)
    timings: dict[str, float] = {}
    stats = EvalStats()
    with sink.reserve(plan.files):
        if maps is None:
            t0 = time.perf_counter()
            maps = evaluate_plan(plan, session, stats)
            timings["evaluate"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        images = _previews(maps, job.previews, session)
        timings["preview"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        manifest, files = _write(plan, maps, images, sink)
        timings["write"] = time.perf_counter() - t0
    nonfinite = dict(manifest["nonfinite_values"])
    for name, n in nonfinite.items():
        say(f"warning: {n} non-finite texel value(s) in {name}")
    if stats.zero_divisions:
        say(f"note: {stats.zero_divisions} division(s) by exactly 0 returned 0")
    timings["total"] = time.perf_counter() - start
    return RenderResult(
        maps, manifest, files, sink.root, nonfinite, stats.zero_divisions, notes, timings
    )


def evaluate_plan(
    plan: RenderPlan, session: Session | None = None, stats: EvalStats | None = None
) -> MaterialMaps:
    """The maps of a planned job, evaluated under ``session``'s lock."""
    from matloom.engine.evaluate import evaluate

    job = plan.job
    if plan.program is None:
        raise ValueError("the plan was made for given maps: there is no program to evaluate")
    session = session or default_session()
    with session.lock:
        return evaluate(
            plan.program,
            job.width,
            job.height,
            backend=job.backend,
            view=plan.view,
            ao_radius_units=job.ao_radius,
            program_seed=job.program_seed,
            stats=stats,
            usage=plan.usage,
            session=session,
        )


def evaluate_job(job: RenderJob, session: Session | None = None) -> MaterialMaps:
    """The maps :func:`run_render` would evaluate for ``job`` (notes are not said)."""
    return evaluate_plan(plan_render(job, session=session), session)


def _previews(
    maps: MaterialMaps, layouts: tuple[str, ...], session: Session
) -> dict[str, np.ndarray]:
    """The shaded preview image of each layout (the flat swatch shaded once)."""
    if not layouts:
        return {}
    from matloom.render.preview import shade, tile_image

    with session.lock:
        swatch = shade(maps, session=session)
    images = {}
    for layout in layouts:
        file, tiles = PREVIEWS[layout]
        images[file] = swatch if tiles == 1 else tile_image(swatch, tiles)
    return images


def _write(
    plan: RenderPlan, maps: MaterialMaps, images: dict[str, np.ndarray], sink: Sink
) -> tuple[dict[str, Any], dict[str, str]]:
    """Write the job's files as one batch of ``sink``; the manifest and the files by role."""
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.export import MANIFEST_NAME, write_manifest, write_maps
    from matloom.io.png import save_png

    job = plan.job
    files: dict[str, str] = {}
    with sink.batch(MANIFEST_NAME) as staging:
        final = sink.root or staging
        result = write_maps(
            maps,
            staging,
            final_dir=final,
            maps_subset=job.map_names,
            program_text=plan.text,
            engine_version=job.engine_version,
            extra_meta=dict(job.extra) if job.extra is not None else None,
            encoding=job.encoding,
            unit_m=job.unit_m,
            presets=job.presets,
            name=job.name,
        )
        if plan.view_note:
            result.manifest["view_adjusted"] = plan.view_note
        if job.write_program and plan.text is not None:
            text = job.program_file_text
            if text is None:
                text = plan.text + "\n"
            atomic_write_bytes(staging / PROGRAM_FILE, text.encode("utf-8"))
            files["program"] = PROGRAM_FILE
        for name, image in images.items():
            save_png(staging / name, image)
            files[Path(name).stem] = name
        write_manifest(result, staging)
    for role, path in result.files.items():
        files[role] = path.relative_to(final).as_posix()
    return result.manifest, files
