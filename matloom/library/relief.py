"""The host's relief as an expression an overlay can follow.

Grime, moss, water and snow settle in the low parts of a surface (the mortar joints, the pits,
the cracks); wear and chips find its high parts. An overlay that names a ``relief`` Define in
its front matter gets it bound, when composed, to :func:`relief_of` the host: the rank of the
host's composite height over the surface (the maximum over the layers that cover a texel, as
the engine composites it), 0 at its lowest texel and 1 at its highest, piecewise linear between
quantiles measured on a small evaluation of the host, and weighted down for a relief too
shallow to see or a directional grain. A host with no relief, or one whose height lines would
be costly to evaluate twice, leaves the overlay's own stand-in value (see docs/library.md).
"""

from __future__ import annotations

import functools
import itertools

import numpy as np

from matloom.lang import ast as A
from matloom.lang.api import parse_expression
from matloom.lang.diagnostics import ProgramError
from matloom.lang.printer import format_expr, format_program
from matloom.lang.rewrite import map_seeds
from matloom.vocab import FUNCTIONS

#: Size of the evaluation that measures the host's height quantiles: a prime, so that no regular
#: pattern (a course of bricks) falls on the same texel phase every period and biases them.
MEASURE_SIZE = 101
#: Function families a height line may use and still be cheap to evaluate a second time
#: (anything else, a noise or a pattern written inside the line, is not repeated).
_CHEAP_FAMILIES = frozenset({"coord", "math", "mask"})
#: Below this spread (coordinate units) two heights count as one.
_FLAT = 1e-6
#: A relief whose 5th-to-95th percentile spread is below this share of the View's width is
#: flat to the eye (a polished stone, a brushed sheet): an overlay does not follow it; up to
#: :data:`_RELIEF_FULL` it follows it in part.
_RELIEF_SHALLOW = 0.0005
_RELIEF_FULL = 0.002
#: A texel no layer with a height line covers sits this far below every covered one.
_ABSENT = 1000.0


def _height_line(layer: A.Layer) -> A.Node | None:
    return next((c.args[0] for c in layer.channels if c.name == "height" and c.args), None)


def _cheap(node: A.Node) -> bool:
    """No call in ``node`` outside the cheap families (Defines are evaluated once each)."""
    return all(
        not isinstance(n, A.Call)
        or (n.func in FUNCTIONS and FUNCTIONS[n.func].family in _CHEAP_FAMILIES)
        for n in A.walk(node)
    )


def height_expr(program: A.Program) -> A.Node | None:
    """The program's composite height as one expression (None: no layer has a height line, or
    one is costly). A layer counts where its alpha is above 0 (the engine's coverage gate),
    whatever its opacity; where only layers without a height line cover, the height is 0."""
    parts: list[str] = []
    everywhere = zero = False  # a layer covers everywhere; one does with no height line
    for layer in program.layers:
        h = _height_line(layer)
        alpha = layer.alpha
        if isinstance(alpha, A.Num) and alpha.value <= 0:
            continue
        whole = alpha is None or isinstance(alpha, A.Num)
        if h is None:
            everywhere, zero = everywhere or whole, zero or whole
            continue
        if not _cheap(h) or not (alpha is None or _cheap(alpha)):
            return None
        if whole:
            everywhere = True
            parts.append(format_expr(h))
            continue
        gate = f"Threshold({format_expr(alpha)}, below_at=0, below_to=0, above_at=0, above_to=1)"
        parts.append(f"({format_expr(h)}) - (1 - {gate}) * {_ABSENT:g}")
    if not parts:
        return None
    if zero or not everywhere:
        parts.append("0")  # a covering layer with no height line, or the substrate
    return parse_expression(parts[0] if len(parts) == 1 else f"Max({', '.join(parts)})")


def relief_of(program: A.Program, height: str) -> tuple[A.Node, A.Node] | None:
    """(H, rank): the program's composite height H, and its rank over the surface, 0 to 1
    (0.2: a fifth of the surface lies lower), piecewise linear between measured quantiles, so
    "the lowest fifth" means the joints on a brick wall and the pits on a plaster one alike.
    The rank reads H as the Define ``height``. None when it has no height, it is costly, or
    it is flat."""
    measured = _measured_height(program)
    if measured is None:
        return None
    h, knots, weight = measured
    terms = []
    for (q0, v0), (q1, v1) in itertools.pairwise(knots):
        step = f"Clamp((H - ({v0:.6g})) / {max(v1 - v0, _FLAT):.6g})"
        terms.append(f"{step} * {q1 - q0:.6g}" if q1 - q0 != 1 else step)
    rank = " + ".join(terms).replace("H", height)
    if weight < 1:  # a grain, not a layout: the overlay mostly keeps its own patches
        rank = f"(({rank}) * {weight:g}) + {0.5 * (1 - weight):g}"
    return h, parse_expression(rank)


def height_span(program: A.Program) -> tuple[A.Node, float, float] | None:
    """(H, low, high): the program's composite height as one expression and its 1st and 99th
    percentiles over the surface, for a mask of its low parts (the joints, grooves, crevices)
    or its high ones (the tops, ridges); None when it has no height, a costly one, or one too
    shallow to see."""
    measured = _measured_height(program)
    if measured is None:
        return None
    h, knots, _ = measured
    return h, knots[0][1], knots[-1][1]


def _measured_height(
    program: A.Program,
) -> tuple[A.Node, tuple[tuple[float, float], ...], float] | None:
    """(H, knots, weight): the composite height expression, its measured (rank, height) knots
    and how fully an overlay follows it; None when it has no height, a costly one, or a flat
    one."""
    h = height_expr(program)
    if h is None:
        return None
    measured = _height_quantiles(program)
    if measured is None:
        return None
    knots, weight = measured
    return h, knots, weight


def _height_quantiles(
    program: A.Program,
) -> tuple[tuple[tuple[float, float], ...], float] | None:
    return _measured(format_program(_canonical_seeds(program)))


def _canonical_seeds(program: A.Program) -> A.Program:
    """``program`` with its explicit seeds numbered in order of first appearance: the measured
    range is then the same for every user seed (a reseed changes only the seeds)."""
    order: dict[int, int] = {}
    return map_seeds(program, lambda old: order.setdefault(old, len(order) + 1))


#: The ranks the piecewise relief passes through (its knots).
_RANKS = (0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)


#: A relief this lopsided (its median this far up from its 5th to its 95th percentile) is a
#: surface with joints, gaps or pits below it: what settles follows it fully.
_JOINTED = 0.7
#: A relief whose rank correlates this much more along one axis than the other (3 texels apart)
#: is a grain (brushing, bands, a weave) unless it has joints: an overlay following it would
#: draw stripes, so it follows it at :data:`_GRAIN_WEIGHT` only.
_ANISOTROPIC = 0.4
_GRAIN_WEIGHT = 0.25


def _weight(h: np.ndarray, width: float) -> float:
    """How fully an overlay follows the relief ``h`` (a square height map over a View
    ``width`` wide): by its depth (:data:`_RELIEF_SHALLOW`, 0 for a flat one), times 1 for
    joints or an isotropic relief and :data:`_GRAIN_WEIGHT` for a directional grain."""
    p5, p50, p95 = np.percentile(h, (5.0, 50.0, 95.0))
    depth = (p95 - p5) / (width or 1.0)
    deep = min(1.0, max(0.0, (depth - _RELIEF_SHALLOW) / (_RELIEF_FULL - _RELIEF_SHALLOW)))
    if deep == 0 or (p50 - p5) >= _JOINTED * (p95 - p5):
        return round(deep, 3)
    r = np.argsort(np.argsort(h.ravel(), kind="stable"), kind="stable").reshape(h.shape)
    r = (r - r.mean()) / (r.std() or 1.0)
    across = float((r * np.roll(r, 3, axis=1)).mean())
    down = float((r * np.roll(r, 3, axis=0)).mean())
    return round(deep * (_GRAIN_WEIGHT if abs(across - down) >= _ANISOTROPIC else 1.0), 3)


@functools.lru_cache(maxsize=256)
def _measured(text: str) -> tuple[tuple[tuple[float, float], ...], float] | None:
    """(rank, height) knots of the host's height, measured at :data:`MEASURE_SIZE` (the 1st and
    99th percentiles stand for its ends), and how fully an overlay follows it (:func:`_weight`);
    None when flat."""
    from matloom.engine.evaluate import evaluate

    try:
        maps = evaluate(text, MEASURE_SIZE, MEASURE_SIZE)
    except (ProgramError, ValueError):
        return None
    grid = np.asarray(maps.height, dtype=np.float64)
    if not np.isfinite(grid).all():
        return None
    h = grid.ravel()
    pct = [min(max(100.0 * r, 1.0), 99.0) for r in _RANKS]
    # rounded so that the bound expression reads cleanly and is the same on every machine
    values = [float(f"{v:.4g}") for v in np.percentile(h, pct)]
    if values[-1] - values[0] < _FLAT:
        return None
    knots: list[tuple[float, float]] = []
    for rank, v in zip(_RANKS, values, strict=True):
        if knots and v - knots[-1][1] < _FLAT:  # a plateau: one jump, not a zero-width step
            knots[-1] = (knots[-1][0], v)
            continue
        knots.append((rank, v))
    knots[-1] = (1.0, knots[-1][1])
    weight = _weight(grid, abs(maps.view.x2 - maps.view.x1))
    return (tuple(knots), weight) if weight > 0 else None
