"""Reading a request as parts: a table of requests and the parts they name (class, named
material, colours with roles, layout, motif, construction, finish, size), the vocabulary's
keys against the composer's tables, and :func:`to_spec`."""

from __future__ import annotations

from typing import Any

import pytest

from matloom.library import colour as C
from matloom.library.compose.tables import BASES, LAYOUTS, MOTIFS
from matloom.library.data import words
from matloom.library.parts import read_parts, to_spec
from matloom.library.parts_words import parts_words, vocabulary

# prompt -> the parts it names. Keys: cls (a BASES key), named, colours ([(words, role)], in
# order), layout, motif, construction, finish (words), size (m), count, overlays, unknown
# (motifs no table holds). A key left out must be empty (None, () or 1.0 for the scale).
TABLE: list[tuple[str, dict[str, Any]]] = [
    ("peat moss ground", {"cls": "soil", "named": "peat", "overlays": ("mossy",)}),
    ("basalt fibre cloth", {"cls": "fabric", "named": "basalt"}),
    (
        "blue knitted wool with white stars",
        {
            "cls": "knit",
            "construction": "knit",
            "colours": [("blue", "base"), ("white", "motif")],
            "motif": "star",
        },
    ),
    (
        "cotton print with orange fox figures",
        {
            "cls": "fabric",
            "construction": "print",
            "colours": [("orange", "motif")],
            "motif": "dog",
        },
    ),
    ("rows of boxes wallpaper", {"cls": "paper", "layout": "rows", "motif": "box"}),
    (
        "cork board with oval perforations",
        {"cls": "cork", "layout": "perforations", "motif": "ellipse"},
    ),
    (
        "red and white striped cotton",
        {"cls": "fabric", "colours": [("red", "base"), ("white", "stripe")], "layout": "stripes"},
    ),
    ("giraffe figures on linen", {"named": "linen", "unknown": ("giraffe figures",)}),
    ("fish scale tiles", {"layout": "grid"}),
    (
        "translucent green resin with gold flecks",
        {
            "cls": "resin",
            "colours": [("green", "base"), ("gold", "secondary")],
            "finish": ("translucent",),
        },
    ),
    (
        "hexagon tiles with white grout, 10 cm",
        {"colours": [("white", "grout")], "layout": "hexagons", "size": 0.1},
    ),
    ("Tweed: a rough woollen fabric", {"cls": "fabric", "finish": ("rough",)}),
    (
        "glossy black obsidian",
        {"named": "obsidian", "colours": [("black", "base")], "finish": ("glossy",)},
    ),
    ("obsidian volcanic glass", {"named": "obsidian"}),
    # a colour inside a longer name is part of the name, and still the colour
    (
        "polished rose quartz",
        {"named": "rose quartz", "colours": [("rose", "base")], "finish": ("polished",)},
    ),
    ("black sand beach", {"named": "black sand", "colours": [("black", "base")]}),
    ("rose pink silk", {"named": "silk", "colours": [("rose pink", "base")]}),
    ("malachite", {"named": "malachite"}),
    ("recycled glass terrazzo", {"named": "recycled glass terrazzo"}),
    (
        "polished green malachite tiles",
        {
            "named": "malachite",
            "colours": [("green", "base")],
            "finish": ("polished",),
            "layout": "grid",
        },
    ),
    (
        "navy velvet with gold polka dots",
        {
            "cls": "fabric",
            "construction": "pile",
            "colours": [("navy", "base"), ("gold", "motif")],
            "motif": "dot",
        },
    ),
    (
        "embroidered linen with red flowers",
        {
            "named": "linen",
            "construction": "embroidery",
            "colours": [("red", "motif")],
            "motif": "flower",
        },
    ),
    (
        "grey felt with animal figures",
        {"cls": "felt", "colours": [("grey", "base")], "motif": "dog"},
    ),
    (
        "matte black rubber with raised circles",
        {
            "cls": "rubber",
            "colours": [("black", "base")],
            "finish": ("matte", "raised"),
            "motif": "circle",
        },
    ),
    ("herringbone oak floor", {"named": "oak", "layout": "herringbone"}),
    (
        "frosted glass with etched stars",
        {"cls": "glass", "finish": ("frosted",), "motif": "star"},
    ),
    ("mossy cobblestone path after rain", {"overlays": ("mossy", "wet")}),
    (
        "black and white checkered vinyl floor",
        {
            "cls": "plastic",
            "colours": [("black", "base"), ("white", "accent")],
            "layout": "checks",
        },
    ),
    ("rusty corrugated metal", {"cls": "metal", "overlays": ("rusty",)}),
    ("30 cm slate tiles in a grid", {"cls": "slate", "layout": "grid", "size": 0.3}),
    (
        "pink wallpaper with little hearts",
        {"cls": "paper", "colours": [("pink", "base")], "motif": "heart", "scale": 0.7},
    ),
    (
        "yellow silk with blue birds",
        {"named": "silk", "colours": [("yellow", "base"), ("blue", "motif")], "motif": "bird"},
    ),
    (
        "white porcelain with a cobalt maze pattern",
        {"cls": "porcelain", "colours": [("white", "base"), ("cobalt", "motif")], "motif": "maze"},
    ),
    ("tree bark", {"cls": "bark"}),
    (
        "autumn leaves on wet ground",
        {"cls": "soil", "motif": "leaf", "explicit": False, "overlays": ("wet",)},
    ),
    (
        "brushed steel with a diamond pattern",
        {"cls": "brushed_metal", "named": "steel", "finish": ("brushed",), "motif": "diamond"},
    ),
    ("terracotta tiles with dark grout", {"named": "terracotta", "layout": "grid"}),
    ("red brick wall", {"colours": [("red", "base")], "layout": "brick"}),
    (
        "semi translucent amber resin",
        {"cls": "resin", "named": "amber", "finish": ("semi", "translucent")},
    ),
    ("sandy beach with scattered shells", {"cls": "sand", "layout": "scatter"}),
    (
        "quilted satin in champagne",
        {
            "cls": "fabric",
            "colours": [("champagne", "base")],
            "finish": ("satin",),
            "layout": "quilting",
        },
    ),
    (
        "knitted jersey with pink hearts",
        {"cls": "knit", "construction": "knit", "colours": [("pink", "motif")], "motif": "heart"},
    ),
    (
        "a plush pile carpet in teal",
        {"construction": "pile", "colours": [("teal", "base")], "finish": ("plush",)},
    ),
    (
        "denim with white paw prints",
        {
            "named": "denim",
            "construction": "print",
            "colours": [("white", "motif")],
            "motif": "paw",
        },
    ),
    ("sea glass pebbles", {"cls": "gravel", "named": "sea glass"}),
    ("8 wide walnut planks", {"cls": "wood", "named": "walnut", "count": 8, "scale": 1.4}),
    (
        "chevron print in mustard and grey",
        {
            "construction": "print",
            "colours": [("mustard", "base"), ("grey", "accent")],
            "layout": "chevron",
        },
    ),
    ("carrara marble with gold veins", {"cls": "marble", "colours": [("gold", "accent")]}),
    ("no stripes, plain beige linen", {"named": "linen", "colours": [("beige", "base")]}),
]


def _row(prompt: str) -> dict[str, Any]:
    p = read_parts(prompt)
    return {
        "cls": p.material_class,
        "named": p.named,
        "colours": [(c.words, c.role) for c in p.colours],
        "layout": p.layout,
        "motif": p.motif,
        "construction": p.construction,
        "finish": p.finish.words,
        "size": p.size_m,
        "count": p.count,
        "overlays": p.overlays,
        "unknown": tuple(u.words for u in p.unknown_motifs),
        "scale": round(p.scale, 3),
        "explicit": all(m.explicit for m in p.motifs),
    }


EMPTY: dict[str, Any] = {
    "cls": None,
    "named": None,
    "colours": [],
    "layout": None,
    "motif": None,
    "construction": None,
    "finish": (),
    "size": None,
    "count": None,
    "overlays": (),
    "unknown": (),
    "scale": 1.0,
    "explicit": True,
}


@pytest.mark.parametrize(("prompt", "expected"), TABLE, ids=[t[0][:32] for t in TABLE])
def test_request_reads_as_its_parts(prompt: str, expected: dict[str, Any]) -> None:
    got = _row(prompt)
    want = {**EMPTY, **expected}
    if want["size"] is not None:
        assert got["size"] == pytest.approx(want["size"])
        got["size"] = want["size"]
    assert got == want


def test_the_table_is_about_forty_requests() -> None:
    assert len(TABLE) >= 40


def test_every_word_maps_to_a_key_of_the_composer() -> None:
    pw = parts_words()
    assert set(pw.bases.values()) <= set(BASES)
    assert set(pw.layouts.values()) <= set(LAYOUTS)
    assert set(pw.motifs.values()) <= set(MOTIFS)
    assert set(pw.category_bases.values()) <= set(BASES)
    assert set(pw.construction_bases.values()) <= set(BASES)
    assert set(pw.colour_layouts) <= set(LAYOUTS)
    assert pw.motif_base in BASES
    # the extra words add to the composer's words, never re-map one of them
    for table, specs in (("bases", BASES), ("layouts", LAYOUTS), ("motifs", MOTIFS)):
        own = {w.replace("-", " ") for s in specs.values() for w in s.words}
        assert not own & set(getattr(pw, table)), table
        assert own <= set(vocabulary(table)), table


def test_negated_and_passing_motifs_are_not_requested() -> None:
    assert read_parts("linen without stars").motif is None
    # a singular motif noun inside a compound names no motif
    for prompt in ("tree bark", "heart pine boards", "fish scale tiles", "cardboard box"):
        assert read_parts(prompt).motif is None, prompt
    # the same nouns said as a motif are one
    assert read_parts("linen with a heart").motif == "heart"
    assert read_parts("cardboard with boxes").motif == "box"


def test_colour_roles_follow_the_noun_they_describe() -> None:
    p = read_parts("ivory tiles with charcoal grout and blue star motifs")
    assert [(c.words, c.role) for c in p.colours] == [
        ("ivory", "base"),
        ("charcoal", "grout"),
        ("blue", "motif"),
    ]
    assert p.motif == "star" and p.motifs[0].words == "star motifs"


def test_to_spec_carries_the_parts() -> None:
    p = read_parts("glossy navy velvet with gold polka dots, 2 cm")
    spec = to_spec(p)
    assert spec.base == "fabric" and spec.motif is not None and spec.motif.shape == "dot"
    assert spec.motif.colour == words().colour("gold")
    assert dict(spec.colours)["base"] == words().colour("navy")
    assert spec.size_m == pytest.approx(0.02)
    assert spec.finish.roughness == words().finish_roughness["glossy"]
    assert to_spec(read_parts("malachite")).named == "malachite"
    assert to_spec(read_parts("stars"), base="paper").base == "paper"
    with pytest.raises(ValueError, match="no material class"):
        to_spec(read_parts("zorblax"))


def test_translucency_and_metalness_are_read() -> None:
    assert read_parts("translucent blue glass").finish.translucency == pytest.approx(0.6)
    assert read_parts("opaque white glass").finish.translucency == 0.0
    metal = read_parts("metallic copper paint").finish.metallic
    assert metal is not None and metal > 0.5
    assert C.luminance(read_parts("dark red silk").colours[0].rgb) < C.luminance(
        words().named["red"]
    )


@pytest.mark.parametrize(
    "prompt",
    [
        "forest floor with fallen oak and maple leaves",
        "a carpet of pine needles",
        "crushed walnut shells",
    ],
)
def test_a_material_word_before_a_plant_part_names_the_plant(prompt: str) -> None:
    # "oak leaves" are leaves: not the material oak (which composed a wood with leaves)
    assert read_parts(prompt).named is None


def test_a_material_word_before_its_material_noun_is_still_the_material() -> None:
    assert read_parts("oak planks").named == "oak"
    assert read_parts("walnut veneer").named == "walnut"
