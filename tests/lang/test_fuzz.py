"""Fuzzing the language front end: it reports problems as diagnostics and never crashes.

* ``matloom.check`` only ever returns a list of diagnostics (it never raises);
* ``matloom.parse`` either returns a program or raises :class:`matloom.ProgramError` with at
  least one error; an accepted program formats to a fixed point;
* huge adversarial inputs fail with an error diagnostic (never ``RecursionError``) and finish
  (their time is printed, not asserted);
* the package never calls ``eval``/``exec``.
"""

from __future__ import annotations

import ast
import re
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import matloom
from matloom.lang.lexer import Lexer
from matloom.lang.random_program import random_program

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
PACKAGE = Path(matloom.__file__).resolve().parent

FUZZ_SETTINGS = settings(
    max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)

#: Fragments that make random text look like (broken) programs.
# fmt: off
FRAGMENTS = [
    "View(", "Define(", "Material(", "Layer(", ").", ".basecolor(", ".roughness(", ".height(",
    "fBm(", "Worley(", "Bricks(", "Weave(", "Fill(", "Stroke(", "Rect(", "Ellipse(", "Path(",
    "LineTo(", "CubicTo(", "Threshold(", "Translate(", "Scale(", "Rotate(", "Log(", "Min(",
    "X()", "Y()", "seed=", "octaves=", "base_freq=None", "to_01=True", '"F2-F1"', '"row"',
    "(", ")", ",", ".", "=", "+", "-", "*", "/", "**", "#", "\n", " ", "0", "1", "0.5", "-1",
    "1e", "1e999", ".5", "5.", "pi", "e", "True", "None", "n", "'", '"', ";", "[", "`", "\x00",
    "é", "²", "٣", "\u2028",
    # extreme numbers: past the float range as digits, the float limits, subnormals
    "9" * 400, "1" + "0" * 308, "9" * 308, "1e308", "-1e308", "1e-320", "2 ** 1024", "0 / 0",
]
# fmt: on


def _bases() -> list[str]:
    names = ["tile", "brick", "bricks", "seedless", "star_evenodd", "leaf_cubic", "denim_twill"]
    texts = [(PARITY / f"{n}.mat").read_text(encoding="utf-8") for n in names]
    return texts + [random_program(s, layers=1) for s in range(3)]


BASES = _bases()


def assert_well_behaved(text: str) -> None:
    """The contract of the public API on arbitrary input."""
    diags = matloom.check(text)
    assert isinstance(diags, list)
    for d in diags:
        assert isinstance(d, matloom.Diagnostic)
        assert d.line >= 1 and d.column >= 1
        assert isinstance(d.format(), str)
    try:
        program = matloom.parse(text)
    except matloom.ProgramError as error:
        assert any(d.is_error for d in error.diagnostics)
        assert any(d.is_error for d in diags)
        return
    assert not any(d.is_error for d in diags)
    once = matloom.format(program)
    assert matloom.format(once) == once


# ---------------------------------------------------------------------------- random input
@FUZZ_SETTINGS
@given(st.text(max_size=400))
def test_arbitrary_text(text: str) -> None:
    assert_well_behaved(text)


@FUZZ_SETTINGS
@given(st.binary(max_size=400))
def test_arbitrary_bytes(data: bytes) -> None:
    assert_well_behaved(data.decode("utf-8", errors="replace"))
    assert_well_behaved(data.decode("latin-1"))


@FUZZ_SETTINGS
@given(st.lists(st.sampled_from(FRAGMENTS), max_size=80))
def test_program_like_fragment_soup(parts: list[str]) -> None:
    assert_well_behaved("".join(parts))


# ---------------------------------------------------------------------------- mutations
_CHAR_OPS = st.one_of(
    st.tuples(st.just("delete"), st.integers(0, 10**6), st.integers(1, 8)),
    st.tuples(st.just("insert"), st.integers(0, 10**6), st.sampled_from(FRAGMENTS)),
    st.tuples(st.just("replace"), st.integers(0, 10**6), st.sampled_from(FRAGMENTS)),
    st.tuples(st.just("duplicate"), st.integers(0, 10**6), st.integers(1, 40)),
)


def _mutate_chars(text: str, ops: list[tuple[str, int, object]]) -> str:
    for op, pos, arg in ops:
        i = pos % (len(text) + 1)
        if op == "delete":
            text = text[:i] + text[i + int(arg) :]  # type: ignore[call-overload]
        elif op == "insert":
            text = text[:i] + str(arg) + text[i:]
        elif op == "replace":
            text = text[:i] + str(arg) + text[i + 1 :]
        else:
            text = text[:i] + text[i : i + int(arg)] + text[i:]  # type: ignore[call-overload]
    return text


@FUZZ_SETTINGS
@given(st.sampled_from(BASES), st.lists(_CHAR_OPS, min_size=1, max_size=4))
def test_character_mutations_of_valid_programs(base: str, ops: list) -> None:
    assert_well_behaved(_mutate_chars(base, ops))


_TOKEN_OPS = st.lists(
    st.tuples(
        st.sampled_from(["delete", "duplicate", "swap", "replace"]),
        st.integers(0, 10**6),
        st.sampled_from(FRAGMENTS),
    ),
    min_size=1,
    max_size=4,
)


def _mutate_tokens(text: str, ops: list[tuple[str, int, str]]) -> str:
    """Apply token-level edits; the text between tokens (whitespace) is kept."""
    pieces = [text[t.span.start : t.span.end] for t in Lexer(text).tokens()[:-1]]
    for op, pos, fragment in ops:
        if not pieces:
            break
        k = pos % len(pieces)
        if op == "delete":
            del pieces[k]
        elif op == "duplicate":
            pieces.insert(k, pieces[k])
        elif op == "swap" and k + 1 < len(pieces):
            pieces[k], pieces[k + 1] = pieces[k + 1], pieces[k]
        elif op == "replace":
            pieces[k] = fragment
    return " ".join(pieces)


@FUZZ_SETTINGS
@given(st.sampled_from(BASES), _TOKEN_OPS)
def test_token_mutations_of_valid_programs(base: str, ops: list) -> None:
    assert_well_behaved(_mutate_tokens(base, ops))


def test_unmutated_bases_are_valid() -> None:
    for base in BASES:
        matloom.parse(base)
    assert _mutate_tokens(BASES[0], []) != ""


# ---------------------------------------------------------------------------- adversarial input
_MB = 1_000_000
ADVERSARIAL = {
    "nesting_1mb": "Material(Layer(" + "(" * _MB + "1" + ")" * 10,
    "nesting_balanced_5000": "Material(Layer(" + "(" * 5000 + "1" + ")" * 5000 + "))",
    "nested_calls_5000": "Material(Layer(" + "Abs(" * 5000 + "X()" + ")" * 5000 + "))",
    "nested_minus_5000": "Material(Layer(" + "-(" * 5000 + "1" + ")" * 5000 + "))",
    "plus_chain_1mb": "Material(Layer(" + "1+" * (_MB // 2) + "1))",
    "times_chain_50k": "Material(Layer(" + "X()*" * 50_000 + "1))",
    "power_chain_50k": "Material(Layer(" + "2**" * 50_000 + "1))",
    "digits_100k": "Material(Layer(" + "7" * 100_000 + "))",
    "fraction_100k": "Material(Layer(0." + "7" * 100_000 + "))",
    "huge_exponent": "Material(Layer(1e999999))",
    "identifier_1mb": "Material(Layer(" + "a" * _MB + "))",
    "layers_100k": "Material(" + ",".join(["Layer(0.5)"] * 100_000) + ")",
    "defines_20k": "".join(f"Define(d{i}, X())\n" for i in range(20_500)) + "Material(Layer(1))",
    "define_chain_5000": "Define(d0, X())\n"
    + "".join(f"Define(d{k}, d{k - 1} + 1)\n" for k in range(1, 5000))
    + "Material(Layer(1).height(d4999))",
    "string_1mb": 'Material(Layer("' + "x" * _MB + '"))',
    "commas_1mb": "Material(Layer(Min(" + "," * _MB + ")))",
    "too_large": "Material(Layer(1))" + " " * (3 * _MB),
}


@pytest.mark.parametrize("name", list(ADVERSARIAL))
def test_adversarial_input_fails_cleanly(name: str) -> None:
    text = ADVERSARIAL[name]
    start = time.perf_counter()
    with pytest.raises(matloom.ProgramError) as info:  # parse = check + raise on errors
        matloom.parse(text)
    elapsed = time.perf_counter() - start
    print(f"\n{name}: {len(text):,} characters rejected in {elapsed:.2f} s")
    diags = info.value.diagnostics
    assert any(d.is_error for d in diags), [d.code for d in diags[:5]]


def test_huge_but_valid_inputs_are_not_refused() -> None:
    """Limits are far above real programs: 99-deep nesting and a 2,000-term sum are accepted."""
    deep = "Material(Layer(" + "Abs(" * 98 + "X()" + ")" * 98 + "))"
    assert [d for d in matloom.check(deep) if d.is_error] == []
    terms = "Material(Layer(1).height(" + " + ".join(["(X() * 0.001)"] * 99) + "))"
    assert [d for d in matloom.check(terms) if d.is_error] == []


# ---------------------------------------------------------------------------- no eval / exec
def _eval_exec_calls(source: str) -> list[int]:
    lines = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call):
            func = node.func
            name = func.id if isinstance(func, ast.Name) else None
            if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name):
                name = func.attr if func.value.id in ("builtins", "__builtins__") else None
            if name in ("eval", "exec"):
                lines.append(node.lineno)
    return lines


def test_package_never_calls_eval_or_exec() -> None:
    bare_call = re.compile(r"(?<![\w.])(eval|exec)\s*\(")
    files = sorted(PACKAGE.rglob("*.py"))
    assert len(files) > 10
    offenders = []
    for path in files:
        source = path.read_text(encoding="utf-8")
        offenders += [f"{path.name}:{n} (call)" for n in _eval_exec_calls(source)]
        for n, line in enumerate(source.splitlines(), 1):
            if bare_call.search(line) and not line.lstrip().startswith(("def ", "#")):
                offenders.append(f"{path.name}:{n} (text)")
    assert offenders == []


def test_eval_detector_detects() -> None:
    assert _eval_exec_calls("x = eval('1')\nexec('y = 2')\nbuiltins.eval('3')") == [1, 2, 3]
    assert _eval_exec_calls("obj.eval(node)\ndef eval(self): pass") == []
