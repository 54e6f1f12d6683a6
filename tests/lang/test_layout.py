"""An edit keeps the user's layout: only the changed numbers or statements differ from the text
as written (``matloom.lang.layout.keep_layout``), and the result is always the edited program."""

from __future__ import annotations

import difflib

from matloom.lang.api import parse
from matloom.lang.layout import keep_layout
from matloom.lang.params import list_params, set_params
from matloom.lang.printer import format_program

# Not canonical: default keywords written out, positional arguments, 0.0, a comment.
WRITTEN = """View(0, 0, 2, 2, tileable=True)
# the joints
Define(edge, Bricks(brick_width=1, brick_height=1, offset=0, mortar=0.07, output="edge"))
Define(lug, Sqrt(Clamp((1 - edge), 0, 1)))
Define(mask, Smoothstep(0.0, 0.15, lug))
Material(
  Layer(1)
    .basecolor(200, 180, 160)
    .roughness(0.5)
    .height((mask * 0.02)),
  Layer(mask)
    .basecolor(90, 80, 70)
    .roughness(0.9)
)
"""


def _changed_lines(before: str, after: str) -> list[str]:
    return [
        line
        for line in difflib.unified_diff(before.splitlines(), after.splitlines(), n=0, lineterm="")
        if line[:1] in "+-" and not line.startswith(("+++", "---"))
    ]


def test_a_changed_number_is_the_only_change() -> None:
    canonical, _ = set_params(WRITTEN, {"define:edge.Bricks.mortar": 0.035})
    kept = keep_layout(WRITTEN, canonical)
    assert _changed_lines(WRITTEN, kept) == [
        '-Define(edge, Bricks(brick_width=1, brick_height=1, offset=0, mortar=0.07, output="edge"))',
        '+Define(edge, Bricks(brick_width=1, brick_height=1, offset=0, mortar=0.035, output="edge"))',
    ]
    # the canonical text rewrote the untouched lines too
    assert len(_changed_lines(WRITTEN, canonical)) > 2
    assert format_program(parse(kept)) == format_program(parse(canonical))


def test_a_layer_literal_changes_in_place() -> None:
    canonical, _ = set_params(WRITTEN, {"layer:2.roughness": 0.4})
    kept = keep_layout(WRITTEN, canonical)
    assert _changed_lines(WRITTEN, kept) == ["-    .roughness(0.9)", "+    .roughness(0.4)"]


def test_added_defines_and_layers_are_inserted_and_nothing_else_moves() -> None:
    after = WRITTEN.replace(
        "Material(", "Define(dirt, fBm(octaves=3, base_freq=4, to_01=True, seed=9))\nMaterial("
    ).replace("    .roughness(0.9)\n)", "    .roughness(0.9),\n  Layer(dirt)\n    .roughness(1)\n)")
    canonical = format_program(parse(after), comments=True)
    kept = keep_layout(WRITTEN, canonical)
    assert all(line.startswith("+") for line in _changed_lines(WRITTEN, kept) if line[0] == "+")
    removed = [line for line in _changed_lines(WRITTEN, kept) if line.startswith("-")]
    assert removed == ["-    .roughness(0.9)"]  # only its new trailing comma
    assert format_program(parse(kept)) == format_program(parse(after))
    assert "# the joints" in kept


def test_a_removed_statement_falls_back_to_the_canonical_text() -> None:
    after = WRITTEN.replace("Define(lug, Sqrt(Clamp((1 - edge), 0, 1)))\n", "").replace(
        "Smoothstep(0.0, 0.15, lug)", "Smoothstep(0.0, 0.15, edge)"
    )
    canonical = format_program(parse(after), comments=True)
    assert keep_layout(WRITTEN, canonical) == canonical


def test_no_change_keeps_the_text_as_written() -> None:
    canonical = format_program(parse(WRITTEN), comments=True)
    assert canonical != WRITTEN
    assert keep_layout(WRITTEN, canonical).rstrip("\n") == WRITTEN.rstrip("\n")


def test_every_library_entry_keeps_its_layout_through_a_number_edit() -> None:
    from matloom.library import load_library

    lib = load_library()
    names = sorted(lib.entries)[::25]  # a spread of about twenty entries
    assert len(names) >= 15
    for name in names:
        text = lib.entry(name).program
        params = [p for p in list_params(parse(text)) if p.kind in ("scalar", "frequency")]
        if not params:
            continue
        p = params[len(params) // 2]
        lo = p.low if p.low is not None else 0.0
        hi = p.high if p.high is not None else float(p.value) * 2 + 1  # type: ignore[arg-type]
        value = round((float(p.value) + (lo + hi) / 2) / 2, 4)  # type: ignore[arg-type]
        canonical, _ = set_params(text, {p.address: value})
        kept = keep_layout(text, canonical)
        assert format_program(parse(kept)) == format_program(parse(canonical)), name
        changed = _changed_lines(text, kept)
        if canonical != format_program(parse(text), comments=True):
            assert 0 < len(changed) <= 6, (name, p.address, changed)
