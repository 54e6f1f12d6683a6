"""Composed programs rendered small: finite maps, the layout and the motif visible, every map
repeating with the View, colour roles landing in the base colour, and the spec's sizes,
finish and notes honoured."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from matloom.engine.evaluate import evaluate
from matloom.lang.api import parse
from matloom.lang.params import list_params, set_params
from matloom.lang.printer import format_program
from matloom.library.checks import period_problems
from matloom.library.colour import RGB
from matloom.library.compose.build import compose
from matloom.library.compose.named import named_material
from matloom.library.compose.spec import CompositionSpec, Finish, MotifSpec
from matloom.library.entry import entry_from_text
from matloom.library.labels import entry_labels
from matloom.vocab.layout import LAYOUT

SIZE = 50  # not a multiple of the patterns' cells per unit (no lucky aliasing)

SAMPLES = [
    CompositionSpec(base="ceramic", layout="grid", motif=MotifSpec("star")),
    CompositionSpec(base="wood", layout="herringbone"),
    CompositionSpec(base="fabric", layout="stripes", motif=MotifSpec("heart")),
    CompositionSpec(base="metal", layout="perforations", motif=MotifSpec("ellipse")),
    CompositionSpec(base="marble", layout="hexagons"),
    CompositionSpec(base="leather", layout="quilting", motif=MotifSpec("maze")),
    CompositionSpec(base="grass", layout="scatter", motif=MotifSpec("leaf")),
    CompositionSpec(base="terrazzo"),
]


def _srgb(maps, mask: np.ndarray | None = None) -> np.ndarray:  # noqa: ANN001 - MaterialMaps
    """Mean base colour (sRGB 0-255) over ``mask`` (all texels without one)."""
    lin = np.clip(np.asarray(maps.basecolor_linear, dtype=np.float64), 0, 1)
    srgb = np.where(lin <= 0.0031308, lin * 12.92, 1.055 * lin ** (1 / 2.4) - 0.055) * 255
    pixels = srgb.reshape(-1, 3) if mask is None else srgb[mask]
    return pixels.mean(axis=0)


def _field(r, name: str, size: int = SIZE) -> np.ndarray:  # noqa: ANN001 - ComposedProgram
    """A Define of the composed program rendered as a height map (its values)."""
    text = format_program(r.program).split("Material(")[0]
    maps = evaluate(text + f"Material(Layer(1).height({name}))", size, size)
    return np.asarray(maps.height)


@pytest.mark.parametrize("spec", SAMPLES, ids=lambda s: f"{s.base}-{s.layout}")
def test_sampled_programs_render_finite_visible_and_seamless(spec: CompositionSpec) -> None:
    r = compose(spec)
    maps = evaluate(r.program, SIZE, SIZE)
    for name in LAYOUT.map_fields:
        assert np.isfinite(np.asarray(getattr(maps, name))).all(), name
    colour = np.asarray(maps.basecolor_linear)
    assert colour.std(axis=(0, 1)).max() > 0.01, "a flat base colour"
    assert np.asarray(maps.height).std() > 0, "no relief"
    if spec.layout is not None:
        cells = _field(r, "tiles", 128) if "tiles" in {d.name for d in r.program.defines} else None
        if cells is not None:
            assert 0.01 < float((cells < 0.5).mean()) < 0.6, "joints missing or everywhere"
    if spec.motif is not None:
        motif = _field(r, "motifs")
        assert 0.02 < float((motif > 0.5).mean()) < 0.8, "the motif does not show"
    # every map repeats with the View: evaluated one View width (and height) further on
    assert period_problems(r.program, 32) == []


def test_a_seam_is_caught() -> None:
    """The seamless check fails on a program that does not repeat with its View."""
    r = compose(CompositionSpec(base="ceramic", layout="grid"))
    text = format_program(r.program).replace(
        "Bricks(brick_height=1,", "Bricks(brick_width=0.9, brick_height=1,"
    )
    assert period_problems(text, 32)


def _close(a: np.ndarray, b: RGB, tol: float) -> bool:
    return bool(np.abs(a - np.asarray(b, dtype=np.float64)).max() <= tol)


def test_colour_roles_land_in_the_base_colour() -> None:
    base, motif, grout = (200, 50, 40), (30, 40, 190), (235, 235, 230)
    spec = CompositionSpec(
        base="plastic",
        layout="grid",
        motif=MotifSpec("circle", colour=motif, scale=0.7),
        colours=(("base", base), ("grout", grout)),
    )
    r = compose(spec)
    wide, _ = set_params(r.program, {"define:grout_width": 0.2})  # joints a few texels wide
    r = replace(r, program=parse(wide))
    maps = evaluate(r.program, 64, 64)
    m, cells = _field(r, "motifs", 64) > 0.99, _field(r, "tiles", 64)
    ground = (cells > 0.99) & ~(_field(r, "motifs", 64) > 0.01)
    joints = cells < 0.01
    assert m.sum() > 50 and ground.sum() > 50 and joints.sum() > 20
    assert _close(_srgb(maps, m), motif, 12), _srgb(maps, m)
    assert _close(_srgb(maps, ground), base, 25), _srgb(maps, ground)
    assert _close(_srgb(maps, joints), grout, 12), _srgb(maps, joints)
    assert any("grout" in s for s in r.shown) and any("the motif" in s for s in r.shown)


def test_two_colour_layouts_take_both_colours() -> None:
    black, white = (20, 20, 22), (240, 240, 236)
    r = compose(
        CompositionSpec(base="felt", layout="checks", colours=(("base", black), ("base", white)))
    )
    maps = evaluate(r.program, 64, 64)
    alt = _field(r, "checker", 64) > 0.5
    assert 0.4 < alt.mean() < 0.6
    assert _close(_srgb(maps, alt), white, 30) and _close(_srgb(maps, ~alt), black, 30)
    assert "tiles" not in {d.name for d in r.program.defines}  # printed checks: no joints


def test_a_named_material_gets_its_table_colour() -> None:
    nm = named_material("malachite")
    assert nm is not None and nm.base == "mineral"
    r = compose(CompositionSpec(base=nm.base, named="malachite"))
    mean = _srgb(evaluate(r.program, 48, 48))
    table = np.asarray([c for _, c in nm.colours[:2]], dtype=np.float64)
    assert mean[1] > mean[0] + 30 and mean[1] > mean[2] + 10, mean  # green, as malachite is
    assert np.abs(mean - table.mean(axis=0)).max() < 40, (mean, table)
    assert any("malachite" in s for s in r.shown)
    # the request's own colour wins over the table's
    red = compose(
        CompositionSpec(base="mineral", named="malachite", colours=(("base", (200, 30, 30)),))
    )
    assert red.program.define("base_r") is not None and "Define(base_r, 200)" in red.text


def test_size_finish_and_notes() -> None:
    r = compose(
        CompositionSpec(
            base="ceramic",
            layout="grid",
            size_m=0.3,
            colours=(("stripe", (1, 2, 3)),),
            finish=Finish(roughness=0.05, translucency=0.3, words=("glossy",)),
            motif=MotifSpec("unicorn"),
        )  # fmt: skip
    )
    assert r.unit_m == 0.3 and r.program.unit_m == 0.3
    x1, _, x2, _ = r.program.view_tuple
    assert abs((x2 - x1) * r.unit_m - 1.2) < 1e-9
    entry = entry_from_text(r.text, "composed-tiles.mat")
    assert entry.size_m == pytest.approx(1.2) and entry.tileable and entry.category == "ceramic"
    params = {p.address: p for p in list_params(r.program, entry_labels(entry, r.program))}
    assert params["define:rough"].value == 0.05 and params["define:clarity"].value == 0.3
    assert params["define:grout_width"].metres == pytest.approx(0.04 * 0.3)
    assert params["define:grout_width"].label == "gap width"
    assert any("unicorn" in d and "unknown motif" in d for d in r.dropped)
    assert any(d.startswith("colour stripe") for d in r.dropped)
    assert any("roughness 0.05 (glossy)" in s for s in r.shown)
    assert ".transmission(clarity)" in r.text


def test_composition_is_deterministic_and_seeded() -> None:
    spec = CompositionSpec(base="granite", layout="brick", motif=MotifSpec("cat"), seed=3)
    assert compose(spec).text == compose(spec).text
    other = compose(CompositionSpec(base="granite", layout="brick", motif=MotifSpec("cat"), seed=4))
    assert other.text != compose(spec).text
