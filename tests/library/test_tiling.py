"""Tiling of the library's output: the periodicity check, where the author puts the wrap edge
(``place_origin``) and the seam ratio of a pattern whose lines would otherwise run along it."""

from __future__ import annotations

import matloom
from matloom.engine.tiling import manifest_entry
from matloom.library import author, library
from matloom.library.adapt import place_origin, resize_view
from matloom.library.checks import SEAM_LIMIT, period_problems
from matloom.library.entry import entry_from_text
from matloom.vocab.layout import LAYOUT

BRICKS = """View(0, 0, 2, 2, tileable=True)
Define(b, Bricks(brick_width=0.5, brick_height=0.25, mortar=0.02))
Material(Layer(1).basecolor((40 + (b * 160)), 60, 50).height((b * 0.01)))
"""


def worst_seam(program: str | matloom.lang.ast.Program, size: int) -> float:
    maps = matloom.evaluate(program, size, size, backend="numpy")
    return max(manifest_entry(maps, LAYOUT.maps)["seam_ratio"].values())


def test_period_check_passes_a_periodic_program_whatever_its_seam_ratio() -> None:
    # mortar on the View's edge: the single-render ratio reports a seam, the maps repeat exactly
    assert worst_seam(BRICKS, 128) > SEAM_LIMIT
    assert period_problems(BRICKS, 32) == []


def test_period_check_catches_a_program_that_does_not_repeat() -> None:
    # a raw X() ramp: the checker warns (W010) and the maps change when the View moves
    program = "View(0, 0, 1, 1, tileable=True)\nMaterial(Layer(1).basecolor((X() * 255), 0, 0))\n"
    problems = period_problems(program, 32)
    assert problems and "width" in problems[0] and "basecolor" in problems[0]
    assert not any("height" in p for p in problems)  # X() does not change along y


ENTRY = """# ---
# description = "test bricks"
# category = "masonry"
# tags = ["brick"]
# size_m = 1
# tileable = true
# colours = []
# ---
"""


def test_an_entry_origin_moves_the_wrap_edge_into_the_cells() -> None:
    program = matloom.parse(BRICKS)
    entry = entry_from_text(
        ENTRY.replace("# ---\n", "# ---\n# origin = [0.1, 0.05]\n", 1) + BRICKS, "masonry/t.mat"
    )
    assert entry.origin == (0.1, 0.05)
    moved = place_origin(program, entry)
    assert moved.view_tuple == (0.1, 0.05, 2.1, 2.05)
    assert worst_seam(moved, 128) <= SEAM_LIMIT  # the mortar no longer runs along the edge
    assert period_problems(moved, 32) == []


def test_a_rescaled_or_centred_view_keeps_the_entry_corner() -> None:
    entry = entry_from_text(ENTRY + BRICKS, "masonry/t.mat")
    centred = matloom.parse(BRICKS.replace("View(0, 0, 2, 2", "View(-1, -1, 1, 1"))
    own = centred.view_tuple
    bigger = resize_view(centred, 3.0)
    assert bigger.view_tuple == (-1.5, -1.5, 1.5, 1.5)  # a plain render stays centred
    assert place_origin(bigger, entry, own).view_tuple == (-1.0, -1.0, 2.0, 2.0)
    same = matloom.parse(BRICKS)
    assert place_origin(same, entry) is same


def test_oak_planks_tile_without_a_measured_seam() -> None:
    # wood-planks started on a joint (View(0, 0, 4, 4)): 8.1 on the normal map at 512
    r = author("oak planks")
    assert r.tileable and r.entry == "wood-planks"
    x1, y1, _, _ = matloom.parse(r.program).view_tuple
    assert (x1, y1) != (0.0, 0.0)
    assert worst_seam(r.program, 256) <= SEAM_LIMIT
    assert period_problems(r.program, 32) == []


def test_non_tileable_output_keeps_the_entry_view() -> None:
    r = author("oak planks", tileable=False)
    own = library().ast(r.entry).view_tuple
    assert matloom.parse(r.program).view_tuple == own
