"""Entry points of one authoring run: open the run folder, build the models, drive the stages.

The run is a resumable state machine over its record (:mod:`matloom.author.run`): every stage
first looks at what the record already holds and only does what is missing, so ``resume=True``
on a crashed or killed run continues without redoing finished stages. Progress is reported
through a callback of :class:`ProgressEvent`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.author.config import AuthorConfig
from matloom.author.llm.base import ChatModel, ModelError, get_model
from matloom.author.prompts.system import system_prompt
from matloom.author.records import RECORD_NAME, ModelIds, RecordStore, RunRecord
from matloom.author.run import PickError, Progress, ProgressEvent, Run, append_library_program
from matloom.author.scorers.base import ScorerUnavailableError, TextImageScorer, get_scorer
from matloom.author.stages.generate import NoParseableProgramError, discard_unfinished_turns
from matloom.author.views import RENDER_LOCK
from matloom.io.outdir import OutputError, OutputFolder

__all__ = [
    "RENDER_LOCK",
    "AuthoringError",
    "Progress",
    "ProgressEvent",
    "RunResult",
    "author_material",
    "resolve_scorer",
]


class AuthoringError(RuntimeError):
    """A run failed; the record (with everything finished so far) is in ``folder``."""

    def __init__(self, message: str, folder: Path) -> None:
        super().__init__(message)
        self.folder = folder


@dataclass(frozen=True)
class RunResult:
    """What a finished run returns (and what ``--json`` prints)."""

    folder: Path
    record: RunRecord

    @property
    def program(self) -> str:
        assert self.record.final is not None
        return self.record.final.program

    def summary(self) -> dict[str, Any]:
        final = self.record.final
        return {
            "prompt": self.record.prompt,
            "folder": str(self.folder),
            "status": self.record.status,
            "author": self.record.author,
            "program": final.program if final else None,
            "score": final.score if final else None,
            "files": final.files if final else {},
            "warnings": list(self.record.warnings),
            "durations": self.record.durations.model_dump(),
        }


def resolve_scorer(config: AuthorConfig) -> tuple[TextImageScorer | None, str | None]:
    """The configured scorer, or None with the reason (``auto`` falls back quietly)."""
    if config.scorer == "none":
        return None, "no scorer configured"
    if config.scorer == "auto":
        try:
            return get_scorer("mobileclip2"), None
        except ScorerUnavailableError as err:
            return None, f"scorer 'auto': MobileCLIP2 unavailable ({str(err).splitlines()[0]})"
    name = config.scorer
    if config.scorer_weights and name in ("mobileclip2", "open_clip"):
        name = f"open_clip:MobileCLIP2-S2:{config.scorer_weights}"
    return get_scorer(name), None


# ---------------------------------------------------------------------- entry points


def _open_store(
    prompt: str | None, config: AuthorConfig | None, folder: Path, resume: bool
) -> RecordStore:
    import matloom

    if (folder / RECORD_NAME).exists():
        if not resume:
            raise AuthoringError(
                f"{folder} already holds a run; pass --resume to continue it or choose another -o",
                folder,
            )
        store = RecordStore.load(folder)
        if config is not None:
            store.record.settings = config
        store.record.status = "running"
        store.record.error = None
        discard_unfinished_turns(store)
        return store
    if prompt is None:
        raise AuthoringError(f"nothing to resume in {folder} (no {RECORD_NAME})", folder)
    config = config or AuthorConfig()
    record = RunRecord(
        matloom_version=matloom.__version__,
        prompt=prompt,
        settings=config,
        author="llm" if config.generator is not None else "library",
    )
    return RecordStore(folder, record)


def _models(
    config: AuthorConfig, generator: ChatModel | None, critic: ChatModel | None
) -> tuple[ChatModel | None, ChatModel | None]:
    if generator is None and config.generator is not None:
        generator = get_model(config.generator)
    if critic is None and config.critic is not None:
        critic = get_model(config.critic)
    return generator, critic or generator


def author_material(
    prompt: str | None,
    out_dir: str | Path,
    config: AuthorConfig | None = None,
    *,
    resume: bool = False,
    progress: Progress | None = None,
    generator: ChatModel | None = None,
    critic: ChatModel | None = None,
    scorer: TextImageScorer | None = None,
) -> RunResult:
    """Author one material into the run folder ``out_dir`` and return the finished record.

    ``config`` defaults to :class:`AuthorConfig()` (or, on resume, to the recorded settings).
    Models and the scorer are built from the config unless given. Raises
    :class:`AuthoringError` on failure, after saving the record. The run folder is locked
    while the run lasts, and files in it that MatLoom did not write are never replaced
    (:class:`matloom.io.outdir.OutputError`).
    """
    with OutputFolder(out_dir) as out:
        return _author_locked(
            prompt, out, config, resume, progress, generator=generator, critic=critic, scorer=scorer
        )


def _author_locked(  # noqa: PLR0913 - author_material's arguments, passed through
    prompt: str | None,
    out: OutputFolder,
    config: AuthorConfig | None,
    resume: bool,
    progress: Progress | None,
    *,
    generator: ChatModel | None,
    critic: ChatModel | None,
    scorer: TextImageScorer | None,
) -> RunResult:
    folder = Path(out.path)
    store = _open_store(prompt, config, folder, resume)
    store.attach(out)
    record = store.record
    session_start = time.perf_counter()
    record.sessions.append(record.updated)
    try:
        gen, crit = (None, None)
        if record.author == "llm":
            gen, crit = _models(record.settings, generator, critic)
        skip = None
        if scorer is None:
            scorer, skip = resolve_scorer(record.settings)
        record.models = ModelIds(
            generator=gen.model_id if gen else "library",
            critic=crit.model_id if crit else None,
            scorer=scorer.name if scorer else None,
        )
        run = Run(store, generator=gen, critic=crit, scorer=scorer, progress=progress)
        _run_stages(run, skip)
        record.status = "finished"
    except (
        ModelError,
        NoParseableProgramError,
        ScorerUnavailableError,
        PickError,
        OSError,
        OutputError,
    ) as err:
        message = store.redactor().text(str(err))  # an error body may echo the API key
        _fail(store, message, session_start)
        raise AuthoringError(message, folder) from err
    except Exception as err:
        _fail(store, f"{type(err).__name__}: {err}", session_start)
        raise
    except BaseException as err:  # KeyboardInterrupt, SystemExit: keep the record resumable
        _fail(store, f"interrupted: {type(err).__name__}", session_start)
        raise
    record.durations.total += time.perf_counter() - session_start
    store.save()
    return RunResult(folder=folder, record=record)


def _run_stages(run: Run, skip: str | None) -> None:
    record = run.record
    if record.offline:
        _library_author(run)
    else:
        if record.system_prompt is None:
            cfg = record.settings
            record.system_prompt = system_prompt(
                playbook=cfg.playbook,
                few_shot=cfg.few_shot,
                render_size=cfg.critique_size,
                views=run.views,
            )
        run.store.save()
        run.generate_initial()
        run.refine()
    run.select()
    run.seed_search(skip)
    run.finalize()


def _library_author(run: Run) -> None:
    """The offline author (no model configured): one program from the library, no critique."""
    if run.record.programs:
        return
    run.notify("generate", "material library (offline author)")
    append_library_program(run)
    run.store.save()


def _fail(store: RecordStore, message: str, session_start: float) -> None:
    store.record.status = "failed"
    store.record.error = message
    store.record.durations.total += time.perf_counter() - session_start
    try:
        store.save()
    except (OSError, OutputError):
        pass
