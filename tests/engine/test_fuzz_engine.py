"""Fuzz the whole pipeline: random and mutated programs never raise an undocumented exception.

* programs from the random generator always evaluate;
* registry-driven mutants with extreme numbers (400-digit integers, 1e308, subnormals, NaN- and
  inf-producing expressions, huge Views) only ever fail with diagnostics (``ProgramError``) or a
  ``LimitError``, through check -> fmt -> evaluate.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest

import matloom
from matloom.engine.evaluate import evaluate
from matloom.engine.limits import LimitError
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.printer import format_program
from matloom.lang.random_program import RandomConfig, random_program, random_program_ast
from matloom.vocab import FUNCTIONS, FunctionSpec, Kind, PrintStyle

N_PROGRAMS = 2000
SHARDS = 8


@pytest.mark.fuzz  # about 2 minutes on 2 cores: `make test-fuzz`, run by .ci/run after `make test`
@pytest.mark.parametrize("shard", range(SHARDS))
def test_random_programs_evaluate(shard):
    for seed in range(shard, N_PROGRAMS, SHARDS):
        text = random_program(seed)
        maps = evaluate(text, 64, 64)
        assert maps.basecolor_linear.shape == (64, 64, 3)
        assert maps.normal.dtype == np.float32
        # non-finite values are allowed (Sqrt/Log/Div/Pow) but must be counted, never crash
        assert isinstance(maps.nonfinite_counts(), dict)


# ---------------------------------------------------------------------------- extreme numbers
# A registry-driven mutation fuzz: every numeric or field slot of every registry function (and
# every operator operand, layer alpha and channel argument) is replaced, one at a time, by an
# extreme number or a NaN/inf-producing expression. Each mutant goes through check -> fmt ->
# evaluate (8x8) and may only fail with diagnostics (ProgramError) or a LimitError.

_BIG = "9" * 300
EXTREMES: tuple[str, ...] = (
    "9" * 400,  # the longest literal the lexer reads, far beyond the float range
    "1" + "0" * 308,
    "9" * 308,  # still a float
    "9223372036854775808",  # 2**63, past int64
    "1e308",
    "-1e308",
    "1e-320",  # subnormal
    "-1e-320",
    "0",
    "-0",
    "(1e308 * 10)",
    "(-1e308 - 1e308)",
    f"({_BIG} * {_BIG})",  # exact int arithmetic past the float range
    "(2 ** 1024)",
    "(0 / 0)",
    "(1 / 1e-320)",
    "(0 ** -1)",
    "((0 - 1) ** 0.5)",
    "Sqrt(-1)",
    "Log(0)",
    "Floor(1e308)",
)

EXTREME_VIEWS: tuple[str, ...] = (
    "View(-1e308, -1e308, 1e308, 1e308)",
    "View(1e308, 0, -1e308, 1)",
    "View(0, 0, 1e-320, 1e-320)",
    "View(0, 0, 5e-324, 1)",
    f"View(0, 0, {'9' * 400}, 1)",
    f"View(0, 0, {_BIG} * {_BIG}, 1)",
    "View(0, 0, Sqrt(-1), 1)",
    "View(0, 0, Log(0), 1)",
    "View(0, 0, 0 / 0, 1)",
    "View(1e308, 1e308, 1.7976931348623157e308, 1.7976931348623157e308)",
    "View(-1e-320, 0, 1e-320, 1)",
    "View(-3e38, -3e38, 3e38, 3e38)",  # a span past the float32 sample grid
    "View(0, 0, 3e38, 3e38)",  # just inside it
    # tileable Views at the same extremes (the registry-wide tileable fuzz is
    # tests/engine/test_fuzz_tileable.py)
    "View(-1e308, -1e308, 1e308, 1e308, tileable=True)",
    "View(0, 0, 5e-324, 1, tileable=True)",
    "View(0, 0, 0 / 0, 1, tileable=True)",
    "View(-3e38, -3e38, 3e38, 3e38, tileable=True)",
    "View(0, 0, 3e38, 3e38, tileable=True)",
    "View(0, 0, 1e-300, 1e-300, tileable=True)",
)

_SENTINEL = 918273645
_SENTINEL_RE = re.compile(rf"(?<![\w.]){_SENTINEL}(?![\w.])")
_SMALL = RandomConfig(max_layers=1, max_depth=2, max_defs=1, channel_prob=0.2)
_MUTABLE = (Kind.INT, Kind.FLOAT, Kind.EXPR)
Slot = tuple[str, str]


def _rewrite(program: A.Program, replace_slot: Callable[[Slot], bool]) -> A.Program:
    """``program`` with the slots for which ``replace_slot`` is true set to the sentinel number.

    Slots are visited in a fixed order, so counting calls of ``replace_slot`` names a slot.
    """

    def expr(node: A.Node) -> A.Node:
        if isinstance(node, A.Call):
            spec = FUNCTIONS[node.func]
            args = tuple(_arg(spec, a) for a in node.args)
            return replace(node, args=args, extra=tuple(expr(e) for e in node.extra))
        if isinstance(node, A.BinOp):
            left, right = slot((node.op, "left"), node.left), slot((node.op, "right"), node.right)
            return replace(node, left=left, right=right)
        if isinstance(node, A.Neg):
            return replace(node, operand=slot(("-", "operand"), node.operand))
        return node

    def _arg(spec: FunctionSpec, arg: A.Arg) -> A.Arg:
        kind = spec.param(arg.param).kind  # type: ignore[union-attr]
        if kind in _MUTABLE:
            return replace(arg, value=slot((spec.name, arg.param), arg.value))
        return replace(arg, value=expr(arg.value)) if kind is Kind.SHAPE else arg

    def slot(key: Slot, node: A.Node) -> A.Node:
        return A.Num(_SENTINEL) if replace_slot(key) else expr(node)

    def layer(lay: A.Layer) -> A.Layer:
        alpha = None if lay.alpha is None else slot(("Layer", "alpha"), lay.alpha)
        chans = tuple(
            replace(c, args=tuple(slot((f".{c.name}", str(i)), a) for i, a in enumerate(c.args)))
            for c in lay.channels
        )
        return replace(lay, alpha=alpha, channels=chans)

    defines = tuple(replace(d, expr=slot(("Define", "expr"), d.expr)) for d in program.defines)
    return replace(program, defines=defines, layers=tuple(layer(x) for x in program.layers))


def _slots(program: A.Program) -> list[Slot]:
    found: list[Slot] = []
    _rewrite(program, lambda key: found.append(key) is not None)
    return found


def _with_sentinel_at(program: A.Program, index: int) -> str:
    """Canonical text of ``program`` with its ``index``-th slot set to the sentinel."""
    counter = iter(range(10**9))
    return format_program(_rewrite(program, lambda _key: next(counter) == index))


#: Slots whose value the canonical printer folds away, with a hand-written template instead.
_FOLDED_SLOTS: dict[Slot, str] = {
    # the printer clamps a corner radius to half the smaller side of the rectangle
    ("Rect", "radius"): f"Material(Layer(1).height(Fill(Rect(0, 0, 1, 1, {_SENTINEL}))))",
}


def _registry_slots() -> set[Slot]:
    """Every numeric/field parameter the registry declares (operators by their symbol)."""
    slots: set[Slot] = set()
    for spec in FUNCTIONS.values():
        if spec.print_style is PrintStyle.OPERATOR and spec.operator is not None:
            slots |= {(spec.operator, "left"), (spec.operator, "right")}
        else:
            slots |= {(spec.name, p.name) for p in spec.params if p.kind in _MUTABLE}
    return slots


@lru_cache(maxsize=1)
def _templates() -> dict[Slot, str]:
    """One program text per slot, with the sentinel number in that slot (first random program
    that has the slot; the search is deterministic)."""
    wanted = _registry_slots()
    out = dict(_FOLDED_SLOTS)
    for seed in range(2000):
        program = random_program_ast(seed, config=_SMALL)
        for index, key in enumerate(_slots(program)):
            if key in out:
                continue
            text = _with_sentinel_at(program, index)
            if len(_SENTINEL_RE.findall(text)) == 1:  # some print styles fold the value away
                out[key] = text
        if wanted <= set(out):
            break
    return out


def assert_documented_failures_only(text: str) -> str:
    """check -> fmt -> evaluate at 8x8; only diagnostics or a LimitError may stop it.

    Returns how it ended: "rejected", "limit" or "rendered".
    """
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        with pytest.raises(matloom.ProgramError):
            matloom.parse(text)
        return "rejected"
    canonical = format_program(program)
    again, diags_again = analyse(canonical)
    assert again is not None and not any(d.is_error for d in diags_again), canonical
    assert format_program(again) == canonical
    try:
        maps = evaluate(again, 8, 8)
    except LimitError:
        return "limit"
    assert maps.height.shape == (8, 8)
    assert isinstance(maps.nonfinite_counts(), dict)
    return "rendered"


def test_every_registry_slot_is_fuzzed() -> None:
    missing = _registry_slots() - set(_templates())
    assert not missing, sorted(missing)


@pytest.mark.parametrize("shard", range(SHARDS))
def test_extreme_numbers_in_every_slot(shard: int) -> None:
    cases = [(key, value) for key, template in sorted(_templates().items()) for value in EXTREMES][
        shard::SHARDS
    ]
    outcomes: dict[str, int] = {}
    for key, value in cases:
        text = value.join(_SENTINEL_RE.split(_templates()[key]))
        try:
            outcome = assert_documented_failures_only(text)
        except Exception as error:  # pragma: no cover - the failure report
            raise AssertionError(f"{key} = {value[:40]}: {error!r}\n{text}") from error
        outcomes[outcome] = outcomes.get(outcome, 0) + 1
    assert outcomes.get("rejected") and outcomes.get("rendered"), outcomes


@pytest.mark.parametrize("view", EXTREME_VIEWS)
def test_extreme_views(view: str) -> None:
    body = random_program(7, config=_SMALL).split("\n", 1)[1]
    assert assert_documented_failures_only(f"{view}\n{body}") in ("rejected", "rendered")
