"""Stage III (d), ``--polish cmaes``: fit the chosen program's exposed numbers, then guard.

After selection and the seed search, the program the export would take
(:func:`matloom.author.stages.seedsearch.chosen_final`) has its continuous exposed parameters
fitted by CMA-ES inside their ranges (:mod:`matloom.author.stages.polish_fit`). The
objective is, in this order of preference:

1. ``scorer``: the run's text-image scorer on the flat preview at ``polish_size`` (higher is
   better), when the run has a scorer;
2. ``reference``: the statistics distance between the flat preview and the reference photo,
   both at ``polish_size`` (:func:`matloom.render.compare_stats.stats_distance`, lower is
   better), with ``--reference``;
3. ``critic``: the critic's match score on the previews and statistics it gets in the rounds,
   at most ``polish_critic_calls`` calls (higher is better).

The fit is bounded by ``polish_evaluations`` and ``polish_seconds``. A fit that does not beat
the unfitted program's objective is dropped. Only parameters that change a map the objective's
previews show are fitted (:func:`visible_maps`): the others would drift at random. Otherwise the critic scores the unfitted and the
fitted program afresh (two stateless calls, the same inputs as in the rounds), and the fit is
kept only when the critic does not score it lower: a proxy objective (a scorer, statistics)
can be fitted into looking worse. A run without a critic (the offline library author) keeps
an improving scorer fit unchecked, and the record says so; a fit to a reference photo it
records but does not export (judged blind, such fits looked less like the photo). ``RunRecord.polish`` holds what was
fitted, the values before and after, the objective and critic scores, and the decision; the
export then takes the fitted program when it was kept (:func:`polished_final`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from matloom.author.records import (
    CritiqueRecord,
    FinalRecord,
    FittedParamRecord,
    PolishRecord,
    RunRecord,
)
from matloom.author.stages.polish_fit import PENALTY, Space, cmaes_minimise, fit_space
from matloom.author.stages.seedsearch import chosen_final

if TYPE_CHECKING:
    from matloom.author.run import Run
    from matloom.author.views import Renderer

#: Objective kind -> whether higher values are better.
HIGHER_IS_BETTER = {"scorer": True, "reference": False, "critic": True}
#: Where the guard's previews are stored in the run folder.
GUARD_FILES = {"before": "renders/polish_before", "after": "renders/polish_after"}


def polished_final(record: RunRecord, final: FinalRecord) -> FinalRecord:
    """``final``, or the fitted program in its place when the fit of it was kept."""
    polish = record.polish
    if (
        polish is None
        or not polish.kept
        or polish.program is None
        or (polish.program_index, polish.variant) != (final.program_index, final.variant)
    ):
        return final
    score = polish.objective_after if polish.objective == "scorer" else polish.critic_after
    return FinalRecord(
        program=polish.program,
        program_index=final.program_index,
        variant=final.variant,
        score=None if score is None else float(score),
    )


def _objective_kind(run: Run) -> str | None:
    if run.scorer is not None:
        return "scorer"
    if run.renderer.reference is not None:
        return "reference"
    if run.critic is not None and run.config.effective_signals():
        return "critic"
    return None


def visible_maps(views: tuple[str, ...]) -> frozenset[str]:
    """The output maps that show in preview layouts ``views``: colour, relief, coverage and
    emission, and each channel that changes a probe swatch by at least
    :data:`~matloom.author.prompts.previews.VISIBLE_LEVELS` there (measured)."""
    from matloom.author.prompts.previews import VISIBLE_LEVELS, channel_changes

    seen = {"alpha", "basecolor", "height", "normal", "ao", "emissive"}
    for view in views:
        seen |= {name for name, levels in channel_changes(view).items() if levels >= VISIBLE_LEVELS}
    return frozenset(seen)


def _preview(run: Run, program: str, size: int) -> np.ndarray:
    """The flat preview of ``program`` at ``size`` (not cached: a fit renders many)."""
    from matloom.author.views import shade_view
    from matloom.engine.evaluate import evaluate
    from matloom.engine.limits import Usage

    session = run.renderer.session
    with session.lock:
        maps = evaluate(program, size, size, usage=Usage(preview_tile=1), session=session)
        return shade_view(maps, "flat", session=session)


def _critic_score(
    run: Run, renderer: Renderer, program: str, index: int, files: str | None = None
) -> CritiqueRecord:
    """A fresh, stateless critique of ``program`` (previews stored under ``files`` when
    given)."""
    from matloom.author.stages.critique import critique_program
    from matloom.author.views import image_input, png_bytes

    assert run.critic is not None
    cfg = run.config
    signals = cfg.effective_signals()
    size = cfg.critique_size
    renders = []
    if "render" in signals and run.critic.accepts_images:
        for view in run.views:
            image = renderer.image(program, size, view)
            path = None
            if files is not None:
                path = f"{files}.png" if view == "flat" else f"{files}_{view}.png"
                run.store.write_file(path, png_bytes(image))
            renders.append(image_input(image, path))
    stats = None
    if "stats" in signals:
        stats = renderer.stats(program, cfg.critic_stats, grid=cfg.stats_grid, size=size)
    return critique_program(
        run.critic,
        run.record.prompt,
        index,
        program,
        signals=signals,
        renders=renders,
        views=run.views,
        stats=stats,
        retries=cfg.critic_retries,
        max_reply_chars=cfg.max_reply_chars,
    )


def _objective(run: Run, kind: str, renderer: Renderer, index: int) -> Callable[[str], float]:
    """Program text -> objective value (higher is better for scorer and critic)."""
    size = run.config.polish_size
    if kind == "scorer":
        assert run.scorer is not None
        scorer, prompt = run.scorer, run.record.prompt
        return lambda text: float(scorer.score([_preview(run, text, size)], prompt)[0])
    if kind == "reference":
        from matloom.render.compare_stats import image_stats, stats_distance

        assert run.renderer.reference is not None
        photo = image_stats(run.renderer.reference.at(size))
        return lambda text: stats_distance(image_stats(_preview(run, text, size)), photo)

    def critic(text: str) -> float:
        result = _critic_score(run, renderer, text, index)
        return float(result.match_score) if result.ok and result.match_score is not None else 0.0

    return critic


def _minimised(
    space: Space, value: Callable[[str], float], higher: bool, notify: Callable[[int], None]
) -> Callable[[np.ndarray], float]:
    """The objective CMA-ES minimises over points of ``space`` (:data:`PENALTY` for a point
    whose program cannot be written or evaluated, or scores non-finite)."""
    count = [0]

    def f(x: np.ndarray) -> float:
        count[0] += 1
        notify(count[0])
        try:
            v = value(space.text(x))
        except (ValueError, ArithmeticError):
            return PENALTY
        if not np.isfinite(v):
            return PENALTY
        return -v if higher else v

    return f


def _parameters(space: Space, x: np.ndarray | None) -> list[FittedParamRecord]:
    after = space.values(x) if x is not None else {}
    records = []
    for param in space.params:
        dims = [d for d in space.dims if d.address == param.address]
        before = param.value if isinstance(param.value, tuple) else (param.value,)
        value = after.get(param.address)
        records.append(
            FittedParamRecord(
                address=param.address,
                label=param.label,
                kind=param.kind,
                low=[round(d.low, 10) for d in dims],
                high=[round(d.high, 10) for d in dims],
                before=[float(v) for v in before],
                after=[]
                if value is None
                else [float(v) for v in (value if isinstance(value, tuple) else (value,))],
                tied=list(space.ties.get(param.address, ())),
            )
        )
    return records


def polish_stage(run: Run) -> None:
    """Fit, guard and record (see the module docstring); nothing when ``polish`` is none or
    the record already holds a finished fit."""
    record, cfg = run.record, run.config
    if cfg.polish == "none" or (record.polish is not None and record.polish.done):
        return
    from matloom.author.views import Renderer
    from matloom.lang.api import parse

    base = chosen_final(record)
    entry = PolishRecord(program_index=base.program_index, variant=base.variant, seed=cfg.seed)
    record.polish = entry
    kind = _objective_kind(run)
    views = run.views if kind == "critic" else ("flat",)
    space = fit_space(parse(base.program), visible=visible_maps(views))
    if kind is None or space is None:
        entry.skipped = (
            "no scorer, reference photo or critic to fit against"
            if kind is None
            else "the program exposes no continuous numeric parameter the previews show"
        )
        entry.done = True
        run.store.save()
        return
    entry.objective, entry.better = kind, "higher" if HIGHER_IS_BETTER[kind] else "lower"
    entry.parameters = _parameters(space, None)
    renderer = Renderer(run.renderer.session, reference=run.renderer.reference)
    budget = cfg.polish_evaluations
    if kind == "critic":
        budget = min(budget, cfg.polish_critic_calls)
    message = f"fitting {len(space.params)} parameter(s) against the {kind}"
    run.notify("polish", message)
    higher = HIGHER_IS_BETTER[kind]
    objective = _minimised(
        space,
        _objective(run, kind, renderer, base.program_index),
        higher,
        lambda n: run.notify("polish", message, done=n, total=budget),
    )
    start = time.perf_counter()
    fit = cmaes_minimise(
        objective, space.start(), seed=cfg.seed + 1, evaluations=budget, seconds=cfg.polish_seconds
    )
    entry.evaluations, entry.seconds = fit.evaluations, time.perf_counter() - start
    sign = -1.0 if higher else 1.0
    entry.objective_before = sign * fit.start_value if fit.start_value < PENALTY else None
    entry.objective_after = sign * fit.value if fit.value < PENALTY else None
    entry.parameters = _parameters(space, fit.x)
    entry.program = space.text(fit.x)
    if not fit.value < fit.start_value:
        entry.reason = f"the fit found nothing better than the unfitted values ({fit.stopped})"
    else:
        _guard(run, renderer, entry, base)
    entry.done = True
    run.store.save()


def _guard(run: Run, renderer: Renderer, entry: PolishRecord, base: FinalRecord) -> None:
    """Keep the fit only when the critic does not score it lower than the unfitted program."""
    assert entry.program is not None
    if run.critic is None or not run.config.effective_signals():
        if entry.objective == "reference":
            # measured: fitted to a photo's global statistics with nothing to check it, the
            # programs looked less like the photo to blind judges (6 photos, 50 -> 43 of 100:
            # the statistics cannot tell which part takes which colour, nor a scale from a
            # texture); the fit is recorded, the unfitted program is exported
            entry.reason = (
                "the photo statistics improved, but no critic can check that the fit looks "
                "more like the photo (unchecked fits looked less like it), so the unfitted "
                "program is kept; the fitted one is in the record"
            )
            return
        entry.kept = True
        entry.reason = "the objective improved; no critic to check the fit (kept unchecked)"
        return
    run.notify("polish", "the critic compares the fitted and the unfitted program")
    before = _critic_score(run, renderer, base.program, base.program_index, GUARD_FILES["before"])
    after = _critic_score(run, renderer, entry.program, base.program_index, GUARD_FILES["after"])
    entry.guard = [before, after]
    entry.critic_before = before.match_score if before.ok else None
    entry.critic_after = after.match_score if after.ok else None
    if entry.critic_before is None or entry.critic_after is None:
        entry.reason = "the critic gave no usable score, so the unfitted program is kept"
    elif entry.critic_after < entry.critic_before:
        entry.reason = (
            f"the critic scored the fit lower ({entry.critic_after} < {entry.critic_before}), "
            "so the unfitted program is kept"
        )
    else:
        entry.kept = True
        entry.reason = (
            f"the objective improved and the critic did not score the fit lower "
            f"({entry.critic_after} >= {entry.critic_before})"
        )
