"""``#`` comments are part of the AST and of ``matloom fmt``: no comment text is ever dropped.

Slots (see :mod:`matloom.lang.comments`): leading comments before a View/Define/Material, a Layer
or a channel call; trailing comments at the end of the line where a construct ends; comments at
the end of the file; anything else goes to the innermost enclosing construct as leading.
"""

from __future__ import annotations

import os
import random
import re
import subprocess
import sys
from pathlib import Path

import pytest

import matloom
from matloom.examples import NAMES, example_text
from matloom.lang import ast as A
from matloom.lang.api import analyse
from matloom.lang.comments import all_comments
from matloom.lang.inline import inline_defines
from matloom.lang.lexer import Lexer
from matloom.lang.printer import format_program
from matloom.lang.seeds import canonicalize_seeds

REPO = Path(__file__).resolve().parents[2]
PARITY = REPO / "tests" / "data" / "parity"

#: A comment in every slot, plus comments inside expressions and on channels the AST drops.
EVERY_SLOT = """\
# header: file comment
View(0, 0, 1, 1)  # view trailing
# define leading
Define(a, Add(1,  # inside an expression, end of line
   # inside an expression, own line
   2))  # define trailing
Define(b, a * 2)
# material leading
Material(  # material open
  # layer leading
  Layer(1)  # layer head trailing
    # channel leading
    .roughness(0.5)  # channel trailing
    .basecolor(a, b, 3),  # after the comma
  # second layer leading
  Layer(0.5).alpha(0.25)  # on a dropped .alpha
    # before an overwritten channel
    .basecolor(1, 2, 3)
    .basecolor(4, 5, 6)  # last basecolor trailing
  # footer before the closing paren
)  # material close
# end of file 1

# end of file 2
"""

#: What ``fmt`` prints for :data:`EVERY_SLOT` (channels in canonical order keep their comments).
EVERY_SLOT_FORMATTED = """\
# header: file comment
View(0, 0, 1, 1)  # view trailing
# define leading
# inside an expression, end of line
# inside an expression, own line
Define(a, (1 + 2))  # define trailing
Define(b, (a * 2))
# material leading
Material(  # material open
  # layer leading
  Layer(1)  # layer head trailing
    .basecolor(a, b, 3)  # after the comma
    # channel leading
    .roughness(0.5),  # channel trailing
  # second layer leading
  # on a dropped .alpha
  # before an overwritten channel
  Layer(0.25)
    .basecolor(4, 5, 6)  # last basecolor trailing
  # footer before the closing paren
)  # material close
# end of file 1
# end of file 2"""


def _comments_of(text: str) -> list[str]:
    return [m.group().rstrip() for m in re.finditer(r"#[^\n]*", text)]


def _fmt(text: str) -> str:
    program, diags = analyse(text)
    assert program is not None and not any(d.is_error for d in diags), diags
    return format_program(program, comments=True)


def _comment_free_texts() -> dict[str, str]:
    """The examples and valid parity fixtures, by name (none of them has a comment)."""
    texts = {name: example_text(name) for name in NAMES}
    texts |= {p.name: p.read_text(encoding="utf-8") for p in sorted(PARITY.glob("*.mat"))}
    assert len(texts) > len(NAMES)  # the parity fixtures were found
    return {
        name: t
        for name, t in texts.items()
        if "#" not in t and not any(d.is_error for d in matloom.check(t))
    }


COMMENT_FREE = _comment_free_texts()


# ---------------------------------------------------------------------------- round trip
def test_every_comment_in_every_slot_survives_fmt() -> None:
    out = _fmt(EVERY_SLOT)
    assert out == EVERY_SLOT_FORMATTED
    for comment in _comments_of(EVERY_SLOT):
        assert out.count(comment) == 1, comment


def test_fmt_with_comments_is_idempotent() -> None:
    once = _fmt(EVERY_SLOT)
    assert _fmt(once) == once
    assert _fmt(once + "\n") == once


def test_comments_do_not_change_the_program() -> None:
    without = re.sub(r"#[^\n]*", "", EVERY_SLOT)
    assert matloom.parse(EVERY_SLOT) == matloom.parse(without)  # equality ignores comments
    assert matloom.format(EVERY_SLOT) == matloom.format(without)  # default text: comment-free
    assert "#" not in matloom.format(EVERY_SLOT)
    assert matloom.format(EVERY_SLOT, comments=True) == EVERY_SLOT_FORMATTED


def test_lexer_token_stream_is_unchanged_by_comments() -> None:
    without = re.sub(r"#[^\n]*", "", EVERY_SLOT)
    lexer = Lexer(EVERY_SLOT)
    kinds = [(t.kind, t.text) for t in lexer.tokens()]
    assert kinds == [(t.kind, t.text) for t in Lexer(without).tokens()]
    assert [c.text for c in lexer.comments] == _comments_of(EVERY_SLOT)
    assert all(c.kind == "COMMENT" for c in lexer.comments)


def test_comments_land_in_the_documented_slots() -> None:
    program = matloom.parse(EVERY_SLOT)

    def slots(node: A.Commented) -> list[tuple[str, str]]:
        return [(c.slot, c.text) for c in node.comments]

    assert program.view is not None
    assert slots(program.view) == [
        ("leading", "# header: file comment"),
        ("trailing", "# view trailing"),
    ]
    assert [s for s, _ in slots(program.defines[0])] == ["leading"] * 3 + ["trailing"]
    assert slots(program.defines[1]) == []
    assert [s for s, _ in slots(program)] == ["leading", "open", "footer", "close", "end", "end"]
    first, second = program.layers
    assert slots(first) == [("leading", "# layer leading"), ("trailing", "# layer head trailing")]
    roughness = first.channel("roughness")
    basecolor = first.channel("basecolor")
    assert roughness is not None and basecolor is not None
    assert slots(roughness) == [
        ("leading", "# channel leading"),
        ("trailing", "# channel trailing"),
    ]
    assert slots(basecolor) == [("trailing", "# after the comma")]
    assert slots(second) == [
        ("leading", "# second layer leading"),
        ("leading", "# on a dropped .alpha"),
        ("leading", "# before an overwritten channel"),
    ]
    assert len(all_comments(program)) == len(_comments_of(EVERY_SLOT))


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("# only\nMaterial(Layer(1))", "# only\nMaterial(\n  Layer(1)\n)"),
        ("Material(Layer(1))  # same line", "Material(\n  Layer(1)\n)  # same line"),
        ("Material(Layer(1))\n#end", "Material(\n  Layer(1)\n)\n#end"),
        (
            "Material(Layer(1).basecolor(1, 2, 3))  # after all",
            "Material(\n  Layer(1)\n    .basecolor(1, 2, 3)\n)  # after all",
        ),
        (
            "Material(\n  Layer(1).basecolor(1, 2, 3)  # one line layer\n)",
            "Material(\n  Layer(1)\n    .basecolor(1, 2, 3)  # one line layer\n)",
        ),
        (
            "Material(\n  Layer(1),  # first\n  Layer(2)\n)",
            "Material(\n  Layer(1),  # first\n  Layer(2)\n)",
        ),
        (
            "Material(\n  Layer(1)\n  # between layers\n  , Layer(2)\n)",
            "Material(\n  Layer(1),\n  # between layers\n  Layer(2)\n)",
        ),
        ("Material(Layer(1  # in alpha\n))", "Material(\n  # in alpha\n  Layer(1)\n)"),
        ("Material(Layer(1))   # blanks after   \r\n", "Material(\n  Layer(1)\n)  # blanks after"),
    ],
)
def test_small_cases(text: str, expected: str) -> None:
    assert _fmt(text) == expected
    assert _fmt(expected) == expected


def test_comments_at_every_token_boundary_are_kept() -> None:
    """A comment after (or before) any token, trailing or on its own line, is never lost."""
    base = example_text("bricks_quickstart")
    toks = Lexer(base).tokens()
    rng = random.Random(7)
    for k, tok in enumerate(toks):
        pos = tok.span.start if rng.random() < 0.3 else tok.span.end
        comment = f"# probe {k}"
        insert = f"  {comment}\n" if k % 2 else f"\n{comment}\n"
        text = base[:pos] + insert + base[pos:]
        out = _fmt(text)
        assert len(re.findall(re.escape(comment) + r"(?!\d)", out)) == 1, text
        assert _fmt(out) == out, text
        assert matloom.format(text) == matloom.format(base)


# ---------------------------------------------------------------------------- no comments
@pytest.mark.parametrize("name", list(COMMENT_FREE))
def test_comment_free_programs_print_exactly_as_before(name: str) -> None:
    program = matloom.parse(COMMENT_FREE[name])
    assert all_comments(program) == []
    assert format_program(program, comments=True) == format_program(program)


def test_canonical_fixtures_are_unchanged_by_fmt() -> None:
    paths = sorted(PARITY.glob("*.canonical.mat"))
    assert len(paths) > 10
    for path in paths:
        expected = path.read_text(encoding="utf-8").strip()
        if "seed=SEED" not in expected:  # `seedless`: a masked template, not a program
            assert _fmt(expected) == expected, path.name


# ---------------------------------------------------------------------------- other consumers
def test_seed_canonicalisation_keeps_comments() -> None:
    text = "Define(n, fBm())  # noise\nMaterial(\n  # base\n  Layer(n)\n)"
    out = format_program(canonicalize_seeds(matloom.parse(text), 3), comments=True)
    assert "seed=" in out
    assert "Define(n, " in out and out.splitlines()[0].endswith("  # noise")
    assert "  # base\n  Layer(n)" in out


def test_inline_moves_define_comments_before_material() -> None:
    text = "# file header\nDefine(a, X())  # the x field\nMaterial(\n  Layer(a)  # uses a\n)"
    out = format_program(inline_defines(matloom.parse(text)), comments=True)
    assert out == ("# file header\n# the x field\nMaterial(\n  Layer(X())  # uses a\n)")
    assert _fmt(out) == out


# ---------------------------------------------------------------------------- CLI
def _run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(REPO), env.get("PYTHONPATH")) if p)
    return subprocess.run(
        [sys.executable, "-m", "matloom", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
        check=False,
    )


def test_cli_fmt_write_keeps_comments(tmp_path: Path) -> None:
    target = tmp_path / "commented.mat"
    target.write_text(EVERY_SLOT, encoding="utf-8")
    assert _run_cli("fmt", "--check", str(target)).returncode == 1
    result = _run_cli("fmt", "--write", str(target))
    assert result.returncode == 0, result.stderr
    written = target.read_text(encoding="utf-8")
    assert written == EVERY_SLOT_FORMATTED + "\n"
    for comment in _comments_of(EVERY_SLOT):
        assert comment in written
    assert _run_cli("fmt", "--check", str(target)).returncode == 0  # idempotent on disk
    printed = _run_cli("fmt", str(target))
    assert printed.returncode == 0 and printed.stdout == written
