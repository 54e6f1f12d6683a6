"""Orchestration of one authoring run: generate -> critique/revise -> select -> seed search.

The run is a resumable state machine over its record: every step first looks at what the
record already holds and only does what is missing, so ``resume=True`` on a crashed or killed
run continues without redoing finished stages (an interrupted model turn restarts from the last
committed conversation). Progress is reported through a callback of :class:`ProgressEvent`.
"""

from __future__ import annotations

import io
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from matloom.author.config import AuthorConfig
from matloom.author.llm.base import ChatModel, ImageInput, ModelError, get_model
from matloom.author.prompts.revision import (
    canonical_assistant_turn,
    request_message,
    revision_message,
)
from matloom.author.prompts.system import system_prompt
from matloom.author.records import (
    RECORD_NAME,
    FinalRecord,
    MessageRecord,
    ModelIds,
    ProgramRecord,
    RecordStore,
    RunRecord,
    SeedSearchRecord,
)
from matloom.author.scorers.base import ScorerUnavailableError, TextImageScorer, get_scorer
from matloom.author.stages.critique import critique_program
from matloom.author.stages.finite import finite_final, nonfinite_texels
from matloom.author.stages.generate import (
    NoParseableProgramError,
    discard_unfinished_turns,
    run_turn,
)
from matloom.author.stages.seedsearch import best_of_sweeps, candidate_indices, run_candidate_sweep
from matloom.author.stages.select import select_program
from matloom.io.outdir import OutputError, OutputFolder
from matloom.lang.seeds import derive_seed


@dataclass(frozen=True)
class ProgressEvent:
    """One progress report: which stage, which round, how far, and an ETA when known."""

    run: str
    stage: str
    message: str
    round: int | None = None
    done: int | None = None
    total: int | None = None
    eta_s: float | None = None


Progress = Callable[[ProgressEvent], None]

#: Serialises engine work between runs of a threaded batch: the numba kernels are
#: ``parallel=True`` and numba's default (workqueue) threading layer is not thread-safe.
RENDER_LOCK = threading.RLock()


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


def _png(image: np.ndarray) -> bytes:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="PNG")
    return buffer.getvalue()


def _jpeg(image: np.ndarray) -> bytes:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="JPEG", quality=92)
    return buffer.getvalue()


class Run:
    """One run's state: store, models, scorer, render cache, progress."""

    def __init__(
        self,
        store: RecordStore,
        *,
        generator: ChatModel | None,
        critic: ChatModel | None,
        scorer: TextImageScorer | None,
        progress: Progress | None,
    ) -> None:
        self.store = store
        self.record = store.record
        self.config = store.record.settings
        self.generator = generator
        self.critic = critic
        self.scorer = scorer
        self._progress = progress
        self._renders: dict[tuple[str, int], np.ndarray] = {}

    def notify(self, stage: str, message: str, **extra: Any) -> None:
        if self._progress is not None:
            self._progress(
                ProgressEvent(run=self.store.folder.name, stage=stage, message=message, **extra)
            )

    def render(self, program: str, size: int) -> np.ndarray:
        from matloom.render.api import preview

        key = (program, size)
        if key not in self._renders:
            with RENDER_LOCK:
                self._renders[key] = preview(program, size)
        return self._renders[key]

    # ------------------------------------------------------------------ stage I / II

    def generate_initial(self) -> None:
        if self.record.programs:
            return
        if self.config.start == "builtin":
            self.start_from_builtin()
            return
        assert self.generator is not None
        self.notify("generate", "generating P0", round=0)
        run_turn(
            self.generator,
            self.store,
            kind="generate",
            user_text=request_message(self.record.prompt),
            program_seed=derive_seed(self.config.seed, 0),
            repair_turns=self.config.repair_turns,
            notify=lambda m: self.notify("generate", m, round=0),
            max_reply_chars=self.config.max_reply_chars,
        )

    def start_from_builtin(self) -> None:
        """P0 from the offline author, committed as the model's first answer to the request.

        The conversation becomes (request, assistant turn with the canonical P0), exactly as if
        the generator had written P0, so the first revision turn has its context. Program and
        conversation are saved together: a resumed run either has both or redoes both.
        """
        self.notify("generate", "P0 from the built-in offline author", round=0)
        program = _append_builtin_program(self)
        self.record.conversation = [
            MessageRecord(role="user", text=request_message(self.record.prompt)),
            MessageRecord(role="assistant", text=canonical_assistant_turn("", program.text)),
        ]
        self.store.save()

    def refine(self) -> None:
        """Critique P_k and revise into P_{k+1} for k = 0..rounds-1, then critique P_rounds."""
        if self.config.rounds == 0 or self.record.stop_reason:
            return
        if not self.config.effective_signals():
            self.record.stop_reason = "no critic signals available"
            self.store.save()
            return
        for k in range(self.config.rounds + 1):
            if k >= len(self.record.programs):
                return
            critique = self.record.critique_of(k) or self.critique(k)
            if not critique.ok:
                self.record.stop_reason = f"critique of P{k} failed: {critique.error}"
                self.store.save()
                return
            if k < self.config.rounds and k + 1 >= len(self.record.programs):
                self.revise(
                    k, critique.match_score or 0, critique.differences, critique.suggestions
                )

    def critique(self, k: int) -> Any:
        assert self.critic is not None
        cfg = self.config
        program = self.record.programs[k].text
        signals = cfg.effective_signals()
        self.notify("critique", f"critiquing P{k}", round=k)
        start = time.perf_counter()
        image = None
        if "render" in signals:
            img = self.render(program, cfg.critique_size)
            path = self.store.write_file(f"renders/p{k}.png", _png(img))
            image = ImageInput(data=_jpeg(img), mime="image/jpeg", path=path)
        stats = None
        if "stats" in signals:
            from matloom.render.api import stats_text

            with RENDER_LOCK:
                stats = stats_text(program, grid=cfg.stats_grid)
        result = critique_program(
            self.critic,
            self.record.prompt,
            k,
            program,
            signals=signals,
            render=image,
            stats=stats,
            retries=cfg.critic_retries,
            max_reply_chars=cfg.max_reply_chars,
        )
        result.seconds = time.perf_counter() - start  # render + statistics + model calls
        self.record.critiques.append(result)
        self.record.durations.critique.append(result.seconds)
        self.store.save()
        return result

    def revise(self, k: int, score: int, differences: list[str], suggestions: list[str]) -> None:
        assert self.generator is not None
        self.notify("revise", f"revising P{k} -> P{k + 1}", round=k + 1)
        run_turn(
            self.generator,
            self.store,
            kind="revise",
            user_text=revision_message(score, differences, suggestions),
            program_seed=derive_seed(self.config.seed, k + 1),
            repair_turns=self.config.repair_turns,
            notify=lambda m: self.notify("revise", m, round=k + 1),
            max_reply_chars=self.config.max_reply_chars,
        )

    # ------------------------------------------------------------------ stage III

    def select(self) -> None:
        if self.record.selection is not None:
            return
        programs = [p.text for p in self.record.programs]
        self.notify("select", f"selecting among {len(programs)} program(s)")
        size = self.config.select_size
        self.record.selection = select_program(
            len(programs),
            prompt=self.record.prompt,
            critiques=self.record.critiques,
            scorer=self.scorer,
            render=lambda k: self.render(programs[k], size),
            size=size,
        )
        self.record.durations.select = self.record.selection.seconds
        self.store.save()

    def seed_search(self, skip_reason: str | None) -> None:
        record, cfg = self.record, self.config
        assert record.selection is not None
        if record.seed_search is None:
            last = len(record.programs) - 1
            record.seed_search = SeedSearchRecord(
                candidates=candidate_indices(0, record.selection.index, last)
            )
        search = record.seed_search
        if search.done:
            return
        if self.scorer is None or cfg.variants == 0:
            search.skipped = skip_reason or "variants = 0"
        else:
            self._sweep_candidates(search)
        search.done = True
        self.store.save()

    def _sweep_candidates(self, search: SeedSearchRecord) -> None:
        assert self.scorer is not None
        done = {s.program_index for s in search.sweeps}
        for n, index in enumerate(search.candidates):
            if index in done:
                continue
            start = time.perf_counter()

            def progress(
                finished: int, total: int, n: int = n, start: float = start, index: int = index
            ) -> None:
                elapsed = time.perf_counter() - start
                eta = elapsed / finished * (total - finished) if finished else None
                self.notify(
                    "seed-search",
                    f"sweep {n + 1}/{len(search.candidates)} (P{index})",
                    done=finished,
                    total=total,
                    eta_s=eta,
                )

            with RENDER_LOCK:
                sweep = run_candidate_sweep(
                    index,
                    self.record.programs[index].text,
                    prompt=self.record.prompt,
                    scorer=self.scorer,
                    variants=self.config.variants,
                    size=self.config.sweep_size,
                    seed=self.config.seed,
                    jobs=self.config.sweep_jobs,
                    progress=progress,
                )
            search.sweeps.append(sweep)
            self.record.durations.seed_search.append(sweep.seconds)
            self.store.save()

    def finalize(self) -> None:
        record = self.record
        if record.final is not None and record.final.files:
            return
        start = time.perf_counter()
        assert record.seed_search is not None and record.selection is not None
        final = best_of_sweeps(record.seed_search)
        if final is None:
            j = record.selection.index
            score = record.selection.scores[j] if record.selection.scores else None
            final = FinalRecord(
                program=record.programs[j].text, program_index=j, variant=0, score=score
            )
        final, warning = finite_final(
            record, final, self._nonfinite_texels, self.config.export_size
        )
        if warning:
            self.warn(warning)
        if self.config.tileable:
            final.program = _tileable_text(final.program)
        self.notify("export", "writing material.mat, preview and maps")
        final.files = self._export(final.program)
        record.final = final
        record.durations.export = time.perf_counter() - start
        self.store.save()

    def warn(self, message: str) -> None:
        """Record a warning once (the CLI prints the record's warnings when the run ends)."""
        if message not in self.record.warnings:
            self.record.warnings.append(message)

    def _nonfinite_texels(self, program: str) -> int:
        import matloom

        size = self.config.export_size
        with RENDER_LOCK:
            return nonfinite_texels(matloom.evaluate(program, size, size))

    def _export(self, program: str) -> dict[str, str]:
        import matloom
        from matloom.io.export import export_maps

        cfg = self.config
        files = {"program": self.store.write_file("material.mat", (program + "\n").encode())}
        files["preview"] = self.store.write_file(
            "preview.png", _png(self.render(program, cfg.select_size))
        )
        with RENDER_LOCK:
            maps = matloom.evaluate(program, cfg.export_size, cfg.export_size)
            export_maps(maps, self.store.folder / "maps", program_text=program)
        files["maps"] = "maps"
        return files


def _tileable_text(program: str) -> str:
    """``program`` with ``View(..., tileable=True)`` (canonical text)."""
    import matloom
    from matloom.lang.tileable import make_tileable

    return matloom.format(make_tileable(matloom.parse(program)))


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
        author="llm" if config.generator is not None else "builtin",
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
            generator=gen.model_id if gen else "builtin",
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
    if record.author == "builtin":
        _builtin_author(run)
    else:
        if record.system_prompt is None:
            cfg = record.settings
            record.system_prompt = system_prompt(playbook=cfg.playbook, few_shot=cfg.few_shot)
        run.store.save()
        run.generate_initial()
        run.refine()
    run.select()
    run.seed_search(skip)
    run.finalize()


def _builtin_author(run: Run) -> None:
    """The offline author (no model configured): one program, no critique."""
    if run.record.programs:
        return
    run.notify("generate", "built-in offline author")
    _append_builtin_program(run)
    run.store.save()


def _append_builtin_program(run: Run) -> ProgramRecord:
    """Record the offline author's program as P0 (canonical, seeds explicit) and its
    explanation; the caller saves."""
    from matloom.author.builtin import author
    from matloom.lang.api import parse
    from matloom.lang.printer import format_program
    from matloom.lang.seeds import canonicalize_seeds

    start = time.perf_counter()
    result = author(run.record.prompt, seed=run.config.seed)
    # The offline author already pins every seed; this only guarantees the canonical form.
    text = format_program(canonicalize_seeds(parse(result.program), run.config.seed))
    program = ProgramRecord(
        index=0, text=text, authored=result.program, source="builtin", program_seed=run.config.seed
    )
    run.record.programs.append(program)
    run.record.builtin_explanation = result.explanation
    run.record.durations.generation.append(time.perf_counter() - start)
    return program


def _fail(store: RecordStore, message: str, session_start: float) -> None:
    store.record.status = "failed"
    store.record.error = message
    store.record.durations.total += time.perf_counter() - session_start
    try:
        store.save()
    except (OSError, OutputError):
        pass
