"""The work of one bench cell (a prompt x system x run) and of its Blender renders.

The task functions are module-level and take only picklable arguments, so the in-process
executor and a Dask cluster run the same code. Each writes through
:func:`~matloom.evaluation.cells.commit_cell`: a cell folder appears whole or not at all.

A cell folder holds ``program.mat`` (the final program), ``preview.png`` (the flat quick
preview at the bench's size), ``cell.json`` (the summary: prompt, system, seed, version,
authoring seconds and tokens) and, for model systems, ``run/`` (the authoring run's record and
files). A render folder holds ``<layout>.png``.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.evaluation.cells import commit_cell

PROGRAM_NAME = "program.mat"
PREVIEW_NAME = "preview.png"


@dataclass(frozen=True)
class CellSpec:
    """Everything a worker needs to author one cell (JSON-able values only)."""

    prompt: str
    system: str
    spec: str
    seed: int
    size: int
    version: str
    #: The system's AuthorConfig dump (``mode="json"``) with the run's seed; None: the library.
    config: dict[str, Any] | None = None


@dataclass(frozen=True)
class RenderSpec:
    """One Blender render of a finished cell's program."""

    cell_dir: str
    layout: str
    size: int
    blender: str | None = None
    samples: int | None = None


class CountingModel:
    """A chat model that adds up the tokens its replies report (thread-safe)."""

    def __init__(self, inner: Any) -> None:
        self.inner = inner
        self.prompt_tokens = 0
        self.completion_tokens = 0
        self.calls = 0
        self._lock = threading.Lock()

    @property
    def model_id(self) -> str:
        return str(self.inner.model_id)

    @property
    def accepts_images(self) -> bool:
        return bool(self.inner.accepts_images)

    def complete(self, messages: Sequence[Any], max_reply_chars: int | None = None) -> Any:
        from matloom.author.llm.base import complete_within

        if max_reply_chars is None:
            reply = self.inner.complete(messages)
        else:
            reply = complete_within(self.inner, messages, max_reply_chars)
        with self._lock:
            self.calls += 1
            self.prompt_tokens += int(reply.usage.get("prompt_tokens", 0))
            self.completion_tokens += int(reply.usage.get("completion_tokens", 0))
        return reply


def author_cell(root: str, key: str, cell: CellSpec) -> dict[str, Any]:
    """Author ``cell`` into ``root/key`` (once) and return its summary."""
    return commit_cell(Path(root), key, lambda stage: _write_cell(stage, cell))


def _write_cell(stage: Path, cell: CellSpec) -> dict[str, Any]:
    from matloom.io.png import save_png
    from matloom.render.api import preview

    summary: dict[str, Any] = {
        "prompt": cell.prompt,
        "system": cell.system,
        "spec": cell.spec,
        "seed": cell.seed,
        "size": cell.size,
        "matloom_version": cell.version,
    }
    if cell.config is None:
        summary.update(_library(cell))
    else:
        summary.update(_model(stage, cell))
    (stage / PROGRAM_NAME).write_text(summary["program"], encoding="utf-8")
    start = time.perf_counter()
    save_png(stage / PREVIEW_NAME, preview(summary["program"], cell.size, layout="flat"))
    summary["preview_seconds"] = round(time.perf_counter() - start, 4)
    summary["images"] = {"quick": PREVIEW_NAME}
    return summary


def _library(cell: CellSpec) -> dict[str, Any]:
    from matloom.library import author

    start = time.perf_counter()
    result = author(cell.prompt, seed=cell.seed)
    return {
        "author": "library",
        "entry": result.entry,
        "program": result.program,
        "seconds": round(time.perf_counter() - start, 4),
        "prompt_tokens": 0,
        "completion_tokens": 0,
        "model_calls": 0,
    }


def _model(stage: Path, cell: CellSpec) -> dict[str, Any]:
    from matloom.author.config import AuthorConfig
    from matloom.author.llm.providers import get_model
    from matloom.author.pipeline import author_material

    config = AuthorConfig.model_validate(cell.config)
    assert config.generator is not None
    generator = CountingModel(get_model(config.generator))
    critic = CountingModel(get_model(config.critic)) if config.critic else generator
    start = time.perf_counter()
    result = author_material(cell.prompt, stage / "run", config, generator=generator, critic=critic)
    seconds = time.perf_counter() - start
    models = [generator] if critic is generator else [generator, critic]
    final = result.record.final
    return {
        "author": "model",
        "model": generator.model_id,
        "program": result.program,
        "critic_score": final.score if final else None,
        "seconds": round(seconds, 4),
        "prompt_tokens": sum(m.prompt_tokens for m in models),
        "completion_tokens": sum(m.completion_tokens for m in models),
        "model_calls": sum(m.calls for m in models),
    }


def render_cell(root: str, key: str, job: RenderSpec) -> dict[str, Any]:
    """Render a finished cell's program in one Blender layout into ``root/key/<layout>.png``."""
    return commit_cell(Path(root), key, lambda stage: _write_render(stage, job))


def _write_render(stage: Path, job: RenderSpec) -> dict[str, Any]:
    from matloom.blender.job import RenderOptions
    from matloom.blender.render import render_to_file
    from matloom.blender.runner import find_blender

    start = time.perf_counter()
    target = stage / f"{job.layout}.png"
    options = RenderOptions(layouts=(job.layout,), size=job.size, samples=job.samples)
    program = str(Path(job.cell_dir) / PROGRAM_NAME)
    render_to_file(program, options, target, find_blender(job.blender))
    return {
        "layout": job.layout,
        "size": job.size,
        "image": target.name,
        "seconds": round(time.perf_counter() - start, 3),
    }
