"""Where ``matloom dataset`` takes its programs from: library entries, a folder of ``*.mat``
programs, or a list of prompts (written by the offline library author, or by a model profile
on the executor, one ``uses_llm`` task per prompt)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.evaluation.cells import commit_cell, content_key
from matloom.evaluation.executor import Executor, Outcome, ProgressCallback, Task


class SourceError(ValueError):
    """A source that cannot be read; the message is one line."""


@dataclass(frozen=True)
class SourceProgram:
    """One program a dataset is built from (before seed variants and sizes)."""

    #: ``library``, ``folder`` or ``prompt``.
    source: str
    #: The entry name, the file's name in the folder, or the prompt's id.
    source_id: str
    text: str
    prompt: str | None = None
    entry: str | None = None
    category: str | None = None
    #: Metres per coordinate unit (None: the program's own View says, or nothing).
    unit_m: float | None = None
    #: ``matloom params`` labels (a library entry's front matter).
    labels: dict[str, str] = field(default_factory=dict)


def library_sources(
    entries: Sequence[str] | None = None,
    tags: Sequence[str] | None = None,
    lib: Any = None,
) -> list[SourceProgram]:
    """The library's entries (all, the named ones, or those with any of ``tags``), sorted by
    category then name; each at its physical size (``size_m`` over the View's width). ``lib``:
    a :class:`~matloom.library.Library` with user entries (default: the built-in one)."""
    from matloom.library import library
    from matloom.library.labels import entry_labels
    from matloom.library.overlay import view_width

    lib = lib if lib is not None else library()
    if entries:
        try:
            chosen = [lib.entry(name) for name in entries]
        except KeyError as err:
            raise SourceError(str(err.args[0])) from None
    else:
        chosen = lib.by_category()
    if tags:
        wanted = {t.lower() for t in tags}
        chosen = [e for e in chosen if wanted & set(e.tags)]
        if not chosen:
            raise SourceError(f"no library entry has any of the tags {', '.join(sorted(wanted))}")
    out = []
    for entry in chosen:
        out.append(
            SourceProgram(
                source="library",
                source_id=entry.name,
                text=entry.program,
                entry=entry.name,
                category=entry.category,
                unit_m=entry.size_m / view_width(lib.ast(entry.name)),
                labels=entry_labels(entry),
            )
        )
    return out


def folder_sources(folder: str | Path) -> list[SourceProgram]:
    """Every ``*.mat`` file of ``folder`` (not its sub-folders), by name."""
    path = Path(folder)
    if not path.is_dir():
        raise SourceError(f"{folder} is not a folder of .mat programs")
    files = sorted(p for p in path.glob("*.mat") if p.is_file())
    if not files:
        raise SourceError(f"{folder} holds no .mat program")
    out = []
    for file in files:
        try:
            text = file.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as err:
            raise SourceError(f"cannot read {file}: {err}") from None
        out.append(SourceProgram(source="folder", source_id=file.name, text=text))
    return out


def prompt_sources(path: str | Path) -> list[SourceProgram]:
    """Every prompt of a prompts file, written by the offline library author."""
    from matloom.library import author

    out = []
    for item in read_prompt_items(path):
        result = author(item.text)
        out.append(
            SourceProgram(
                source="prompt",
                source_id=item.id,
                text=result.program,
                prompt=item.text,
                entry=result.entry,
                category=result.category,
                unit_m=result.unit_m,
            )
        )
    return out


def read_prompt_items(path: str | Path) -> list[Any]:
    """The prompts of a JSON prompts file (as ``generate --prompts`` reads them)."""
    from matloom.author.batch import read_prompts

    try:
        return read_prompts(path)
    except OSError as err:
        raise SourceError(f"cannot read {path}: {err.strerror}") from None
    except (ValueError, json.JSONDecodeError) as err:
        raise SourceError(" ".join(str(err).split())) from None


def author_with_model(prompt: str, config: Any, root: str, key: str) -> dict[str, Any]:
    """The executor task of a model-written program: one authoring run in cell ``key``."""
    from matloom.author.pipeline import author_material

    def write(stage: Path) -> dict[str, Any]:
        result = author_material(prompt, stage / "run", config)
        return {"prompt": prompt, "program": result.program, "status": result.record.status}

    return commit_cell(Path(root), key, write)


def model_sources(
    path: str | Path,
    config: Any,
    executor: Executor,
    root: Path,
    on_progress: ProgressCallback | None = None,
) -> tuple[list[SourceProgram], list[Outcome]]:
    """Every prompt of a prompts file authored by the model of ``config`` (an
    :class:`~matloom.author.config.AuthorConfig`), one ``uses_llm`` task each, into cells of
    ``root`` (resumable like the samples); the programs and the failed outcomes."""
    from matloom._version import __version__

    items = read_prompt_items(path)
    settings = config.model_dump(mode="json")
    keys = [content_key("matloom-dataset-program", it.text, settings, __version__) for it in items]
    tasks = [
        Task(key, author_with_model, (item.text, config, str(root), key), uses_llm=True)
        for key, item in zip(keys, items, strict=True)
    ]
    outcomes = executor.run(tasks, root, on_progress)
    out, failed = [], []
    for item, task, outcome in zip(items, tasks, outcomes, strict=True):
        if not outcome.ok:
            failed.append(outcome)
            continue
        cell = json.loads((root / task.key / "cell.json").read_text(encoding="utf-8"))
        out.append(
            SourceProgram(
                source="prompt", source_id=item.id, text=cell["program"], prompt=item.text
            )
        )
    return out, failed
