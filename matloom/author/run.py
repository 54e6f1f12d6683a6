"""One authoring run's stages over its record: generate, critique/revise, select, seed search,
export.

Every stage first looks at what the record already holds and only does what is missing, so a
resumed run continues without redoing finished stages (an interrupted model turn restarts from
the last committed conversation). :mod:`matloom.author.pipeline` opens the run folder, builds
the models and drives these stages.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.author.finalize import export_final, material_name, tileable_text
from matloom.author.library_refs import library_references
from matloom.author.llm.base import ChatModel, ImageInput
from matloom.author.prompts.critic import CriticOptions
from matloom.author.prompts.revision import (
    canonical_assistant_turn,
    draft_message,
    request_message,
    revision_message,
    warning_lines,
)
from matloom.author.records import (
    CritiqueRecord,
    FinalRecord,
    MessageRecord,
    ProgramRecord,
    RecordStore,
    SeedSearchRecord,
)
from matloom.author.scorers.base import TextImageScorer
from matloom.author.stages.critique import PreviousRound, critique_program
from matloom.author.stages.finite import finite_final, nonfinite_texels
from matloom.author.stages.generate import extract_answer, run_turn
from matloom.author.stages.loop import (
    LoopState,
    continue_from,
    critic_score,
    guide,
    loop_sections,
    preview_difference,
)
from matloom.author.stages.seedsearch import best_of_sweeps, candidate_indices, run_candidate_sweep
from matloom.author.stages.select import select_program
from matloom.author.views import (
    Renderer,
    ViewUnavailableError,
    available_views,
    image_input,
    png_bytes,
    view_file,
)
from matloom.engine.maps import MaterialMaps
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


class Run:
    """One run's state: store, models, scorer, renderer, progress."""

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
        self.renderer = Renderer()
        self._written: set[str] = set()
        #: program text -> its maps at the export size (the finite check's, reused by export)
        self._evaluated: dict[str, MaterialMaps] = {}
        self.views: tuple[str, ...] = ("flat",)
        if self.record.author == "llm":  # the library author has no critic to show views to
            self.views, missing = available_views(self.config.views)
            if missing:
                self.warn(missing)

    def notify(self, stage: str, message: str, **extra: Any) -> None:
        if self._progress is not None:
            self._progress(
                ProgressEvent(run=self.store.folder.name, stage=stage, message=message, **extra)
            )

    def warn(self, message: str) -> None:
        """Record a warning once (the CLI prints the record's warnings when the run ends)."""
        if message not in self.record.warnings:
            self.record.warnings.append(message)

    def render(self, program: str, size: int) -> np.ndarray:
        """The flat preview (selection, sweeps)."""
        return self.renderer.image(program, size, "flat")

    def view_inputs(self, k: int) -> list[ImageInput]:
        """P_k's previews at the critique size in the run's layouts, stored under renders/."""
        program, size = self.record.programs[k].text, self.config.critique_size
        inputs = []
        for view in self.views:
            image = self.renderer.image(program, size, view)
            path = view_file(k, view)
            if path not in self._written:
                self.store.write_file(path, png_bytes(image))
                self._written.add(path)
            inputs.append(image_input(image, path))
        return inputs

    def critic_stats(self, program: str) -> str:
        cfg = self.config
        kind = cfg.critic_stats
        try:
            return self.renderer.stats(program, kind, grid=cfg.stats_grid, size=cfg.critique_size)
        except ViewUnavailableError as err:
            self.warn(f"{err}; the critic got the 28 statistics instead")
            return self.renderer.stats(
                program, "paper", grid=cfg.stats_grid, size=cfg.critique_size
            )

    # ------------------------------------------------------------------ stage I / II

    def generate_initial(self) -> None:
        if self.record.programs:
            return
        if self.config.start == "library":
            self.start_from_library()
            return
        assert self.generator is not None
        refs = library_references(
            self.record.prompt,
            self.config.library_refs,
            seed=self.config.seed,
            library_dirs=self.config.library_dirs,
        )
        if refs:
            self.notify("generate", f"library references: {', '.join(r.entry for r in refs)}")
        self.notify("generate", "generating P0", round=0)
        run_turn(
            self.generator,
            self.store,
            kind="generate",
            user_text=request_message(self.record.prompt, refs),
            program_seed=derive_seed(self.config.seed, 0),
            repair_turns=self.config.repair_turns,
            notify=lambda m: self.notify("generate", m, round=0),
            max_reply_chars=self.config.max_reply_chars,
            refused_warnings=frozenset(self.config.refuse_warnings),
        )

    def start_from_library(self) -> None:
        """P0 from the material library, committed as the model's first answer to the request.

        The conversation becomes (request, assistant turn with P0), exactly as if the generator
        had written P0, so the first revision turn has its context. Program and conversation
        are saved together: a resumed run either has both or redoes both.
        """
        self.notify("generate", "P0 from the material library", round=0)
        program = append_library_program(self)
        self.record.conversation = [
            MessageRecord(role="user", text=request_message(self.record.prompt)),
            MessageRecord(role="assistant", text=canonical_assistant_turn("", program.text)),
        ]
        self.store.save()

    def refine(self) -> None:
        """Critique P_k and revise into P_{k+1} for k = 0..rounds-1, then critique P_rounds.

        With ``drafts`` D > 1, P_0 .. P_{D-1} are first drafts, each critiqued, and the
        ``rounds`` revisions follow from the best of them: P_D .. P_{D-1+rounds}.

        Loop v3 (off in the paper): a revision with no visible change is not critiqued and
        counts toward stopping; a revision continues from the best program so far; the last
        critique asks for the score only (:mod:`matloom.author.stages.loop`)."""
        cfg = self.config
        if (cfg.rounds == 0 and self.drafts == 1) or self.record.stop_reason:
            return
        if not cfg.effective_signals():
            self.record.stop_reason = "no critic signals available"
            self.store.save()
            return
        loop = LoopState(drafts=self.drafts)
        final = loop.drafts - 1 + cfg.rounds
        for k in range(final + 1):
            if k >= len(self.record.programs):
                return
            last = k == final
            drafting = k + 1 < loop.drafts  # the next program is another first draft
            critique = None
            if self._unchanged(k, loop):
                if len(loop.unchanged) >= cfg.no_change_limit:
                    shown = ", ".join(f"P{j}" for j in loop.unchanged)
                    self.record.stop_reason = (
                        f"{len(loop.unchanged)} revision(s) made no visible change ({shown})"
                    )
                    self.store.save()
                    return
            else:
                score_only = last and cfg.score_only_last
                critique = self.record.critique_of(k) or self.critique(k, loop, score_only)
                if not critique.ok:
                    self.record.stop_reason = f"critique of P{k} failed: {critique.error}"
                    self.store.save()
                    return
            if drafting:
                if k + 1 >= len(self.record.programs):
                    self.draft(k + 1, loop.drafts)
                continue
            if last:
                break
            base = continue_from(self.record, k, loop, self._scorer_of(loop))
            if critique is not None and cfg.stop_when_satisfied:
                # after the drafts, the best draft's critique says whether to go on
                ask_of = base if loop.is_draft(k) else k
                if not _asks(self.record.critique_of(ask_of) or critique, cfg.critic_structural):
                    self.record.stop_reason = f"the critic asked for no changes to P{ask_of}"
                    self.store.save()
                    return
            loop.parents[k + 1] = base
            if k + 1 >= len(self.record.programs):
                self.revise(k, base, loop)
        done = f"all {cfg.rounds} revision rounds used" if cfg.rounds else "all drafts written"
        self.record.stop_reason = done
        self.store.save()

    def _scorer_of(self, loop: LoopState) -> Callable[[int], float] | None:
        """P_j -> the scorer's score, for revising from the best (None without a scorer)."""
        return None if self.scorer is None else lambda j: self._scorer_score(j, loop)

    @property
    def drafts(self) -> int:
        """First drafts the generator writes (one when the library writes P0)."""
        return 1 if self.config.start == "library" else self.config.drafts

    def draft(self, k: int, total: int) -> None:
        """Ask the generator for P_k, first draft k + 1 of ``total``: a new program for the
        request, a different approach from the earlier drafts its conversation holds."""
        assert self.generator is not None
        cfg = self.config
        self.notify("generate", f"writing draft {k + 1} of {total} (P{k})", round=k)
        run_turn(
            self.generator,
            self.store,
            kind="draft",
            user_text=draft_message(k + 1, total),
            program_seed=derive_seed(cfg.seed, k),
            repair_turns=cfg.repair_turns,
            notify=lambda m: self.notify("generate", m, round=k),
            max_reply_chars=cfg.max_reply_chars,
            refused_warnings=frozenset(cfg.refuse_warnings),
        )

    def _unchanged(self, k: int, loop: LoopState) -> bool:
        """True (and noted in ``loop``) when P_k's previews differ from its parent's by less
        than ``no_change_threshold`` (never for a first draft)."""
        threshold = self.config.no_change_threshold
        if threshold is None or loop.is_draft(k):
            return False
        size, parent = self.config.critique_size, loop.parent(k)
        images = [
            [self.renderer.image(self.record.programs[j].text, size, view) for view in self.views]
            for j in (k, parent)
        ]
        difference = preview_difference(*images)
        if difference >= threshold:
            return False
        loop.unchanged[k] = difference
        return True

    def _scorer_score(self, k: int, loop: LoopState) -> float:
        assert self.scorer is not None
        if k not in loop.scores:
            image = self.render(self.record.programs[k].text, self.config.select_size)
            loop.scores[k] = float(self.scorer.score([image], self.record.prompt)[0])
        return loop.scores[k]

    def shown_text(self, k: int) -> str:
        """P_k as its author wrote it (the generator's own text), as the critic quotes it."""
        record = self.record.programs[k]
        if record.source == "generator" and record.authored:
            return (extract_answer(record.authored)[0] or record.text).strip()
        return record.text

    def _previous_round(self, k: int, sees_render: bool, loop: LoopState) -> PreviousRound | None:
        if not self.config.critic_history or loop.is_draft(k):
            return None
        parent = loop.parent(k)
        images = tuple(self.view_inputs(parent)) if sees_render else ()
        return PreviousRound(index=parent, score=critic_score(self.record, parent), images=images)

    def critique(
        self, k: int, loop: LoopState | None = None, score_only: bool = False
    ) -> CritiqueRecord:
        assert self.critic is not None
        cfg = self.config
        loop = loop or LoopState()
        program = self.record.programs[k].text
        # The critic quotes the program the generator wrote (its own text, as the generator's
        # conversation holds it), so its edits name lines the generator can find.
        shown = self.shown_text(k)
        signals = cfg.effective_signals()
        self.notify("critique", f"critiquing P{k}", round=k)
        start = time.perf_counter()
        sees_render = "render" in signals and self.critic.accepts_images
        renders = self.view_inputs(k) if sees_render else []
        stats = self.critic_stats(program) if "stats" in signals else None
        result = critique_program(
            self.critic,
            self.record.prompt,
            k,
            shown,
            signals=signals,
            renders=renders,
            views=self.views,
            stats=stats,
            retries=cfg.critic_retries,
            history=cfg.critic_history,
            previous=self._previous_round(k, sees_render, loop),
            max_reply_chars=cfg.max_reply_chars,
            options=CriticOptions(
                previews=cfg.critic_previews,
                structural=cfg.critic_structural,
                size=cfg.critique_size,
            ),
            score_only=score_only,
        )
        result.seconds = time.perf_counter() - start  # renders + statistics + model calls
        self.record.critiques.append(result)
        self.record.durations.critique.append(result.seconds)
        self.store.save()
        return result

    def revise(self, k: int, base: int | None = None, loop: LoopState | None = None) -> None:
        """Ask the generator for P_{k+1}, revising ``base`` (P_k unless the loop continues from
        the best program so far)."""
        assert self.generator is not None
        cfg = self.config
        loop = loop or LoopState()
        base = k if base is None else base
        guiding = guide(self.record, base, loop)
        critique = self.record.critique_of(guiding)
        assert critique is not None
        self.notify("revise", f"revising P{base} -> P{k + 1}", round=k + 1)
        images = []
        if cfg.revision_images and self.generator.accepts_images:
            images = self.view_inputs(base)
        before = None
        if cfg.critic_history and not loop.is_draft(guiding):
            before = self.record.critique_of(loop.parent(guiding))
        text = revision_message(
            critique.match_score or 0,
            critique.differences,
            critique.suggestions,
            edits=critique.edits,
            views=self.views if images else (),
            added_seeds=self.record.programs[base].added_seeds,
            # at the positions of the text the model wrote (or was shown as its own)
            warnings=warning_lines(self.shown_text(base)) if cfg.revision_warnings else (),
            previous_score=before.match_score if before is not None and before.ok else None,
            **loop_sections(
                self.record,
                k,
                base,
                loop,
                self.shown_text,
                self.scorer.name if self.scorer else None,
            ),
        )
        run_turn(
            self.generator,
            self.store,
            kind="revise",
            user_text=text,
            program_seed=derive_seed(cfg.seed, k + 1),
            repair_turns=cfg.repair_turns,
            notify=lambda m: self.notify("revise", m, round=k + 1),
            max_reply_chars=cfg.max_reply_chars,
            images=images,
            refused_warnings=frozenset(cfg.refuse_warnings),
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

            with self.renderer.session.lock:
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
        from matloom.author.stages.polish import polished_final

        final = polished_final(record, final)  # --polish: the fitted program, when kept
        final, warning = finite_final(
            record, final, self._nonfinite_texels, self.config.export_size
        )
        if warning:
            self.warn(warning)
        if self.config.tileable:
            final.program = tileable_text(final.program)
        self.notify("export", "writing material.mat, preview.png, the maps and material.json")
        maps = self._evaluated.get(final.program)  # the finite check's maps: not evaluated twice
        self._evaluated.clear()
        record.material_name = record.material_name or material_name(record.prompt)
        final.files = export_final(
            self.store,
            final.program,
            self.config.export_size,
            maps,
            name=record.material_name,
            session=self.renderer.session,
        )
        record.final = final
        record.durations.export = time.perf_counter() - start
        self.store.save()
        if self.config.blender_layouts:
            self.render_blender()

    def render_blender(self) -> None:
        """Render the exported material in Blender's layouts (a failure is recorded and warned
        about; the material itself stays exported)."""
        from matloom.author.records import BlenderRecord
        from matloom.blender import BlenderError, render_layouts

        layouts = list(self.config.blender_layouts)
        self.notify("blender", "rendering " + ", ".join(layouts) + " in Blender")
        folder = self.store.folder
        entry = BlenderRecord(layouts=layouts)
        start = time.perf_counter()
        try:
            paths = render_layouts(
                folder,
                layouts,
                folder / "blender",
                size=self.config.blender_size,
                progress=lambda line: self.notify("blender", line),
            )
            entry.files = [str(p.relative_to(folder)) for p in paths]
        except BlenderError as err:
            entry.error = str(err)
            self.warn(f"Blender renders skipped: {err}")
        entry.seconds = time.perf_counter() - start
        self.record.blender = entry
        self.store.save()

    def _nonfinite_texels(self, program: str) -> int:
        """Non-finite texels of ``program`` at the export size; its maps are kept (the last
        program's only) so that exporting the same program does not evaluate it again."""
        from matloom.author.finalize import evaluate_for_export

        self._evaluated.clear()
        maps = evaluate_for_export(
            program, self.config.export_size, session=self.renderer.session
        )  # (under the session's lock)
        self._evaluated[program] = maps
        return nonfinite_texels(maps)


class PickError(ValueError):
    """``pick`` names a candidate past the library's ranking for the prompt."""


def append_library_program(run: Run) -> ProgramRecord:
    """Record the library's program for the run's prompt and seed as P0 (canonical, seeds
    explicit, the View carrying the physical size ``unit_m``) and its explanation; the caller
    saves.

    The library makes the program tileable wherever the entry allows it (``config.tileable``
    then forces it for the others, at export). The recorded ``authored`` text keeps the
    library's header comments (entry, adaptations, overlays); ``text`` is the canonical form
    of the library's program (its AST: the library's text is not read back).
    """
    from matloom.lang.printer import format_program
    from matloom.lang.seeds import canonicalize_seeds
    from matloom.library import author
    from matloom.library.user import library_for

    start = time.perf_counter()
    lib = library_for(run.config.library_dirs)  # a bad user entry: LibraryError, one line
    try:
        result = author(
            run.record.prompt, seed=run.config.seed, pick=run.config.pick, tileable=True, lib=lib
        )
    except ValueError as err:  # only a pick past the candidates
        raise PickError(str(err)) from None
    # The library already pins every seed; this only guarantees the canonical form.
    text = format_program(canonicalize_seeds(result.ast, run.config.seed))
    program = ProgramRecord(
        index=0, text=text, authored=result.program, source="library", program_seed=run.config.seed
    )
    run.record.programs.append(program)
    run.record.library_explanation = result.explanation
    if run.record.offline:  # the library's program is the result: the entry names it
        run.record.material_name = material_name(result.entry)
    run.record.durations.generation.append(time.perf_counter() - start)
    return program


def _asks(critique: CritiqueRecord, structural: bool) -> bool:
    """Whether a critique asks for changes (suggestions, edits, or structural changes when
    the critic may ask for them)."""
    return bool(critique.suggestions or critique.edits or (structural and critique.structural))
