"""The search space and the CMA-ES loop of ``--polish cmaes`` (no run, model or record here).

**Space.** The program's exposed parameters (:func:`matloom.lang.params.listing`) that are
continuous: colours (three dimensions each), scalars, frequencies, sizes and angles; counts
and seeds are left alone (a count changes the cost, a seed is the seed search's), and so are
a literal ``metallic`` (a choice, 0 or 1) and the bottom layer's coverage. At most
:data:`MAX_PARAMS` parameters are fitted, chosen by :func:`priority` (colours, then the
layers' literal channel values, then frequencies and sizes, then the rest; source order
within each). Static parameters of calls of one function that have the same name and value
(the bricks' and their edges' ``brick_width``) are one parameter (:func:`tie_key`): a
program that repeats a number there means the same thing. A parameter that changes no map the
objective can see (the caller says which) is left alone. Each one moves inside a window
around its current value, cut to its registry range: a colour component by
:data:`COLOUR_RADIUS` levels, a frequency or a positive size by a factor of 2 either way, an
angle by :data:`ANGLE_RADIUS` degrees, another ranged scalar by a quarter of its range, an
unbounded one by half its value (at least 0.1). CMA-ES works in [0, 1] per dimension, mapped
linearly onto the windows; values are rounded (colours to whole levels, others to
:data:`DIGITS` significant digits) before the program is written, so what is scored is what
would be kept.

**Search.** :func:`cmaes_minimise` evaluates the start first, then runs the ``cma`` package's
CMA-ES (bounded to [0, 1], its own Gaussian samples drawn from a generator seeded by the run's
seed, so a fit is reproducible) until the evaluation budget or the time limit is spent, and
returns the best point seen (the start when nothing beat it). A one-parameter fit runs in two
dimensions, the second unread (the ``cma`` package does not take one).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from matloom.lang import ast as A
from matloom.lang.params import Listing, Param, Value, edit_program, listing

#: Most parameters fitted at once.
MAX_PARAMS = 12
#: Kinds of parameter that are fitted.
FITTED_KINDS = frozenset({"colour", "scalar", "frequency", "size", "angle"})
#: Parameters never fitted: the bottom layer's coverage only lets the uncovered background
#: through (no material property).
NOT_FITTED = frozenset({"layer:1.alpha"})
#: Channels never fitted: metallic is a choice of material (0 or 1), not a dial.
NOT_FITTED_CHANNELS = frozenset({"metallic"})
#: A colour component moves at most this many sRGB levels.
COLOUR_RADIUS = 64.0
#: An angle moves at most this many degrees.
ANGLE_RADIUS = 45.0
#: Significant digits kept of a fitted number (colours: whole levels).
DIGITS = 4
#: CMA-ES's initial step, in window widths.
SIGMA0 = 0.25
#: Objective value of a point whose program cannot be written or rendered.
PENALTY = 1e9


class PolishUnavailableError(ValueError):
    """The ``cma`` package is not installed (the ``polish`` extra)."""


def require_cma() -> None:
    """Raise :class:`PolishUnavailableError` unless ``cma`` can be imported."""
    try:
        import cma  # noqa: F401
    except ImportError:
        raise PolishUnavailableError(
            "--polish cmaes needs the cma package: pip install 'matloom[polish]'"
        ) from None


@dataclass(frozen=True)
class Dimension:
    """One searched number: a parameter (and colour component) and its window."""

    address: str
    component: int | None
    low: float
    high: float
    start: float
    integer: bool = False


def _round(value: float, integer: bool) -> float:
    if integer:
        return float(round(value))
    if value == 0 or not math.isfinite(value):
        return value
    digits = DIGITS - 1 - math.floor(math.log10(abs(value)))
    return round(value, digits)


def _window(param: Param, value: float) -> tuple[float, float]:
    lo, hi = param.low, param.high
    if param.kind == "colour":
        a, b = value - COLOUR_RADIUS, value + COLOUR_RADIUS
    elif param.kind in ("frequency", "size") and value > 0:
        a, b = value / 2, value * 2
    elif param.kind == "angle":
        a, b = value - ANGLE_RADIUS, value + ANGLE_RADIUS
    elif lo is not None and hi is not None:
        a, b = value - (hi - lo) / 4, value + (hi - lo) / 4
    else:
        reach = max(abs(value) / 2, 0.1)
        a, b = value - reach, value + reach
    return max(a, lo) if lo is not None else a, min(b, hi) if hi is not None else b


@dataclass(frozen=True)
class Space:
    """The fitted parameters of one program and how a point in [0, 1]^n becomes a program."""

    program: A.Program
    listed: Listing
    params: tuple[Param, ...]
    dims: tuple[Dimension, ...]
    #: A fitted parameter's address -> the addresses that move with it (see :func:`tie_key`).
    ties: dict[str, tuple[str, ...]] = field(default_factory=dict)

    def start(self) -> np.ndarray:
        """The program's own values, as a point."""
        return np.array([(d.start - d.low) / (d.high - d.low) for d in self.dims])

    def values(self, x: np.ndarray) -> dict[str, Value]:
        """Parameter values at point ``x`` (rounded; colours as (r, g, b))."""
        out: dict[str, list[float]] = {}
        for d, u in zip(self.dims, np.clip(x, 0.0, 1.0), strict=True):
            out.setdefault(d.address, []).append(
                _round(d.low + float(u) * (d.high - d.low), d.integer)
            )
        values: dict[str, Value] = {
            a: (tuple(v) if len(v) == 3 else v[0])  # type: ignore[misc]
            for a, v in out.items()
        }
        for address, value in list(values.items()):
            for other in self.ties.get(address, ()):
                values[other] = value
        return values

    def text(self, x: np.ndarray) -> str:
        """The program with the values at ``x`` (canonical text). ValueError when a value is
        refused (an open range end)."""
        from matloom.lang.printer import format_program

        edited, _ = edit_program(self.program, self.values(x), self.listed)
        return format_program(edited, comments=True)


def _fitted(param: Param) -> bool:
    head, _, rest = param.address.partition(".")
    channel = rest if head.startswith("layer:") and "." not in rest else None
    return (
        param.kind in FITTED_KINDS
        and param.address not in NOT_FITTED
        and channel not in NOT_FITTED_CHANNELS
    )


def priority(param: Param) -> int:
    """Which parameters are fitted first (lower first): colours, then a layer's literal
    channel values (``layer:2.roughness``), then frequencies and sizes, then the rest."""
    if param.kind == "colour":
        return 0
    if param.address.startswith("layer:") and param.address.count(".") == 1:
        return 1
    return 2 if param.kind in ("frequency", "size") else 3


def tie_key(param: Param) -> tuple[str, str, float] | None:
    """Static parameters of calls of one function with one name and one value move together
    (``Bricks(brick_width=1)`` for the bricks and ``Bricks(brick_width=1, output="edge")`` for
    their edges): ``(function, parameter, value)``; None for other parameters."""
    parts = param.address.split(".")
    if len(parts) < 3 or not parts[-2][:1].isupper() or isinstance(param.value, tuple):
        return None
    return parts[-2].split("#")[0], parts[-1], float(param.value)


def fit_space(
    program: A.Program,
    max_params: int = MAX_PARAMS,
    visible: frozenset[str] | None = None,
) -> Space | None:
    """The search space of ``program``; None when it exposes nothing that can move.
    ``visible``: the output maps the objective can see (a parameter that changes none of
    them is left alone, not drifted at random); None: every map."""
    listed = listing(program)
    params: list[Param] = []
    dims: list[Dimension] = []
    groups: dict[tuple[str, str, float], list[str]] = {}
    for param in listed[0]:
        key = tie_key(param)
        if key is not None:
            groups.setdefault(key, []).append(param.address)
    ties: dict[str, tuple[str, ...]] = {}
    tied: set[str] = set()
    for param in sorted(listed[0], key=priority):
        if len(params) >= max_params:
            break
        if not _fitted(param) or param.address in tied:
            continue
        if visible is not None and not visible & set(param.affects):
            continue
        key = tie_key(param)
        if key is not None and len(groups[key]) > 1:
            ties[param.address] = tuple(a for a in groups[key] if a != param.address)
            tied.update(groups[key])
        values = param.value if isinstance(param.value, tuple) else (param.value,)
        mine = []
        for k, value in enumerate(values):
            low, high = _window(param, float(value))
            if high - low > 1e-9 * max(1.0, abs(float(value))):
                mine.append(
                    Dimension(
                        param.address,
                        k if len(values) == 3 else None,
                        low,
                        high,
                        min(max(float(value), low), high),
                        integer=param.kind == "colour",
                    )
                )
        if len(mine) == len(values):  # every component can move
            params.append(param)
            dims.extend(mine)
    if not dims:
        return None
    return Space(program, listed, tuple(params), tuple(dims), ties)


@dataclass(frozen=True)
class FitResult:
    """The best point seen and what the search cost."""

    x: np.ndarray
    value: float
    start_value: float
    evaluations: int
    seconds: float
    #: Why the search ended: "budget", "time" or "converged".
    stopped: str


def cmaes_minimise(
    objective: Callable[[np.ndarray], float],
    x0: np.ndarray,
    *,
    seed: int,
    evaluations: int,
    seconds: float,
    sigma0: float = SIGMA0,
) -> FitResult:
    """Minimise ``objective`` over [0, 1]^n from ``x0`` (see the module docstring)."""
    import cma

    start = time.perf_counter()
    best_x, best = np.asarray(x0, dtype=np.float64), float(objective(x0))
    start_value, used = best, 1
    n = len(best_x)
    if n == 1:  # the cma package needs two dimensions: a second one that nothing reads
        inner = objective
        objective = lambda x: inner(x[:1])  # noqa: E731
        x0 = np.append(best_x, 0.5)
    rng = np.random.default_rng(seed)
    remaining = evaluations - used
    popsize = max(2, min(4 + int(3 * math.log(len(x0))), remaining // 2 or 1))
    options = {
        "bounds": [0.0, 1.0],
        "popsize": popsize,
        "randn": lambda lam, n: rng.standard_normal((lam, n)),
        "verbose": -9,
        "verb_log": 0,
        "verb_disp": 0,
        "maxfevals": max(evaluations, popsize),
        "tolfun": 1e-9,
    }
    es = cma.CMAEvolutionStrategy(np.clip(x0, 0.0, 1.0).tolist(), sigma0, options)
    stopped = "converged"
    while True:
        if used + popsize > evaluations:
            stopped = "budget"
            break
        if es.stop():
            break
        points = es.ask()
        values = []
        for point in points:
            if time.perf_counter() - start > seconds:
                break
            values.append(float(objective(np.asarray(point))))
            used += 1
        if values:
            k = int(np.argmin(values))
            if values[k] < best:
                best, best_x = values[k], np.asarray(points[k], dtype=np.float64)[:n]
        if len(values) < len(points):
            stopped = "time"
            break
        es.tell(points, values)
    return FitResult(
        x=best_x,
        value=best,
        start_value=start_value,
        evaluations=used,
        seconds=time.perf_counter() - start,
        stopped=stopped,
    )
