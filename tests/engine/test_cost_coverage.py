"""The cost model covers every loop (issue 22, item 2 and Build 3).

Every registry function is evaluated over a sweep of each of its numeric static parameters,
from small values to the extremes the checker accepts (one enum choice at a time), and its
measured time per texel, divided by the node evaluations the cost model counts for it
(:func:`matloom.lang.cost.expanded_cost`), must stay within :data:`FACTOR` of the same ratio for
a baseline of element-wise operations measured in the same process. A primitive whose kernels
loop more than its parameters' counted cost (``Weave(over=1048576, shift=2, output="along")``
counted 2 and looped 2^20 times) fails here; so would a new primitive without a work rule for a
loop, since the sweep reads the registry.

Not a timing assertion: only ratios of times measured back to back are compared, each the
minimum of several runs once it looks over, against a generous factor (measured ratios stay
below about a third of it). A case still running at twice its allowance is stopped and fails.
"""

from __future__ import annotations

import itertools
import math
import signal
import time
import warnings
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np
import pytest

from matloom.engine.backends import get_backend
from matloom.engine.evaluate import Evaluator, prepare
from matloom.lang.api import analyse
from matloom.lang.cost import expanded_cost
from matloom.ops import OPS
from matloom.vocab import FUNCTIONS, Kind
from matloom.vocab.spec import FunctionSpec, ParamSpec, Returns

#: Largest allowed (time per texel / counted cost) of a case over that of the baseline.
FACTOR = 50
SIZES = (16, 64)
#: Measurements of a case that looks over the factor, each paired with the baseline's.
RETRIES = 5
BASELINE = "X() * Y() + X() * 0.5"
#: Values tried for every numeric parameter (those the parameter's constraints reject are
#: dropped, and so are programs the checker rejects: they never run).
SWEEP: tuple[float, ...] = (-1e300, -1.0, 0.0, 1e-300, 0.25, 1.0, 16.0, 2.0**20, 1e300)
#: Path segments drawn by the Fill/Stroke cases.
SEGMENT_COUNTS = (1, 10, 100, 1000)
#: Motif of Tile and operands of the other expression parameters, in order.
MOTIF = "Fill(Ellipse(0, 0, 0.3, 0.2))"
OPERANDS = ("X()", "Y()", "X() * Y()")
SHAPES = ("Rect(0.1, 0.2, 0.6, 0.5, 0.05)", "Ellipse(0.5, 0.5, 0.3, 0.2)")


def _number(v: float, p: ParamSpec) -> str | None:
    """``v`` as written for ``p`` (None when ``p`` rejects it)."""
    if p.kind is Kind.INT:
        if not float(v).is_integer() or abs(v) > 2.0**62:
            return None
        v = int(v)
    if p.check_value(v) is not None:
        return None
    return repr(v)


def _call(spec: FunctionSpec, given: dict[str, str], extra: tuple[str, ...] = ()) -> str:
    """A call of ``spec``: ``given`` arguments, required ones filled in, ``extra`` segments."""
    args: list[str] = []
    operands = iter(OPERANDS)
    for p in spec.params:
        if p.name in given:
            args.append(f"{p.name}={given[p.name]}")
        elif p.required and p.kind is Kind.EXPR:
            value = MOTIF if spec.instances else next(operands)
            args.append(f"{p.name}={value}")
        elif p.required and p.kind is Kind.SHAPE:
            args.append(f"{p.name}={SHAPES[1]}")
        elif p.required:  # a size or a coordinate inside the View
            args.append(f"{p.name}=0.3")
    if extra:  # positional: segments follow the parameters
        args = [a.split("=", 1)[1] for a in args] + list(extra)
    return f"{spec.name}({', '.join(args)})"


def _settings(spec: FunctionSpec) -> list[dict[str, str]]:
    """The defaults, then each enum choice and each boolean on its own."""
    out: list[dict[str, str]] = [{}]
    for p in spec.params:
        if p.kind is Kind.ENUM:
            out += [{p.name: f'"{c}"'} for c in p.choices if c != p.default]
        elif p.kind is Kind.BOOL:
            out.append({p.name: str(not p.default)})
    return out


def _numeric(spec: FunctionSpec) -> list[ParamSpec]:
    return [p for p in spec.params if p.kind in (Kind.INT, Kind.FLOAT)]


def _far(spec: FunctionSpec) -> dict[str, str]:
    """Every numeric parameter at the far end of its search range (e.g. Weave's shift=3: the
    draft steps that need a search), where that is a valid value."""
    out: dict[str, str] = {}
    for p in _numeric(spec):
        text = None if p.search is None or p.is_seed else _number(p.search[1], p)
        if text is not None:
            out[p.name] = text
    return out


def _field_cases(spec: FunctionSpec) -> Iterator[str]:
    """Every enum setting x every numeric parameter x the sweep, the other parameters at their
    defaults or at the far ends of their search ranges."""
    for setting, background in itertools.product(_settings(spec), ({}, _far(spec))):
        yield _call(spec, {**background, **setting})
        for p in _numeric(spec):
            for v in SWEEP:
                text = _number(v, p)
                if text is not None:
                    yield _call(spec, {**background, **setting, p.name: text})


def _geometry_cases(spec: FunctionSpec) -> Iterator[str]:
    """A shape or path segment, drawn by every Fill/Stroke setting, its numbers swept, and a
    path of each of :data:`SEGMENT_COUNTS` segments."""
    drawers = [
        (FUNCTIONS[name], setting)
        for name in ("Fill", "Stroke")
        for setting in _settings(FUNCTIONS[name])
    ]
    extra = ("LineTo(1, 1)",) if spec.variadic is not None else ()  # a Path's one segment
    variants = [_call(spec, {}, extra)] if spec.returns is Returns.SHAPE else []
    for p in _numeric(spec):
        for v in SWEEP:
            text = _number(v, p)
            if text is not None:
                variants.append(_call(spec, {p.name: text}, extra))
    if spec.returns is Returns.SEGMENT:  # inside a Path, repeated
        segment = _call(spec, {})
        variants = [f"Path(0, 0, {v})" for v in variants]
        variants += [f"Path(0, 0, {', '.join([segment] * n)})" for n in SEGMENT_COUNTS]
    for (drawer, setting), shape in itertools.product(drawers, variants):
        yield _call(drawer, {**setting, "shape": shape})


def cases(spec: FunctionSpec) -> list[str]:
    if spec.returns is Returns.FIELD:
        return list(_field_cases(spec))
    return list(_geometry_cases(spec))


# ---------------------------------------------------------------------------- measuring
def _program(expr: str) -> str:
    return f"Material(Layer(1).height({expr}))"


def _grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Full float32 grids (as after a rotation), so that no operand stays a broadcast axis."""
    axis = np.linspace(0.01, 0.99, n, dtype=np.float32)
    x, y = np.meshgrid(axis, axis[::-1])
    return np.ascontiguousarray(x), np.ascontiguousarray(y)


class Overrun(Exception):
    """A case ran past its allowance."""


@contextmanager
def _deadline(seconds: float) -> Iterator[None]:
    """Raise :class:`Overrun` in the evaluation after ``seconds`` of this process's CPU time
    (POSIX profiling timer: other processes on a busy machine do not count)."""

    def stop(signum: int, frame: object) -> None:
        raise Overrun

    previous = signal.signal(signal.SIGPROF, stop)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)


class Meter:
    """Seconds per (texel x counted node evaluation) of expressions, relative to a baseline."""

    def __init__(self, backend: str = "numpy") -> None:
        self.backend = get_backend(backend)
        self.grids = {n: _grid(n) for n in SIZES}
        self.unit = {n: self._per_unit(BASELINE, n, runs=9) for n in SIZES}

    def _run(self, expr: str, n: int, allowance: float) -> float:
        program = prepare(_program(expr))
        node = program.layers[0].channel("height").args[0]
        x, y = self.grids[n]
        ev = Evaluator(program, x, y, self.backend)
        start = time.perf_counter()
        try:
            with _deadline(allowance), warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                ev.field(node)
        except Overrun:
            return math.inf
        except Exception:  # noqa: BLE001 - an error after a long loop still took the time
            pass
        return time.perf_counter() - start

    def _per_unit(self, expr: str, n: int, runs: int) -> float:
        nodes = expanded_cost(prepare(_program(expr))).nodes
        return min(self._run(expr, n, 60.0) for _ in range(runs)) / nodes

    def ratio(self, expr: str) -> tuple[float, int]:
        """The largest (time / counted cost) / the baseline's over :data:`SIZES`, and the
        counted cost. A case over the factor is measured again, each time right after the
        baseline (a busy machine slows both), and keeps its smallest ratio."""
        nodes = expanded_cost(prepare(_program(expr))).nodes
        worst = 0.0
        for n in SIZES:
            allowance = 2 * FACTOR * self.unit[n] * nodes + 0.2
            best = self._run(expr, n, allowance) / nodes / self.unit[n]
            for _ in range(RETRIES if best > FACTOR else 0):
                unit = self._per_unit(BASELINE, n, runs=3)
                best = min(best, self._run(expr, n, allowance) / nodes / unit)
                if best <= FACTOR:
                    break
            worst = max(worst, best)
        return worst, nodes


def accepted(expr: str) -> bool:
    """True when ``check`` accepts the program (rejected ones never run)."""
    _, diags = analyse(_program(expr))
    return not any(d.is_error for d in diags)


@pytest.fixture(scope="module")
def meter() -> Meter:
    return Meter("numpy")


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="needs POSIX interval timers")
@pytest.mark.parametrize("name", list(FUNCTIONS))
def test_counted_cost_bounds_the_work_of_every_primitive(meter: Meter, name: str) -> None:
    """Time per texel / counted cost within FACTOR of the baseline's, over the sweep."""
    measured, over = 0, []
    for expr in cases(FUNCTIONS[name]):
        if not accepted(expr):
            continue
        ratio, nodes = meter.ratio(expr)
        measured += 1
        if ratio > FACTOR:
            over.append(f"{expr[:100]}: {ratio:.0f}x the baseline per counted node ({nodes:,})")
    assert measured, f"no accepted case of {name}"
    assert not over, "work beyond the counted cost:\n" + "\n".join(over)


# ---------------------------------------------------------------------------- the rules
def test_the_weave_of_the_issue_is_rejected_by_check_with_one_line() -> None:
    """The issue's reproducer counts its float search and is refused before any work."""
    text = _program('Weave(over=1048576, under=1, shift=2, output="along")')
    _, diags = analyse(text)  # a count: nothing is evaluated
    errors = [d for d in diags if d.is_error]
    assert [d.code for d in errors] == ["E071"]
    assert "Weave" in errors[0].message and errors[0].hint
    assert "\n" not in errors[0].message


def test_weave_along_counts_its_search_steps() -> None:
    from matloom.ops import work as W

    def work(**kw: object) -> int:
        params = {"output": "along", "over": 1, "under": 1, "shift": 1, **kw}
        return OPS["Weave"].work(params.__getitem__)

    assert work(over=3, under=2, shift=1) == W.WEAVE_ALONG  # closed form: no search
    assert work(over=3, under=2, shift=-1) == W.WEAVE_ALONG
    assert work(over=3, under=2, shift=2) == W.WEAVE_ALONG + W.WEAVE_ALONG_STEP * 4
    assert work(over=1048576, under=1, shift=2) > 12 * 2**20
    assert work(output="mask", over=1048576, under=1, shift=2) == W.WEAVE


def test_work_constants_match_the_kernels_and_registry() -> None:
    from matloom.engine.kernels.shapes import CUBIC_STEPS
    from matloom.ops import work as W

    assert W.CUBIC_EDGES == CUBIC_STEPS
    assert OPS["Tile"].work == W.tile_work(FUNCTIONS["Tile"].instances)
