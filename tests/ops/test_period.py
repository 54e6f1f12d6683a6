"""Period rules (``Op.period``, ``ParamSpec.cycle``): every op states one, they say what the
checker and the engine do with a tileable View's periods, and no tiling module outside the op
table and the registry names a function to decide tiling."""

from __future__ import annotations

import ast
import math
from pathlib import Path

import pytest

from matloom.lang.api import parse
from matloom.lang.tileable import make_tileable, tileable_warnings
from matloom.ops import OPS, Period, Repeats
from matloom.ops.period import whole
from matloom.vocab import FUNCTIONS
from matloom.vocab.spec import Kind

ROOT = Path(__file__).resolve().parents[2]

#: The modules that decide tiling outside the op table (matloom/ops) and the registry
#: (matloom/vocab): none of them may compare a function name with a literal one.
TILING_MODULES = (
    "matloom/lang/tileable.py",
    "matloom/lang/affine.py",
    "matloom/engine/interpret.py",
    "matloom/engine/tiling.py",
    "matloom/engine/rules/fields.py",
    "matloom/engine/rules/fields_math.py",
    "matloom/engine/rules/support.py",
    "matloom/engine/kernels/noise.py",
    "matloom/engine/kernels/tile.py",
    "matloom/engine/kernels/patterns.py",
    "matloom/library/author.py",
    "matloom/library/adapt.py",
    "matloom/cli/tileable.py",
)
#: Of those, the ones that need no function's name at all (every literal one is a finding).
NAME_FREE = (
    "matloom/lang/tileable.py",
    "matloom/lang/affine.py",
    "matloom/engine/interpret.py",
    "matloom/engine/tiling.py",
    "matloom/engine/kernels/noise.py",
    "matloom/engine/kernels/tile.py",
)


def _param(values: dict[str, object], func: str):  # noqa: ANN202 - a rule's param accessor
    spec = FUNCTIONS[func]

    def param(name: str) -> object:
        p = spec.param(name)
        assert p is not None, name
        return values.get(name, p.default)

    return param


# ------------------------------------------------------------------ every op has one
@pytest.mark.parametrize("name", sorted(OPS))
def test_every_op_states_a_period_rule(name: str) -> None:
    op, spec = OPS[name], FUNCTIONS[name]
    period = op.period
    assert isinstance(period, Period) and isinstance(period.repeats, Repeats)
    assert (period.axis is not None) == (period.repeats is Repeats.AXIS)
    assert (period.frame is not None) == (period.repeats is Repeats.FRAME)
    assert (op.transform is not None) == (period.repeats is Repeats.FRAME)
    assert period.misfit is None or period.repeats is Repeats.OWN
    assert period.warp_keeps is False or period.repeats is Repeats.FRAME
    if period.repeats is Repeats.OWN:
        assert period.framed  # its own period needs the View's periods
    if period.repeats is Repeats.STEP:
        assert [p.name for p in spec.params if p.kind is Kind.EXPR] == ["expr"]
    cycles = [p for p in spec.params if p.cycle is not None]
    if period.repeats is Repeats.WRAP:
        assert cycles, "a periodic wrapper's arguments carry their cycle"
        assert period.unit in ("cycles", "cells")
    for p in cycles:
        assert period.repeats in (Repeats.WRAP, Repeats.FRAME), p.name
        if isinstance(p.cycle, str):  # the cycle is another parameter's value
            assert spec.param(p.cycle) is not None
        else:
            assert math.isfinite(p.cycle) and p.cycle > 0


def test_the_framed_primitives_are_the_registry_s_noise_patterns_and_shapes() -> None:
    """What cannot repeat under a Rotate: the seeded primitives, the patterns and the shapes
    that return fields (the families the analysis read before the rules existed)."""
    expected = {
        name
        for name, spec in FUNCTIONS.items()
        if spec.is_noise
        or spec.family == "pattern"
        or (spec.family == "shape" and spec.returns.value == "field")
    }
    assert {name for name, op in OPS.items() if op.period.framed} == expected


# ------------------------------------------------------------------ direct cases
def test_coordinates_steps_and_wrappers() -> None:
    assert OPS["X"].period.axis == (1.0, 0.0)
    assert OPS["Y"].period.axis == (0.0, 1.0)
    assert OPS["Add"].period.repeats is Repeats.KEEP
    assert OPS["Floor"].period.repeats is Repeats.STEP
    assert OPS["Sin"].period.repeats is Repeats.WRAP
    assert FUNCTIONS["Sin"].param("expr").cycle == 2 * math.pi  # type: ignore[union-attr]
    assert FUNCTIONS["Fract"].param("x").cycle == 1.0  # type: ignore[union-attr]
    assert FUNCTIONS["Mod"].param("x").cycle == "m"  # type: ignore[union-attr]
    assert FUNCTIONS["Rotate"].param("degrees").cycle == 360.0  # type: ignore[union-attr]
    hash_ = OPS["Hash"].period
    assert hash_.repeats is Repeats.WRAP and hash_.unit == "cells" and hash_.framed


def test_transform_frames() -> None:
    periods = (1.0, 2.0)

    def frame(func: str, **values: object) -> object:
        rule = OPS[func].period.frame
        assert rule is not None
        return rule(func, _param(values, func), periods)

    assert frame("Translate", dx=0.3, dy=0.1) == periods
    assert OPS["Translate"].period.warp_keeps
    assert frame("Scale", sx=2.0, sy=-4.0) == (0.5, 0.5)
    assert frame("Scale", sx=1e-320, sy=1.0) == "a Scale past the float range"
    assert not OPS["Scale"].period.warp_keeps
    assert frame("Rotate", degrees=180.0) == periods
    assert frame("Rotate", degrees=-540.0) == periods
    assert frame("Rotate", degrees=180.0001) == periods  # within a thousandth of half a turn
    assert frame("Rotate", degrees=45.0) == "Rotate"
    assert not OPS["Rotate"].period.warp_keeps
    assert whole(2.0004) == 2 and whole(2.01) is None and whole(math.inf) is None


def test_transform_rules_agree() -> None:
    """A transform's coordinates, matrix and way back state one map."""
    x, y = 0.3, -1.7
    for func, values in (
        ("Translate", {"dx": 0.25, "dy": -2.0}),
        ("Scale", {"sx": 2.0, "sy": 0.5}),
        ("Rotate", {"degrees": 30.0}),
    ):
        rule = OPS[func].transform
        assert rule is not None
        a, b = rule.values(_param(values, func))
        u, v = rule.coords(x, y, a, b)
        m = rule.matrix(a, b)
        assert (u, v) == pytest.approx((m[0] * x + m[1] * y + m[2], m[3] * x + m[4] * y + m[5]))
        assert rule.back(u, v, a, b) == pytest.approx((x, y))
    a, b = OPS["Rotate"].transform.values(_param({"degrees": 90.0}, "Rotate"))  # type: ignore[union-attr]
    assert (a, b) == pytest.approx((0.0, 1.0))


def test_own_periods() -> None:
    def misfit(func: str, periods: tuple[float, float] = (1.0, 1.0), **values: object):  # noqa: ANN202
        rule = OPS[func].period.misfit
        assert rule is not None
        return rule(func, _param(values, func), periods)

    assert misfit("Bricks", brick_width=0.25, brick_height=0.125) is None
    msg, hint = misfit("Bricks", brick_width=0.3, brick_height=0.125)
    assert msg.startswith("Bricks: brick_width=0.3 gives 3.333 bricks per View period")
    assert hint is not None and "brick_width=0.3333" in hint
    assert misfit("Weave", base_freq=8.0) is None
    assert misfit("Weave", base_freq=8.3) is not None
    assert misfit("fBm", base_freq=4.0) is None
    assert "more than 16,777,216 cells" in misfit("fBm", base_freq=1e9)[0]
    assert misfit("Worley", base_freq=3.7) is None  # snapped by the engine
    assert misfit("Worley", base_freq=1e300) is not None
    assert misfit("Tile", width=0.3, height=0.3) is None  # snapped by the engine
    assert misfit("Tile", width=1e-300, height=0.3) is not None


def test_rules_drive_the_warnings() -> None:
    def codes(text: str) -> list[str]:
        return [d.code for d in tileable_warnings(make_tileable(parse(text)))]

    fbm = "fBm(base_freq=4, seed=1)"
    assert codes(f"Material(Layer().height({fbm}))") == []
    assert codes(f"Material(Layer().height(Rotate({fbm}, 90)))") == ["W009"]
    assert codes(f"Material(Layer().height(Rotate({fbm}, 180)))") == []
    assert codes(f"Material(Layer().height(Translate({fbm}, {fbm}, 0)))") == []
    assert codes(f"Material(Layer().height(Scale({fbm}, {fbm}, 1)))") == ["W009"]
    assert codes("Material(Layer().height(X()))") == ["W010"]
    assert codes("Material(Layer().height(Fract(X() * 3)))") == []
    assert codes("Material(Layer().height(Fract(X() * 3.5)))") == ["W010"]
    assert codes("Material(Layer().height(Mod(X() * 3, 0.5)))") == []
    assert codes("Material(Layer().height(Hash(X() * 2.5, seed=1)))") == ["W009"]
    assert codes("Material(Layer().height(Floor(X() * 4) * 0.1))") == ["W010"]
    assert codes("Material(Layer().height(Sin(Floor(X() * 4) * 2 * pi)))") == []
    motif = "Tile(X() * 3, 0.25, 0.25, seed=1)"  # a motif repeats with its instances
    assert codes(f"Material(Layer().height({motif}))") == []


# ------------------------------------------------------------------ no names outside the table
def _string_constants(node: ast.AST) -> list[str]:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, ast.Tuple | ast.List | ast.Set):
        return [s for elt in node.elts for s in _string_constants(elt)]
    return []


def _docstrings(tree: ast.AST) -> set[int]:
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                found.add(id(body[0].value))
    return found


def name_comparisons(source: str) -> list[tuple[int, str]]:
    """(line, name) of every comparison (==, !=, in, not in) with a registry function's
    name, and every such name passed to ``periods_of``."""
    tree = ast.parse(source)
    found = []
    for node in ast.walk(tree):
        sides: list[ast.AST] = []
        if isinstance(node, ast.Compare):
            sides = [node.left, *node.comparators]
        elif isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "periods_of":
            sides = list(node.args)
        for side in sides:
            found += [(node.lineno, s) for s in _string_constants(side) if s in FUNCTIONS]
    return found


def name_literals(source: str) -> list[tuple[int, str]]:
    """(line, name) of every string literal (docstrings aside) that names a function."""
    tree = ast.parse(source)
    docs = _docstrings(tree)
    return [
        (node.lineno, node.value)
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant)
        and isinstance(node.value, str)
        and node.value in FUNCTIONS
        and id(node) not in docs
    ]


@pytest.mark.parametrize("path", TILING_MODULES)
def test_no_tiling_module_compares_function_names(path: str) -> None:
    file = ROOT / path
    assert file.exists(), f"{path} is listed in TILING_MODULES but does not exist"
    found = name_comparisons(file.read_text(encoding="utf-8"))
    assert not found, f"{path} names functions (read Op.period instead): {found}"


@pytest.mark.parametrize("path", NAME_FREE)
def test_name_free_tiling_modules(path: str) -> None:
    found = name_literals((ROOT / path).read_text(encoding="utf-8"))
    assert not found, f"{path} names functions (read Op.period / Op.transform): {found}"


def test_the_name_checks_can_fail() -> None:
    bad = (
        'if call.func == "Bricks":\n    pass\n'
        'x = node.func in ("Translate", "Scale")\n'
        'p = ev.periods_of(c, "Tile")\n'
    )
    assert [name for _, name in name_comparisons(bad)] == ["Bricks", "Translate", "Scale", "Tile"]
    assert name_comparisons('if call.func == op.name:\n    pass\nx = "Bricks"\n') == []
    assert [name for _, name in name_literals('"""Bricks"""\nx = "Bricks"\n')] == ["Bricks"]
