"""The table of named materials (``library/data/materials.toml``): every row valid, found by
its name and aliases, and composed in its table colour and finish."""

from __future__ import annotations

from pathlib import Path

import pytest

import matloom.library.compose.named as named_mod
from matloom.library.compose.build import compose
from matloom.library.compose.named import (
    named_material,
    named_materials,
    named_phrases,
    normalise,
)
from matloom.library.compose.spec import CompositionSpec
from matloom.library.compose.tables import BASES
from matloom.library.entry import LibraryError


def test_the_table_is_large_and_valid() -> None:
    table = named_materials()
    assert len(table) >= 90
    for name, m in table.items():
        assert m.name == name and m.base in BASES and m.description
        assert m.colours[0][0] == "base"
    for wanted in ("malachite", "obsidian", "basalt", "jade", "amber", "turquoise", "lapis lazuli",
                   "onyx", "peat", "loam", "clay soil", "laterite", "recycled glass terrazzo",
                   "recycled plastic", "corian"):  # fmt: skip
        assert wanted in table, wanted


@pytest.mark.parametrize(
    ("said", "name"),
    [
        ("Malachite", "malachite"),
        ("Tiger's-Eye", "tiger's eye"),
        ("tigers eye", "tiger's eye"),
        ("volcanic glass", "obsidian"),
        ("LAPIS", "lapis lazuli"),
        ("clay_soil", "clay soil"),
        ("glass terrazzo", "recycled glass terrazzo"),
    ],
)
def test_lookup_by_name_or_alias(said: str, name: str) -> None:
    m = named_material(said)
    assert m is not None and m.name == name


def test_unknown_names_are_none() -> None:
    assert named_material("flurbonium") is None
    assert named_material("") is None
    assert normalise("  Rose   Quartz ") == "rose quartz"
    assert all(named_phrases()[normalise(n)] == n for n in named_materials())


def test_every_named_material_composes_in_its_colours() -> None:
    for name, m in named_materials().items():
        r = compose(CompositionSpec(base=m.base, named=name))
        assert r.tileable, name
        base = r.program
        rgb = tuple(base.define(f"base_{c}").expr.value for c in "rgb")  # type: ignore[union-attr]
        assert rgb == m.colour("base"), name
        if m.finish.roughness is not None:
            assert base.define("rough").expr.value == m.finish.roughness, name  # type: ignore[union-attr]
        assert any(name in s for s in r.shown), name


def test_a_malformed_row_names_the_file_and_the_key(tmp_path: Path, monkeypatch) -> None:  # noqa: ANN001
    bad = tmp_path / "materials.toml"
    bad.write_text('[gloop]\nbase = "jelly"\ndescription = "x"\ncolours = [[1, 2, 3]]\n')
    monkeypatch.setattr(named_mod, "MATERIALS_DIR", tmp_path)
    named_materials.cache_clear()
    named_phrases.cache_clear()
    try:
        with pytest.raises(LibraryError, match=r"\[gloop\] key 'base'"):
            named_materials()
        bad.write_text('[gloop]\nbase = "foam"\ndescription = "x"\ncolours = [[1, 2, 300]]\n')
        named_materials.cache_clear()
        with pytest.raises(LibraryError, match=r"key 'colours'"):
            named_materials()
        bad.write_text(
            '[gloop]\nbase = "foam"\ndescription = "x"\ncolours = [[1, 2, 3]]\nhue = 1\n'
        )
        named_materials.cache_clear()
        with pytest.raises(LibraryError, match=r"key 'hue'"):
            named_materials()
    finally:
        named_materials.cache_clear()
        named_phrases.cache_clear()


def _table(tmp_path: Path, monkeypatch, files: dict[str, str]) -> None:  # noqa: ANN001
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    monkeypatch.setattr(named_mod, "MATERIALS_DIR", tmp_path)
    named_materials.cache_clear()
    named_phrases.cache_clear()


@pytest.fixture
def fresh_cache():  # noqa: ANN201
    yield
    named_materials.cache_clear()
    named_phrases.cache_clear()


def test_a_name_two_files_give_is_an_error(tmp_path: Path, monkeypatch, fresh_cache) -> None:  # noqa: ANN001
    row = '[gloop]\nbase = "foam"\ndescription = "x"\ncolours = [[1, 2, 3]]\n'
    _table(tmp_path, monkeypatch, {"a.toml": row, "b.toml": row})
    with pytest.raises(LibraryError, match=r"b\.toml: \[gloop\] is already a row of a\.toml"):
        named_materials()


def test_layout_and_motif_keys_are_checked(tmp_path: Path, monkeypatch, fresh_cache) -> None:  # noqa: ANN001
    row = '[gloop]\nbase = "foam"\ndescription = "x"\ncolours = [[1, 2, 3]]\n'
    _table(tmp_path, monkeypatch, {"a.toml": row + 'layout = "spirals"\n'})
    with pytest.raises(LibraryError, match=r"key 'layout': 'spirals' is not a layout"):
        named_materials()
    _table(tmp_path, monkeypatch, {"a.toml": row + 'motif = "dragon"\n'})
    with pytest.raises(LibraryError, match=r"key 'motif': 'dragon' is not a motif"):
        named_materials()


def test_a_named_layout_and_motif_are_used_unless_the_request_names_its_own(
    tmp_path: Path,
    monkeypatch,  # noqa: ANN001
    fresh_cache,  # noqa: ANN001
) -> None:
    _table(tmp_path, monkeypatch, {"a.toml": (
        '[gloop]\nbase = "metal"\ndescription = "x"\ncolours = [[150, 150, 150]]\n'
        'layout = "grid"\nmotif = "flower"\n'
    )})  # fmt: skip
    own = compose(CompositionSpec(base="metal", named="gloop"))
    assert any(s.startswith("layout: grid ") for s in own.shown)
    assert any(s.startswith("motif: flower") for s in own.shown)
    said = compose(CompositionSpec(base="metal", named="gloop", layout="hexagons"))
    assert any(s.startswith("layout: hexagons") for s in said.shown)
    assert any(s.startswith("motif: flower") for s in said.shown)
    plain = compose(CompositionSpec(base="metal"))
    assert not any(s.startswith(("layout:", "motif:")) for s in plain.shown)


def test_every_named_layout_and_motif_is_shown() -> None:
    for name, m in named_materials().items():
        if m.layout is None and m.motif is None:
            continue
        shown = compose(CompositionSpec(base=m.base, named=name)).shown
        if m.layout is not None:
            assert any(s.startswith(f"layout: {m.layout} ") for s in shown), name
        if m.motif is not None:
            assert any(s.startswith(f"motif: {m.motif} ") for s in shown), name


def test_a_named_accent_colours_the_motif_on_a_base_without_accents(
    tmp_path: Path,
    monkeypatch,  # noqa: ANN001
    fresh_cache,  # noqa: ANN001
) -> None:
    """Pepperoni on a pizza: the row's accent colours its motif where the base shows no
    accents of its own; too close to the ground, the usual contrasting shade is used."""
    row = '[gloop]\nbase = "plaster"\ndescription = "x"\nlayout = "scatter"\nmotif = "circle"\n'
    _table(tmp_path, monkeypatch, {"a.toml": row + "colours = [[236, 186, 96], [220, 152, 64], [180, 40, 30]]\n"})  # fmt: skip
    prog = compose(CompositionSpec(base="plaster", named="gloop")).program
    rgb = tuple(prog.define(f"motif_{c}").expr.value for c in "rgb")  # type: ignore[union-attr]
    assert rgb == (180, 40, 30)
    _table(tmp_path, monkeypatch, {"a.toml": row + "colours = [[236, 186, 96], [220, 152, 64], [232, 184, 98]]\n"})  # fmt: skip
    prog = compose(CompositionSpec(base="plaster", named="gloop")).program
    rgb = tuple(prog.define(f"motif_{c}").expr.value for c in "rgb")  # type: ignore[union-attr]
    assert rgb != (232, 184, 98)
