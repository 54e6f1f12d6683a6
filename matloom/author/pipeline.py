"""Entry points of one authoring run: open the run folder, build the models, drive the stages.

The run is a resumable state machine over its record (:mod:`matloom.author.run`): every stage
first looks at what the record already holds and only does what is missing, so ``resume=True``
on a crashed or killed run continues without redoing finished stages. Progress is reported
through a callback of :class:`ProgressEvent`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.author.config import AuthorConfig
from matloom.author.llm.base import ChatModel, ModelError
from matloom.author.llm.providers import get_model
from matloom.author.prompts.system import system_prompt
from matloom.author.records import RECORD_NAME, ModelIds, RecordStore, RunRecord
from matloom.author.reference import ReferencePhotoError, open_reference
from matloom.author.reference_chat import with_reference
from matloom.author.run import PickError, Progress, ProgressEvent, Run, append_library_program
from matloom.author.scorers.base import ScorerUnavailableError, TextImageScorer
from matloom.author.scorers.lookup import get_scorer
from matloom.author.stages.generate import NoParseableProgramError, discard_unfinished_turns
from matloom.author.stages.polish import polish_stage
from matloom.author.stages.polish_fit import PolishUnavailableError
from matloom.io.outdir import OutputError, OutputFolder

__all__ = [
    "AuthoringError",
    "Progress",
    "ProgressEvent",
    "RunRequestError",
    "RunResult",
    "author_material",
    "check_inputs",
    "check_prompt",
    "check_sizes",
    "resolve_scorer",
]


class AuthoringError(RuntimeError):
    """A run failed; the record (with everything finished so far) is in ``folder``."""

    def __init__(self, message: str, folder: Path) -> None:
        super().__init__(message)
        self.folder = folder


class RunRequestError(AuthoringError):
    """The run cannot start as asked (a bad prompt or setting, a resume that does not match
    the record): nothing was requested or written."""


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
            "name": self.record.material_name,
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


def check_prompt(prompt: str) -> None:
    """ValueError unless ``prompt`` is text that can be stored (no undecodable bytes)."""
    try:
        prompt.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError(
            "the prompt is not valid UTF-8 text (it holds bytes that do not decode); "
            "give it in UTF-8"
        ) from None


def check_sizes(config: AuthorConfig) -> None:
    """The documented limits (size, memory budget) that every render of the run meets whatever
    the program: checked before the first request, so the paid rounds cannot end in a refused
    export. Raises :class:`matloom.engine.limits.LimitError`."""
    from matloom.engine.limits import Usage, check_request
    from matloom.lang.api import parse

    smallest = parse("Material(Layer(1))")
    sizes = {
        "--export-size": config.export_size,
        "--critique-size": config.critique_size,
        "--select-size": config.select_size,
        "--sweep-size": config.sweep_size,
        "--stats-grid": config.stats_grid,
    }
    for flag, size in sizes.items():
        try:
            check_request(smallest, size, size, usage=Usage(preview_tile=1))
        except ValueError as err:
            raise type(err)(f"{flag} {size}: {err}") from None


def check_inputs(config: AuthorConfig) -> None:
    """The reference photo (``--reference``) can be used and the parameter fit's package
    (``--polish cmaes``) is installed: checked before the first request. Raises ValueError
    with a one-line message."""
    from matloom.author.reference import load_reference
    from matloom.author.stages.polish_fit import require_cma

    if config.reference is not None:
        load_reference(config.reference)
    if config.polish == "cmaes":
        require_cma()


def _open_store(  # noqa: PLR0913 - author_material's arguments, passed through
    prompt: str | None,
    config: AuthorConfig | None,
    folder: Path,
    resume: bool,
    trust_record: bool,
) -> RecordStore:
    """The run's record: a new one, or (``resume``) the folder's, checked against the prompt
    and settings given, before anything is requested or written."""
    from matloom._version import __version__

    def refuse(message: str) -> RunRequestError:
        return RunRequestError(message, folder)

    if (folder / RECORD_NAME).exists():
        if not resume:
            raise refuse(
                f"{folder} already holds a run; pass --resume to continue it or choose another -o"
            )
        store = _load_for_resume(folder, prompt, config, trust_record, refuse)
        store.record.status = "running"
        store.record.error = None
        discard_unfinished_turns(store)
        return store
    if prompt is None:
        raise refuse(f"nothing to resume in {folder} (no {RECORD_NAME})")
    config = config or AuthorConfig()
    record = RunRecord(
        matloom_version=__version__,
        prompt=prompt,
        settings=config,
        author="llm" if config.generator is not None else "library",
    )
    return RecordStore(folder, record)


def _load_for_resume(
    folder: Path,
    prompt: str | None,
    config: AuthorConfig | None,
    trust_record: bool,
    refuse: Callable[[str], RunRequestError],
) -> RecordStore:
    """The folder's record, refused when the prompt or settings differ from it, or when it
    would send requests where the user did not say (:mod:`matloom.author.resume`)."""
    from pydantic import ValidationError

    from matloom.author.config import ConfigError, one_line
    from matloom.author.resume import check_recorded_access, differences

    try:
        store = RecordStore.load(folder)
    except (OSError, ValueError) as err:  # ValidationError and JSONDecodeError included
        reason = one_line(err) if isinstance(err, ValidationError) else str(err)
        message = f"cannot resume: {folder / RECORD_NAME} is not a valid run record ({reason})"
        raise refuse(message) from None
    recorded = store.record
    if prompt is not None and prompt != recorded.prompt:
        raise refuse(
            f"--resume: {folder} holds the run for {recorded.prompt!r}, not {prompt!r}; "
            "resume it without a prompt, or choose another -o for the new prompt"
        )
    try:
        if config is None:
            check_recorded_access(recorded.settings, trust_record)
            check_sizes(recorded.settings)
        else:
            changed = differences(recorded.settings, config)
            if changed:
                raise refuse(
                    f"--resume: {folder} was run with other settings ("
                    + "; ".join(changed)
                    + "); resume it without them, or choose another -o for a new run"
                )
            store.record.settings = config
    except (ConfigError, ValueError) as err:  # RunRequestError is neither: it passes
        raise refuse(str(err)) from None
    return store


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
    trust_record: bool = False,
) -> RunResult:
    """Author one material into the run folder ``out_dir`` and return the finished record.

    ``config`` defaults to :class:`AuthorConfig()` (or, on resume, to the recorded settings,
    whose model servers and key variables are used only with ``trust_record``). On resume a
    ``prompt`` or ``config`` that differs from the record is refused. Models and the scorer are
    built from the config unless given. Raises :class:`RunRequestError` before anything is
    done when the run cannot start as asked, and :class:`AuthoringError` on failure, after
    saving the record. The run folder is locked while the run lasts, and files in it that
    MatLoom did not write are never replaced (:class:`matloom.io.outdir.OutputError`).
    """
    try:  # before the folder is made or locked
        if prompt is not None:
            check_prompt(prompt)
        if config is not None:
            check_sizes(config)
            check_inputs(config)
    except ValueError as err:
        raise RunRequestError(str(err), Path(out_dir)) from None
    with OutputFolder(out_dir) as out:
        folder = Path(out.path)
        store = _open_store(prompt, config, folder, resume, trust_record)
        return _author_locked(
            store, out, progress, generator=generator, critic=critic, scorer=scorer
        )


def _author_locked(
    store: RecordStore,
    out: OutputFolder,
    progress: Progress | None,
    *,
    generator: ChatModel | None,
    critic: ChatModel | None,
    scorer: TextImageScorer | None,
) -> RunResult:
    folder = Path(out.path)
    store.attach(out)
    record = store.record
    session_start = time.perf_counter()
    record.sessions.append(record.updated)
    try:
        gen, crit = (None, None)
        if record.author == "llm":
            gen, crit = _models(record.settings, generator, critic)
        photo = open_reference(record)  # --reference: checked against the recorded hash
        gen, crit, notes = with_reference(photo, record.settings.critique_size, gen, crit)
        skip = None
        if scorer is None:
            scorer, skip = resolve_scorer(record.settings)
        record.models = ModelIds(
            generator=gen.model_id if gen else "library",
            critic=crit.model_id if crit else None,
            scorer=scorer.name if scorer else None,
        )
        run = Run(store, generator=gen, critic=crit, scorer=scorer, progress=progress)
        run.renderer.reference = photo
        for note in notes:
            run.warn(note)
        _run_stages(run, skip)
        record.status = "finished"
    except (
        ModelError,
        NoParseableProgramError,
        ScorerUnavailableError,
        PickError,
        OSError,
        OutputError,
        ReferencePhotoError,
        PolishUnavailableError,
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
                examples=cfg.examples,
            )
        run.store.save()
        run.generate_initial()
        run.refine()
    run.select()
    run.seed_search(skip)
    polish_stage(run)  # --polish: fit the chosen program's numbers, kept if not worse
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
