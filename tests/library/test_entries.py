"""Every library entry and overlay: parses clean (no warnings), front matter matches the
program, evaluates finite at 128 x 128, tileable entries tile (seam ratio <= 1.2 per map), and
every slot Define reaches an output map."""

from __future__ import annotations

import pytest

import matloom
from matloom.lang.deps import channel_dependencies
from matloom.library import library
from matloom.library.checks import check_entry, evaluate_problems, overlay_reports
from matloom.library.overlay import compose

LIB = library()
NAMES = sorted(LIB.entries)


@pytest.mark.parametrize("name", NAMES)
def test_entry_is_clean_finite_and_tiles(name: str) -> None:
    report = check_entry(LIB, LIB.entry(name), size=128)
    assert report.ok, f"{LIB.entry(name).path}: " + "; ".join(report.problems)


def _reached(name: str) -> set[str]:
    """Define names whose literals some output map depends on."""
    deps = channel_dependencies(LIB.ast(name))
    return {p.where.removeprefix("Define ") for ps in deps.values() for p in ps}


@pytest.mark.parametrize("name", NAMES)
def test_every_slot_reaches_the_maps(name: str) -> None:
    entry = LIB.entry(name)
    reached = _reached(name)
    for slot in entry.colours:
        assert any(f"{slot}_{ch}" in reached for ch in "rgb"), (
            f"{name}: colour slot {slot} does not reach any map"
        )
    for scalar in entry.scalars:
        assert scalar in reached, f"{name}: scalar slot {scalar} does not reach any map"


#: one entry per category, evaluated for real: the main colour slot changes basecolor.
SAMPLE = sorted({e.category: e.name for e in LIB.entries.values() if e.colours}.values())


@pytest.mark.parametrize("name", SAMPLE)
def test_main_colour_changes_basecolor(name: str) -> None:
    from matloom.library.adapt import set_colour, slot_colour

    program = LIB.ast(name)
    slot = LIB.entry(name).colours[0]
    rgb = slot_colour(program, slot)
    assert rgb is not None, f"{name}: main colour slot {slot} is not a constant"
    other = tuple(255 - v for v in rgb)
    a = matloom.evaluate(program, 24, 24, backend="numpy")
    b = matloom.evaluate(set_colour(program, slot, other), 24, 24, backend="numpy")
    assert (abs(a.basecolor_linear - b.basecolor_linear) > 1e-3).any()


def test_overlays_are_clean() -> None:
    bad = {k: v for k, v in overlay_reports(LIB).items() if v}
    assert not bad


@pytest.mark.parametrize("overlay", sorted(LIB.overlays))
def test_overlay_composes_clean_finite_and_tileable(overlay: str) -> None:
    host = LIB.ast("cobblestone")
    program = compose(
        host, LIB.overlays[overlay], main_colour="base", cover=0.7, colour=(200, 30, 30)
    )
    text = matloom.format(program)
    assert matloom.check(text) == []
    assert len(program.layers) > len(host.layers)
    problems, _ = evaluate_problems(program, 48, program.tileable)
    assert not [p for p in problems if "non-finite" in p]
