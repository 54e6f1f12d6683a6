"""Offline edits that place what they add and size what shows: overlays confined to the joints
("dirt in the grout"), asked for as spots ("rust spots"), and relief judged in the lit preview
(a relief step that moves the normals but not the lit preview is escalated)."""

from __future__ import annotations

import numpy as np

from author.test_edit_rules import program
from matloom.author.edit import edit_offline
from matloom.author.edit.core import parse_program
from matloom.author.edit.visible import lit_changes
from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A


def _added_layers(before: str, after: str) -> tuple[A.Layer, ...]:
    n = len(parse_program(before).layers)
    return parse_program(after).layers[n:]


def _coverage(text: str, layers: tuple[A.Layer, ...], size: int = 64) -> np.ndarray:
    """Where the added layers cover, on a grid (each composited over the last, read as
    roughness)."""
    prog = parse_program(text)
    probe = A.Program(
        prog.view,
        prog.defines,
        (
            A.Layer(None, (A.ChannelSet("roughness", (A.Num(0),)),)),
            *(A.Layer(layer.alpha, (A.ChannelSet("roughness", (A.Num(1),)),)) for layer in layers),
        ),
    )
    return np.asarray(evaluate(probe, size, size).roughness)


def test_dirt_in_the_grout_stays_in_the_joints() -> None:
    before = program("quick")
    result = edit_offline(before, "add dirt in the mortar joints")
    assert "in the joints" in result.report.plan["note"]
    added = _added_layers(before, result.program)
    assert added
    cover = _coverage(result.program, added)
    joints = _coverage(before, parse_program(before).layers[1:2])  # the bricks' own layer
    on_bricks = cover[joints > 0.99]
    in_joints = cover[joints < 0.01]
    assert on_bricks.size and in_joints.size
    assert float(on_bricks.max()) < 0.05, "the dirt spilled onto the bricks"
    assert float(in_joints.mean()) > 0.3, "the joints got no dirt"


def test_dirt_without_joint_words_covers_the_bricks_too() -> None:
    before = program("quick")
    result = edit_offline(before, "add dirt")
    assert "in the joints" not in result.report.plan["note"]
    joints = _coverage(before, parse_program(before).layers[1:2])
    cover = _coverage(result.program, _added_layers(before, result.program))
    assert float(cover[joints > 0.99].max()) > 0.3


def test_spots_are_small_and_cover_little() -> None:
    before = program("brushed")
    plain = edit_offline(before, "add rust")
    spots = edit_offline(before, "add some rust spots")
    assert "as spots" in spots.report.plan["note"]
    share = float(_coverage(spots.program, _added_layers(before, spots.program)).mean())
    full = float(_coverage(plain.program, _added_layers(before, plain.program)).mean())
    assert 0.0 < share < 0.75 * full, (share, full)


def test_a_relief_step_that_does_not_show_in_the_lit_preview_is_escalated() -> None:
    # a wood grain: its relief x2 moves half of the normals but 1 % of the lit pixels
    from matloom.library import load_library

    before = load_library().entry("weathered-grey-barn-wood").program
    result = edit_offline(before, "deeper relief")
    a = evaluate(parse_program(before), 128, 128)
    b = evaluate(parse_program(result.program), 128, 128)
    visible, moved = lit_changes(a, b)
    assert visible >= 0.05, f"only {visible:.3f} of the lit preview changed visibly"
    assert moved >= visible
