"""Evaluation: AST -> sampled fields -> composited :class:`MaterialMaps`.

:func:`evaluate` picks a schedule: the fused, banded one (:mod:`matloom.engine.schedules.banded`) for a
backend with compiled kernels, else the dense one (:mod:`matloom.engine.schedules.dense`). Both
run the one interpreter (:mod:`matloom.engine.interpret`) over the op table
(:mod:`matloom.ops`) and give the same maps, bit for bit.
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np

from matloom.engine.backends import Backend, session_backend
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import (
    Coords,
    EvalStats,
    Evaluator,
    Field,
    Frame,
    layer_fields,
)
from matloom.engine.limits import (
    DEFAULT_LIMITS,
    EVALUATE,
    Limits,
    Usage,
    check_request,
    check_size,
    request_cost,
)
from matloom.engine.maps import MaterialMaps, View
from matloom.engine.schedules.dense import evaluate_dense
from matloom.engine.session import Session, default_session, running
from matloom.lang import ast as A
from matloom.lang.api import parse
from matloom.lang.constants import resolve_static
from matloom.lang.macros import expand_program
from matloom.lang.seeds import canonicalize_seeds, has_seedless_noise

__all__ = [
    "Coords",
    "EvalStats",
    "Evaluator",
    "Field",
    "Frame",
    "evaluate",
    "layer_fields",
    "prepare",
]


def prepare(
    program_or_text: A.Program | str, program_seed: int = 0, *, session: Session | None = None
) -> A.Program:
    """Parse (if text) and make omitted seeds explicit so evaluation is deterministic (named
    static values written out, :func:`~matloom.lang.constants.resolve_static`). Texts
    are parsed once per ``session`` (default: :func:`default_session`): its ``parsed`` and
    ``prepared`` caches hold the (immutable, so shareable) programs."""
    if not isinstance(program_or_text, str):
        return _with_seeds(program_or_text, program_seed)
    s = session or default_session()
    text = program_or_text

    def seeded() -> A.Program:
        return _with_seeds(s.cached("parsed", text, lambda: parse(text)), program_seed)

    return s.cached("prepared", (text, program_seed), seeded)


def _with_seeds(program: A.Program, program_seed: int) -> A.Program:
    """Omitted seeds made explicit, parameterised Defines expanded (:mod:`matloom.lang.macros`:
    after the seeds, so every use of one shares its body's seeds, as the canonical text says)
    and named static values (``Bricks(mortar=grout)``) written out
    (:mod:`matloom.lang.constants`), as the interpreter reads them."""
    if has_seedless_noise(program):
        program = canonicalize_seeds(program, program_seed)
    return resolve_static(expand_program(program))


def evaluate(
    program_or_text: A.Program | str,
    width: int = 512,
    height: int = 512,
    *,
    backend: str | Backend = "auto",
    view: View | tuple[float, float, float, float] | None = None,
    ao_radius_units: float | None = None,
    program_seed: int = 0,
    limits: Limits = DEFAULT_LIMITS,
    stats: EvalStats | None = None,
    usage: Usage = EVALUATE,
    tileable: bool = False,
    session: Session | None = None,
) -> MaterialMaps:
    """Evaluate a program into composited float32 maps at ``width`` x ``height``.

    ``view`` overrides the program's View; ``ao_radius_units`` makes AO resolution-independent
    (default: the reference's 8 texels). Omitted seeds are derived from ``program_seed``.
    Raises :class:`~matloom.engine.limits.LimitError` before any work when the request exceeds
    a limit (``usage``: what the caller makes of the maps too, e.g. a tiled preview).
    ``tileable=True`` (or ``View(..., tileable=True)`` in the program, or a tileable ``view``)
    makes every map repeat seamlessly with the View's width and height (docs/tileable.md).
    ``session`` (default: :func:`~matloom.engine.session.default_session`) decides what
    ``backend="auto"`` means and holds the parse caches; the evaluation runs under its lock
    (re-entrant: a caller that holds it already, like a render job, is fine), so threads that
    share a session never run the kernels at once.
    """
    s = session or default_session()
    program = prepare(program_or_text, program_seed, session=s)
    check_size(width, height, limits=limits)
    s.evaluations += 1
    if isinstance(backend, Backend):
        be = backend
    else:
        work = width * height * request_cost(program, width, height, usage, limits).nodes
        be = session_backend(s, backend, width * height, work)
    check_request(program, width, height, fused=be.fused, usage=usage, limits=limits)
    if not program.layers:
        raise ValueError("material has no layers: add at least one Layer(...) to Material(...)")
    v = view if isinstance(view, View) else View(*(view or program.view_tuple))
    if (tileable or program.tileable) and not v.tileable:
        v = replace(v, tileable=True)
    if v.unit_m is None and program.unit_m is not None:
        v = replace(v, unit_m=program.unit_m)
    x, y = sample_axes(v, width, height)
    with s.lock, running(s):  # numba's compile events go to this session's reporter
        return _run(program, x, y, v, be, ao_radius_units, stats)


def _run(
    program: A.Program,
    x: np.ndarray,
    y: np.ndarray,
    v: View,
    be: Backend,
    ao_radius_units: float | None,
    stats: EvalStats | None,
) -> MaterialMaps:
    """The schedule for ``be``: fused and banded for compiled kernels, else dense."""
    if be.fused:  # same maps as below, bit for bit (see matloom.engine.schedules.banded)
        from matloom.engine.schedules.banded import evaluate_fused

        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore", RuntimeWarning)
            return evaluate_fused(
                program, x, y, v, be, ao_radius_units=ao_radius_units, stats=stats
            )
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        return evaluate_dense(program, x, y, v, be, ao_radius_units=ao_radius_units, stats=stats)
