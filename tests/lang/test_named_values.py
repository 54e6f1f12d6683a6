"""Named values in static parameters (issue 24, item 1): ``Define(grout, 0.02)`` then
``Bricks(mortar=grout)``: checked, printed with the names, inlined and evaluated as the literal."""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.engine.evaluate import evaluate
from matloom.engine.maps import ARRAY_FIELDS
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.codes import Code
from matloom.lang.constants import constant_defines, plain_numbers, resolve_static
from matloom.lang.cost import expanded_cost
from matloom.lang.deps import channel_dependencies
from matloom.lang.inline import inline_defines
from matloom.lang.printer import format_program
from matloom.lang.tileable import tileable_warnings

_DEFINES = (
    "Define(grout, 0.02)\n"
    "Define(scale, 2)\n"
    "Define(freq, (scale * 8))\n"
    "Define(oct, (scale + 1))\n"
    "Define(half, (grout / 2))\n"
    "Define(s, 7)\n"
    "Define(nz, fBm(base_freq=5, seed=2, to_01=True))\n"
)

#: (named, literal): the same program with each named value written in as its expression
_PAIRS = [
    (
        "Bricks(mortar=grout, brick_width=(scale * 0.1), feather=half)",
        "Bricks(mortar=0.02, brick_width=(2 * 0.1), feather=(0.02 / 2))",
    ),
    ("fBm(octaves=oct, base_freq=freq, seed=s)", "fBm(octaves=(2 + 1), base_freq=(2 * 8), seed=7)"),
    (
        "Worley(base_freq_x=freq, base_freq_y=scale, seed=s)",
        "Worley(base_freq_x=16, base_freq_y=2, seed=7)",
    ),
    (
        "Weave(base_freq=freq, warp_width=(grout * 20))",
        "Weave(base_freq=16, warp_width=(0.02 * 20))",
    ),
    (
        "Threshold(nz, below_at=(grout * 20), below_to=0, transition_width=grout)",
        "Threshold(nz, below_at=(0.02 * 20), below_to=0, transition_width=0.02)",
    ),
    (
        "Fill(Rect(0.1, 0.1, (scale / 4), 0.5, radius=half), feather=grout)",
        "Fill(Rect(0.1, 0.1, (2 / 4), 0.5, radius=(0.02 / 2)), feather=0.02)",
    ),
    (
        "Stroke(Path(0.1, 0.1, LineTo((scale / 3), 0.8)), width=grout)",
        "Stroke(Path(0.1, 0.1, LineTo((2 / 3), 0.8)), width=0.02)",
    ),
    ("Log((nz + 1), scale)", "Log((nz + 1), 2)"),
    (
        "Tile(Fill(Ellipse(0.5, 0.5, 0.3, 0.3)), (grout * 5), (grout * 5), jitter=half, seed=s)",
        "Tile(Fill(Ellipse(0.5, 0.5, 0.3, 0.3)), (0.02 * 5), (0.02 * 5), jitter=(0.02 / 2), seed=7)",
    ),
]


def _program(expr: str, defines: str = _DEFINES) -> str:
    return f"{defines}Material(Layer().basecolor({expr}, 0.5, 0.5).height(({expr}) * 0.1))"


def _maps(text: str, backend: str) -> dict[str, np.ndarray]:
    maps = evaluate(text, 32, 32, backend=backend)
    return {k: np.asarray(getattr(maps, k)) for k in ARRAY_FIELDS}


@pytest.mark.parametrize("backend", ["numpy", "numba"])
@pytest.mark.parametrize(("named", "literal"), _PAIRS, ids=[p[0].split("(")[0] for p in _PAIRS])
def test_named_values_give_the_maps_of_the_literal_bit_for_bit(
    named: str, literal: str, backend: str
) -> None:
    named_text, literal_text = _program(named), _program(literal)
    _, diags = analyse(named_text)
    assert not [d for d in diags if d.is_error], diags
    a, b = _maps(named_text, backend), _maps(literal_text, backend)
    for k in ARRAY_FIELDS:
        assert a[k].tobytes() == b[k].tobytes(), k
    # the values are really used: another mortar/frequency changes the maps
    if "grout" in named or "freq" in named:
        other = _program(named, _DEFINES.replace("0.02", "0.04").replace("* 8", "* 3"))
        c = _maps(other, backend)
        assert any(c[k].tobytes() != a[k].tobytes() for k in ARRAY_FIELDS)


@pytest.mark.parametrize(("named", "literal"), _PAIRS, ids=[p[0].split("(")[0] for p in _PAIRS])
def test_fmt_keeps_the_names_and_inline_writes_plain_numbers(named: str, literal: str) -> None:
    program = matloom.parse(_program(named))
    text = format_program(program, comments=True)
    assert "grout" in text or "scale" in text
    assert format_program(matloom.parse(text), comments=True) == text  # a fixed point
    plain = format_program(inline_defines(program))
    lit = format_program(inline_defines(matloom.parse(_program(literal))))
    assert plain == lit
    assert format_program(plain_numbers(program)) == format_program(
        matloom.parse(_program(literal))
    )


def test_printer_keeps_names_in_weave_threshold_rect_and_log() -> None:
    text = format_program(matloom.parse(_program(_PAIRS[3][0])))
    assert "Weave(base_freq=freq, warp_width=(grout * 20))" in text
    text = format_program(matloom.parse(_program(_PAIRS[4][0])))
    assert "below_at=(grout * 20)" in text and "transition_width=grout" in text
    text = format_program(matloom.parse(_program(_PAIRS[5][0])))
    assert "Rect(0.1, 0.1, (scale / 4), 0.5, half)" in text and "feather=grout" in text
    assert "Log((nz + 1), scale)" in format_program(matloom.parse(_program(_PAIRS[7][0])))


def test_constant_defines_are_the_constant_arithmetic_ones() -> None:
    program = matloom.parse(
        _DEFINES + "Define(xs, (X() * 2))\nDefine(mix, (grout + nz))\n"
        "Material(Layer().basecolor(nz, xs, mix))"
    )
    consts = constant_defines(program)
    assert list(consts) == ["grout", "scale", "freq", "oct", "half", "s"]
    assert consts["freq"] == A.BinOp("*", A.Num(2), A.Num(8))


def test_a_field_define_in_a_static_parameter_is_e045_naming_it() -> None:
    for define in ("fBm(seed=1)", "(X() * 2)", "(grout + Worley(seed=1))"):
        _, diags = analyse(
            f"Define(grout, 0.02)\nDefine(f, {define})\n"
            "Material(Layer().basecolor(Bricks(mortar=f), 0.5, 0.5))"
        )
        errors = [d for d in diags if d.is_error]
        assert [d.code for d in errors] == [Code.NOT_A_NUMBER.code], define
        assert "Define 'f' is a field" in errors[0].message


def test_range_and_integer_checks_name_the_define() -> None:
    _, diags = analyse(
        "Define(k, -1)\nDefine(o, 2.5)\nDefine(many, (k * -40))\n"
        "Material(Layer().basecolor(Bricks(mortar=k), fBm(octaves=o, seed=1), "
        "fBm(octaves=many, seed=2)))"
    )
    by_code = {d.code: d.message for d in diags if d.is_error}
    assert by_code[Code.OUT_OF_RANGE.code].endswith("got -1 (from Define 'k')")
    assert "2.5 (from Define 'o')" in by_code[Code.NOT_AN_INTEGER.code]
    assert "octaves=40 (from Define 'many')" in by_code[Code.SIZE_LIMIT.code]


def test_resolution_leaves_programs_without_named_values_untouched() -> None:
    text = "Define(nz, fBm(seed=1))\nMaterial(Layer().basecolor(nz, Bricks(mortar=0.02), 0.5))"
    program = matloom.parse(text)
    assert resolve_static(program) is program
    # a Define in a field parameter stays a per-sample field (Translate's dx)
    field = matloom.parse(
        "Define(d, 0.5)\nMaterial(Layer().basecolor(Translate(fBm(seed=1), d, 0), 0.5, 0.5))"
    )
    assert resolve_static(field) is field


def test_cost_deps_and_tileable_read_named_values() -> None:
    named = matloom.parse(_program(_PAIRS[1][0]))
    literal = matloom.parse(_program(_PAIRS[1][1]))
    assert expanded_cost(named).nodes == expanded_cost(literal).nodes
    deps = channel_dependencies(named)
    seed_line = _DEFINES.splitlines().index("Define(s, 7)") + 1
    seeds = [p for p in deps["basecolor"] if p.line == seed_line]
    assert len(seeds) == 1 and seeds[0].is_seed and seeds[0].value == 7
    assert not any(p.line == seed_line for p in deps["roughness"])
    # tileable warnings: a named brick width that does not fit the period is reported (W009)
    view = "View(0, 0, 1, 1, tileable=True)\n"
    off = view + "Define(w, 0.3)\nMaterial(Layer().basecolor(Bricks(brick_width=w), 0.5, 0.5))"
    lit = view + "Material(Layer().basecolor(Bricks(brick_width=0.3), 0.5, 0.5))"
    codes = [d.code for d in analyse(off)[1] if d.code.startswith("W009")]
    assert codes and codes == [d.code for d in tileable_warnings(matloom.parse(lit))]
    fits = off.replace("0.3", "0.25")
    assert not [d for d in analyse(fits)[1] if d.code == "W009"]


def test_inline_of_named_values_and_seedless_named_noise_keeps_the_maps() -> None:
    source = (
        "Define(grout, 0.03)\nDefine(grain, fBm(base_freq=6, to_01=True))\n"
        "Material(Layer().basecolor((grain * 200), (Bricks(mortar=grout) * 180), 60)"
        ".roughness(((fBm(base_freq=9, to_01=True) * 0.5) + (grain * 0.5)))"
        ".height(((Bricks(mortar=grout) * 0.02) + (grain * 0.01))))"
    )
    inlined = format_program(inline_defines(matloom.parse(source)))
    assert "Define(" not in inlined and "mortar=0.03" in inlined
    for backend in ("numpy", "numba"):
        a, b = _maps(source, backend), _maps(inlined, backend)
        assert all(a[k].tobytes() == b[k].tobytes() for k in ARRAY_FIELDS)


def test_cli_fmt_keeps_names_inline_and_seed_variants_write_numbers(tmp_path) -> None:
    from click.testing import CliRunner

    from matloom.cli.lang_cmds import fmt_cmd, seeds_cmd

    path = tmp_path / "named.mat"
    path.write_text(
        "Define(grout, 0.03)  # joint width\nDefine(s, 7)\n"
        "Material(Layer().basecolor(Bricks(mortar=grout), fBm(seed=s), 0.5))\n",
        encoding="utf-8",
    )
    runner = CliRunner()
    kept = runner.invoke(fmt_cmd, [str(path)])
    assert kept.exit_code == 0 and "Bricks(mortar=grout)" in kept.output
    assert "fBm(seed=s)" in kept.output and "# joint width" in kept.output
    inlined = runner.invoke(fmt_cmd, ["--inline", str(path)])
    assert inlined.exit_code == 0
    assert "Bricks(mortar=0.03)" in inlined.output and "fBm(seed=7)" in inlined.output
    variants = runner.invoke(seeds_cmd, [str(path), "-k", "2"])
    assert variants.exit_code == 0
    seeds = {
        line.split("fBm(seed=")[1].split(")")[0]
        for line in variants.output.splitlines()
        if "fBm(seed=" in line
    }
    assert "7" in seeds and len(seeds) == 3  # the named seed is varied
