"""Batches of prompts: read a prompts file and author every prompt, ``jobs`` at a time.

Runs share nothing but the models (thread-safe clients) and the engine lock; each prompt gets
its own run folder ``<out>/<id>`` with its own record, so a batch can be resumed prompt by
prompt (finished runs are skipped on ``resume``).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.author.config import AuthorConfig
from matloom.author.pipeline import AuthoringError, Progress, RunResult, author_material
from matloom.author.records import RECORD_NAME, RecordStore
from matloom.author.redact import Redactor


@dataclass(frozen=True)
class PromptItem:
    """One prompt of a batch and the name of its run folder."""

    id: str
    text: str


def _slug(text: str, limit: int = 40) -> str:
    slug = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
    return slug[:limit].rstrip("-") or "prompt"


def read_prompts(path: str | Path) -> list[PromptItem]:
    """Prompts from JSON: a list of strings, a list of ``{id?, text|prompt}``, or ``{"prompts": [...]}``."""
    data: Any = json.loads(Path(path).read_text(encoding="utf-8"))
    if isinstance(data, dict):
        data = data.get("prompts")
    if not isinstance(data, list):
        raise ValueError(f"{path}: expected a list of prompts or an object with 'prompts'")
    items: list[PromptItem] = []
    for i, entry in enumerate(data):
        if isinstance(entry, str):
            text, ident = entry, None
        elif isinstance(entry, dict) and isinstance(entry.get("text", entry.get("prompt")), str):
            text, ident = entry.get("text", entry.get("prompt")), entry.get("id")
        else:
            raise ValueError(f"{path}: entry {i} is neither a string nor an object with 'text'")
        name = _slug(str(ident)) if ident else f"{i:03d}-{_slug(text)}"
        items.append(PromptItem(id=name, text=text))
    if len({it.id for it in items}) != len(items):
        raise ValueError(f"{path}: prompt ids are not unique")
    return items


def _finished(folder: Path) -> RunResult | None:
    """The result of an already finished run in ``folder`` (resume skips it), else None."""
    if not (folder / RECORD_NAME).exists():
        return None
    store = RecordStore.load(folder)
    if store.record.status != "finished":
        return None
    return RunResult(folder=folder, record=store.record)


@dataclass
class BatchOutcome:
    """Result of one prompt: a finished run, or the error that stopped it."""

    item: PromptItem
    folder: Path
    result: RunResult | None = None
    error: str | None = None


def author_batch(
    items: list[PromptItem],
    out_dir: str | Path,
    config: AuthorConfig,
    *,
    jobs: int = 1,
    resume: bool = False,
    progress: Progress | None = None,
    on_done: Callable[[BatchOutcome], None] | None = None,
) -> list[BatchOutcome]:
    """Author every prompt into ``out_dir/<id>``; failures are reported, never raised."""
    root = Path(out_dir)

    def one(item: PromptItem) -> BatchOutcome:
        folder = root / item.id
        outcome = BatchOutcome(item=item, folder=folder)
        try:
            outcome.result = _finished(folder) if resume else None
            if outcome.result is None:
                outcome.result = author_material(
                    item.text,
                    folder,
                    config,
                    resume=resume and (folder / RECORD_NAME).exists(),
                    progress=progress,
                )
        except AuthoringError as err:
            outcome.error = str(err)
        except Exception as err:  # noqa: BLE001 - one prompt's bug must not stop the batch
            outcome.error = Redactor.for_config(config).text(f"{type(err).__name__}: {err}")
        if on_done:
            on_done(outcome)
        return outcome

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(one, items))
