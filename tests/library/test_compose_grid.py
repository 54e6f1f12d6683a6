"""The composer builds a valid, tileable program with named parameters for every combination of
its parts, without rendering them (renders: ``test_compose_render.py``).

A full base x layout x motif product is ~18,000 programs (about 15 ms each to check): the grid
composes every base x layout pair (the plain base included) with a motif that cycles so that
every layout x motif pair occurs too, and checks the base x motif pairs where they can clash:
the Define names each part writes are disjoint from every other part's (a clash is the one way
two parts that are each valid could make an invalid program together).
"""

from __future__ import annotations

import pytest

from matloom.lang import ast as A
from matloom.lang.params import list_params
from matloom.library.compose.build import compose
from matloom.library.compose.layouts import build_layout
from matloom.library.compose.motifs import place_motif
from matloom.library.compose.spec import CompositionSpec, MotifSpec
from matloom.library.compose.structure import Ctx
from matloom.library.compose.structures import STRUCTURES
from matloom.library.compose.tables import BASES, LAYOUTS, MOTIFS, word_index
from matloom.library.compose.writer import Axes, Writer
from matloom.library.entry import entry_from_text
from matloom.library.labels import entry_labels

BASE_NAMES = list(BASES)
LAYOUT_NAMES: list[str | None] = [None, *LAYOUTS]
MOTIF_NAMES = list(MOTIFS)


def _grid() -> list[tuple[str, str | None, str]]:
    return [
        (b, layout, MOTIF_NAMES[(i + j) % len(MOTIF_NAMES)])
        for i, b in enumerate(BASE_NAMES)
        for j, layout in enumerate(LAYOUT_NAMES)
    ]


def test_the_grid_covers_every_base_layout_and_layout_motif_pair() -> None:
    grid = _grid()
    assert {(b, layout) for b, layout, _ in grid} == {
        (b, layout) for b in BASE_NAMES for layout in LAYOUT_NAMES
    }
    assert {(layout, m) for _, layout, m in grid} == {
        (layout, m) for layout in LAYOUT_NAMES for m in MOTIF_NAMES
    }


@pytest.mark.parametrize("base", BASE_NAMES)
def test_every_combination_checks_and_tiles(base: str) -> None:
    """compose() parses and checks its program (any diagnostic, warnings included, raises) and
    measures its tileability; every one must tile, with its View, and list parameters."""
    rows = [row for row in _grid() if row[0] == base]
    for k, (b, layout, motif) in enumerate(rows):
        spec = CompositionSpec(base=b, layout=layout, motif=MotifSpec(motif), seed=k)
        r = compose(spec)
        where = f"{b} / {layout} / {motif}"
        assert r.tileable and r.program.view.tileable, f"{where}: {r.dropped}"
        assert r.program.unit_m == r.unit_m > 0, where
        assert not [d for d in r.dropped if "tiling" in d or "unknown" in d], where
        names = {d.name for d in r.program.defines}
        assert {"base_r", "rough", "relief"} <= names, where
        if layout is None or not LAYOUTS[layout].holes:
            assert "motif_size" in names and "motif_r" in names, where
    # the parameter listing, on one layout per base (it is the slow part)
    layout = LAYOUT_NAMES[BASE_NAMES.index(base) % len(LAYOUT_NAMES)]
    r = compose(CompositionSpec(base=base, layout=layout, motif=MotifSpec("star")))
    labels = entry_labels(entry_from_text(r.text, "composed.mat"), r.program)
    params = {p.address: p for p in list_params(r.program, labels)}
    assert params["define:base"].kind == "colour" and params["define:base"].label == "base colour"
    for slot in entry_from_text(r.text, "composed.mat").colours:  # every literal colour slot
        if isinstance(r.program.define(f"{slot}_r").expr, A.Num):  # type: ignore[union-attr]
            assert params[f"define:{slot}"].kind == "colour", slot
    assert params["define:rough"].label == "roughness"
    assert dict(r.labels)["define:rough"] == "roughness"


@pytest.mark.parametrize("layout", list(LAYOUTS))
def test_every_layout_lists_its_parameters(layout: str) -> None:
    base = BASE_NAMES[LAYOUT_NAMES.index(layout) * 5 % len(BASE_NAMES)]
    r = compose(CompositionSpec(base=base, layout=layout))
    params = {p.address for p in list_params(r.program)}
    assert {"define:base", "define:rough", "define:relief"} <= params
    if LAYOUTS[layout].joints:
        assert "define:grout_width" in params and "define:grout" in params


def _base_names(b, sfx: str, vertical: bool) -> set[str]:  # noqa: ANN001 - a BaseSpec
    w = Writer(0.3, 4, 100)
    STRUCTURES[b.structure](Ctx(w, b, Axes(vertical), sfx, "0"))
    return set(w.names)


def _layout_names(spec) -> set[str]:  # noqa: ANN001 - a LayoutSpec
    w = Writer(0.3, spec.side, 100)
    build_layout(w, spec)
    return set(w.names) - {"grout_width"}


def _motif_names(m, spec) -> set[str]:  # noqa: ANN001 - a MotifShape and a LayoutSpec
    w = Writer(0.3, spec.side, 100)
    place_motif(w, m, spec.lattice, spec.name == "scatter")
    return set(w.names)


def test_the_parts_write_disjoint_define_names() -> None:
    """Every base (flat and under upright planks), layout and motif writes names no other kind
    of part writes, so every base x layout x motif combination is free of clashes."""
    heads = {"rough", "metal", "gloss", "clarity", "relief", "variation", "motif_size"}
    heads |= {"shade", "body", "plate", "surface", "solid", "accent_mask", "metal_var"}
    heads |= {"grout_width"}
    bases: set[str] = set()
    for b in BASES.values():
        for sfx, vertical in (("", False), ("_flat", False), ("_up", True)):
            bases |= _base_names(b, sfx, vertical)
    layouts: set[str] = set()
    for spec in LAYOUTS.values():
        layouts |= _layout_names(spec)
    motifs: set[str] = set()
    for m in MOTIFS.values():
        for spec in LAYOUTS.values():
            motifs |= _motif_names(m, spec)
    names = {
        "base",
        "secondary",
        "accent",
        "grout",
        "motif",
        *(s.alt_slot for s in LAYOUTS.values()),
    }
    # a Define named like a slot would also hide the slot's colour parameter (define:motif)
    slots = names | {f"{s}_{c}" for s in names for c in "rgb"}
    parts = {"bases": bases, "layouts": layouts, "motifs": motifs, "slots": slots}
    for a, names_a in parts.items():
        for b, names_b in parts.items():
            if a < b:
                assert not names_a & names_b, f"{a} and {b} both write {sorted(names_a & names_b)}"
    everything = bases | layouts | motifs | slots
    assert not everything & heads, everything & heads


def test_a_directional_base_follows_upright_planks() -> None:
    r = compose(CompositionSpec(base="wood", layout="herringbone"))
    text = r.text
    assert (
        "rings_flat" in text and "rings_up" in text and "Mix(tone_flat, tone_up, upright)" in text
    )
    plain = compose(CompositionSpec(base="wood", layout="brick"))
    assert "rings_up" not in plain.text


def test_words_are_unique_within_each_table() -> None:
    for table, specs in (("bases", BASES), ("layouts", LAYOUTS), ("motifs", MOTIFS)):
        seen: dict[str, str] = {}
        for name, spec in specs.items():
            for word in spec.words:
                assert word not in seen or seen[word] == name, (table, word, seen.get(word), name)
                seen[word] = name
        index = word_index(table)
        assert all(index[name] == name for name in specs)


def test_accents_follow_the_accent_share() -> None:
    """The palette gives an accent slot exactly to the bases whose structure draws accents."""
    for b in BASES.values():
        w = Writer(0.3, 4, 100)
        s = STRUCTURES[b.structure](Ctx(w, b, Axes(), "", "0"))
        assert (s.accent is not None) == (b.accent_share > 0), b.name


def test_the_docs_count_the_parts() -> None:
    from pathlib import Path

    from matloom.library.compose.named import named_materials

    text = (Path(__file__).resolve().parents[2] / "docs" / "library.md").read_text("utf-8")
    counts = (len(BASES), len(LAYOUTS), len(MOTIFS), len(named_materials()))
    sentence = "{} bases, {} layouts, {} motifs and {} named materials".format(*counts)
    assert sentence in " ".join(text.split()), f"docs/library.md should say: {sentence}"


def test_small_cells_widen_the_view_by_whole_repeats() -> None:
    """2 cm tesserae: the View shows at least MIN_VIEW_M of the material (whole repeats of the
    layout, so it still tiles); a 20 cm tile keeps the layout's own View."""
    from matloom.library.compose.plan import MAX_REPEATS, MIN_VIEW_M

    small = compose(CompositionSpec(base="stone", layout="grid", size_m=0.02))
    big = compose(CompositionSpec(base="stone", layout="grid", size_m=0.2))
    assert small.tileable and big.tileable
    v, w = small.program.view, big.program.view
    assert v is not None and w is not None
    side_small, side_big = v.x2 - v.x1, w.x2 - w.x1
    assert side_big == LAYOUTS["grid"].side
    assert side_small == LAYOUTS["grid"].side * MAX_REPEATS
    assert side_small * small.unit_m >= MIN_VIEW_M > side_big * small.unit_m
