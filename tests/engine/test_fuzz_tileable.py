"""Fuzz the tileable path with extreme values (issue "Reliability, third pass" #7).

Every numeric or field parameter of every registry function (read from the registry, so a new
function is fuzzed without a change here) gets each of the :data:`EXTREMES` (zeros, subnormals,
the float range's ends, integers past 2**53 and 2**63, literals past the float range, NaN- and
inf-producing expressions), in one of the :data:`TILEABLE_VIEWS` and one of the
:data:`CONTEXTS` (Scale, Translate warp, periodic wrappers, Tile) that the tileable analysis
treats differently; field slots take the value alone or as a coordinate's coefficient
(:data:`FIELD_FORMS`). Each program goes
through check (with the tileable analysis of W009/W010) and, when accepted, the ``--tileable``
render path at 4 x 4: :func:`matloom.cli.tileable.apply_tileable`, a tileable evaluation and
the manifest's seam ratios. Only the project's diagnostics (``ProgramError``) and
``LimitError`` may stop it; any other exception is a failure.

The full cross product (slots x values x Views x contexts) is large; every (slot, value) pair
is run once, with the View and the context cycling deterministically, so that every slot meets
every View and every value every View.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import pytest

import matloom
from matloom.cli.tileable import apply_tileable
from matloom.engine.evaluate import evaluate
from matloom.engine.limits import LimitError
from matloom.engine.tiling import manifest_entry
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.printer import format_program
from matloom.vocab import FUNCTIONS, FunctionSpec, Kind, PrintStyle, Returns
from matloom.vocab.layout import LAYOUT

EXTREMES: tuple[str, ...] = (
    "0",
    "-0",
    "1e-320",  # subnormal
    "-1e-320",
    "5e-324",  # the smallest subnormal
    "-5e-324",
    "2.2250738585072014e-308",  # the smallest normal float
    "1e-300",
    "-1e-300",
    "1e-9",
    "0.3333333333333333",
    "123456789.5",
    "1e300",
    "-1e300",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",  # the largest float
    "-1.7976931348623157e308",
    "9007199254740993",  # 2**53 + 1: not a float
    "9223372036854775808",  # 2**63: past int64
    "9" * 400,  # the longest literal the lexer reads, far past the float range
    "(2 ** 1024)",  # exact integer arithmetic past the float range
    "(1e308 * 10)",  # inf
    "(-1e308 - 1e308)",  # -inf
    "(1 / 1e-320)",  # inf by division
    "(0 / 0)",  # NaN
    "Sqrt(-1)",  # NaN
    "Log(0)",  # -inf
    "(0 - Log(0))",  # inf
    "1e999",  # a literal past the float range
    "1e-400",  # a literal that underflows to 0
    "inf",  # no such names: the language spells inf and NaN only as expressions
    "nan",
)

TILEABLE_VIEWS: tuple[str, ...] = (
    "View(0, 0, 1, 1, tileable=True)",
    "View(-1, -1, 1, 1, tileable=True, unit_m=0.5)",
    "View(0.0625, 0.125, 2.0625, 2.125, tileable=True)",
    "View(0, 0, 3, 0.5, tileable=True)",
    "View(1, 1, 0, 0, tileable=True)",  # reversed: mirrored, periods 1 x 1
    "View(0, 0, 1e-300, 1e-300, tileable=True)",  # periods near the bottom of the float range
    "View(-1e30, -1e30, 1e30, 1e30, tileable=True)",  # and near the top of float32's
)

#: Where the fuzzed call sits: each is analysed differently (frames scaled, warped, rotated by
#: 180 degrees, inside a periodic wrapper or Hash, as a Tile motif). ``{f}`` is the call.
CONTEXTS: tuple[str, ...] = (
    "{f}",
    "Scale({f}, 0.5, 2)",
    "Translate({f}, 0.25, X())",
    "Fract(({f}) + (X() * 3))",
    "Hash(({f}) + (X() * 2), Y() * 4, seed=1)",
    "Tile({f}, 0.5, 0.5, seed=2)",
    "Rotate({f}, 180)",
)

#: How an extreme value fills a field slot: alone, or as a coordinate's coefficient (what the
#: tileable analysis turns into cycles or cells per View period).
FIELD_FORMS: tuple[str, ...] = ("{v}", "(X() * {v})", "(({v} * Y()) + X())")

_SENTINEL = 918273645
#: A second sentinel for slots whose printed value the printer clamps (Rect's radius).
_SMALL_SENTINEL = 0.0918273645
_MUTABLE = (Kind.INT, Kind.FLOAT, Kind.EXPR)
_OPERATORS = {
    s.name: s.operator for s in FUNCTIONS.values() if s.print_style is PrintStyle.OPERATOR
}
Slot = tuple[str, str]
SHARDS = 4


def _example_field(spec: FunctionSpec) -> A.Node:
    """The registry's example of ``spec`` as a field expression (shapes and segments drawn
    with Fill, as their examples do or the registry's Fill would)."""
    text = spec.example
    if spec.returns is not Returns.FIELD and not text.startswith("Fill("):
        text = f"Fill({text})"
    program, diags = analyse(f"Material(Layer(1).height({text}))")
    assert program is not None, (spec.name, diags)
    return program.layers[0].channels[0].args[0]


def _with_value(node: A.Node, spec: FunctionSpec, name: str, value: A.Node) -> A.Node:
    """``node`` with parameter ``name`` of its first call of ``spec`` set to ``value`` (and
    what the parameter needs to be used: Bricks' seed needs output="cell_value")."""
    found = False

    def rewrite(n: A.Node) -> A.Node:
        nonlocal found
        if found:
            return n
        if isinstance(n, A.BinOp):
            if _OPERATORS.get(spec.name) == n.op:
                found = True
                side = ("left", "right")[spec.param_names.index(name)]
                return replace(n, **{side: value})
            return replace(n, left=rewrite(n.left), right=rewrite(n.right))
        if isinstance(n, A.Neg):
            return replace(n, operand=rewrite(n.operand))
        if not isinstance(n, A.Call):
            return n
        if n.func != spec.name:
            args = tuple(replace(a, value=rewrite(a.value)) for a in n.args)
            return replace(n, args=args, extra=tuple(rewrite(e) for e in n.extra))
        found = True
        param = spec.param(name)
        assert param is not None
        wanted: dict[str, A.Node] = {}
        if param.used_when is not None:
            wanted[param.used_when[0]] = A.Str(param.used_when[1][0])
        if param.needs is not None and n.arg(param.needs) is None:
            wanted[param.needs] = A.Num(0.5)
        wanted[name] = value
        args = [a for a in n.args if a.param not in wanted]
        args += [A.Arg(k, v) for k, v in wanted.items()]
        args.sort(key=lambda a: spec.param_names.index(a.param))
        return replace(n, args=tuple(args))

    out = rewrite(node)
    assert found, (spec.name, name)
    return out


def _printed(node: A.Node) -> str:
    """Canonical text of the field ``node``."""
    program = A.Program(None, (), (A.Layer(channels=(A.ChannelSet("height", (node,)),)),))
    text = format_program(program)
    return text.split(".height(", 1)[1].rsplit(")", 2)[0]


def _registry_slots() -> list[tuple[Slot, Kind]]:
    return [
        ((spec.name, p.name), p.kind)
        for spec in FUNCTIONS.values()
        for p in spec.params
        if p.kind in _MUTABLE
    ]


@lru_cache(maxsize=1)
def _templates() -> dict[Slot, str]:
    """Slot -> its function's example as text with the sentinel number in that slot."""
    out: dict[Slot, str] = {}
    for (func, name), _kind in _registry_slots():
        spec = FUNCTIONS[func]
        base = _example_field(spec)
        for sentinel in (_SENTINEL, _SMALL_SENTINEL):
            text = _printed(_with_value(base, spec, name, A.Num(sentinel)))
            if text.count(str(sentinel)) == 1:
                out[(func, name)] = text.replace(str(sentinel), str(_SENTINEL))
                break
    return out


@lru_cache(maxsize=1)
def fuzz_programs() -> tuple[tuple[Slot, str], ...]:
    """(slot, program text) of every (slot, extreme value) pair, deterministically placed."""
    kinds = dict(_registry_slots())
    programs = []
    for s, (key, template) in enumerate(sorted(_templates().items())):
        for v, value in enumerate(EXTREMES):
            form = FIELD_FORMS[(s + v) % len(FIELD_FORMS)] if kinds[key] is Kind.EXPR else "{v}"
            call = template.replace(str(_SENTINEL), form.format(v=value))
            view = TILEABLE_VIEWS[(s + v) % len(TILEABLE_VIEWS)]
            context = CONTEXTS[(3 * s + v) % len(CONTEXTS)]
            height = context.format(f=call)
            programs.append(
                (key, f"{view}\nMaterial(Layer(1).basecolor(128, 64, 32).height({height}))\n")
            )
    return tuple(programs)


def check_and_render_tileable(text: str, backend: str = "numpy") -> str:
    """check, then the ``--tileable`` render path at 4 x 4 on ``backend``; only diagnostics or
    a LimitError may stop it. Returns how it ended: "rejected", "limit" or "rendered"."""
    program, diags = analyse(text)
    if program is None or any(d.is_error for d in diags):
        with pytest.raises(matloom.ProgramError):
            matloom.parse(text)
        return "rejected"
    program = apply_tileable(program, True, text)
    try:
        maps = evaluate(program, 4, 4, backend=backend)
    except LimitError:
        return "limit"
    assert maps.view.tileable
    entry = manifest_entry(maps, LAYOUT.maps)
    assert entry["tileable"] is True and set(entry["seam_ratio"])
    return "rendered"


def test_every_registry_slot_is_fuzzed() -> None:
    assert {key for key, _ in _registry_slots()} == set(_templates())


def test_the_fuzz_has_2000_programs_over_7_tileable_views() -> None:
    programs = fuzz_programs()
    assert len(programs) >= 2000
    assert len(EXTREMES) >= 27 and len(TILEABLE_VIEWS) == 7
    for view in TILEABLE_VIEWS:
        assert sum(text.startswith(view) for _, text in programs) >= 2000 // 7 // 2


def _run(programs: tuple[tuple[Slot, str], ...], backend: str) -> None:
    outcomes: dict[str, int] = {}
    for key, text in programs:
        try:
            outcome = check_and_render_tileable(text, backend)
        except Exception as error:  # pragma: no cover - the failure report
            raise AssertionError(f"{key}: {error!r}\n{text}") from error
        outcomes[outcome] = outcomes.get(outcome, 0) + 1
    assert outcomes.get("rejected") and outcomes.get("rendered"), outcomes


@pytest.mark.parametrize("shard", range(SHARDS))
def test_extreme_values_in_tileable_views(shard: int) -> None:
    _run(fuzz_programs()[shard::SHARDS], "numpy")


@pytest.mark.numba
def test_extreme_values_in_tileable_views_on_numba() -> None:
    """Every 8th program on the numba backend (its tileable kernels take the same plans)."""
    pytest.importorskip("numba")
    _run(fuzz_programs()[::8], "numba")
