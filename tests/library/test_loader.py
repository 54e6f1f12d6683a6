"""Front matter parsing and validation: every error names the file and the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from matloom.library import LibraryError, load_entry, load_library
from matloom.library.entry import entry_from_text

PROGRAM = """View(0, 0, 1, 1, tileable=True)
Define(base_r, 200)
Define(base_g, 100)
Define(base_b, 50)
Define(rough, 0.5)
Material(
  Layer(1)
    .basecolor(base_r, base_g, base_b)
    .roughness(rough)
)
"""

GOOD = {
    "description": '"A plain test surface"',
    "category": '"plastic"',
    "tags": '["plain", "test"]',
    "size_m": "1",
    "tileable": "true",
    "colours": '["base"]',
}


def text(fields: dict[str, str] | None = None, extra: str = "", program: str = PROGRAM) -> str:
    lines = [f"# {k} = {v}" for k, v in (fields if fields is not None else GOOD).items()]
    if extra:
        lines.append(extra)
    return "# ---\n" + "\n".join(lines) + "\n# ---\n" + program


def fail(source: str, *needles: str) -> None:
    with pytest.raises(LibraryError) as err:
        entry_from_text(source, Path("lib/plastic/plain-test.mat"))
    message = str(err.value)
    assert "plain-test.mat" in message
    for needle in needles:
        assert needle in message, message


def test_good_entry_loads() -> None:
    e = entry_from_text(text(extra='# [scalars]\n# rough = "roughness"'), "x/plain-test.mat")
    assert e.name == "plain-test"
    assert e.colours == ("base",)
    assert e.scalars == {"rough": "roughness"}
    assert e.tileable is True
    assert e.program.startswith("View(")


def test_missing_fences() -> None:
    fail(PROGRAM, "must start with")
    fail("# ---\n# description = 'x'\n" + PROGRAM, "no closing")


def test_front_matter_lines_must_be_comments() -> None:
    fail("# ---\ndescription = 'x'\n# ---\n" + PROGRAM, "must be '#' comments")


def test_invalid_toml() -> None:
    fail(text(extra="# tags = [unclosed"), "not valid TOML")


@pytest.mark.parametrize(
    "key", ["description", "category", "tags", "size_m", "tileable", "colours"]
)
def test_missing_required_key(key: str) -> None:
    fields = {k: v for k, v in GOOD.items() if k != key}
    fail(text(fields), f"'{key}'", "missing")


@pytest.mark.parametrize(
    ("key", "value", "needle"),
    [
        ("category", '"spaceship"', "not one of"),
        ("size_m", "-2", "> 0"),
        ("size_m", '"big"', "expected a number"),
        ("tileable", '"yes"', "true or false"),
        ("tags", '"wood"', "list of non-empty strings"),
        ("description", '""', "non-empty string"),
    ],
)
def test_bad_values(key: str, value: str, needle: str) -> None:
    fail(text({**GOOD, key: value}), f"'{key}'", needle)


def test_unknown_key_is_an_error() -> None:
    fail(text(extra='# colour = "red"'), "'colour'", "unknown key")


def test_bad_tables() -> None:
    fail(text(extra='# [scalars]\n# rough = "shininess"'), "'scalars.rough'", "kind")
    fail(text(extra='# [roles]\n# grout = "grout"'), "'roles.grout'", "no colour slot")
    fail(text(extra="# [presets.walnut]\n# base = [1, 2]"), "'presets.walnut.base'")
    fail(text(extra="# [presets.walnut]\n# base = [300, 2, 3]"), "'presets.walnut.base'")


def test_file_name_must_be_lowercase_words(tmp_path: Path) -> None:
    path = tmp_path / "Plain_Test.mat"
    path.write_text(text())
    with pytest.raises(LibraryError, match="lowercase words"):
        load_entry(path)


def test_empty_program() -> None:
    fail(text(program=""), "no program")


def write(root: Path, category: str, name: str, source: str) -> None:
    (root / category).mkdir(parents=True, exist_ok=True)
    (root / category / f"{name}.mat").write_text(source)


def test_library_rejects_duplicate_names_and_misplaced_files(tmp_path: Path) -> None:
    empty = tmp_path / "overlays"
    empty.mkdir()
    write(tmp_path / "a", "plastic", "plain-test", text())
    write(tmp_path / "a", "wood", "plain-test", text({**GOOD, "category": '"wood"'}))
    with pytest.raises(LibraryError, match="also"):
        load_library(tmp_path / "a", empty)
    write(tmp_path / "b", "wood", "plain-test", text())
    with pytest.raises(LibraryError, match="'category'"):
        load_library(tmp_path / "b", empty)


def test_library_rejects_unknown_absorbed_overlay(tmp_path: Path) -> None:
    empty = tmp_path / "overlays"
    empty.mkdir()
    write(tmp_path / "c", "plastic", "plain-test", text(extra='# absorbs = ["mouldy"]'))
    with pytest.raises(LibraryError, match="'absorbs'"):
        load_library(tmp_path / "c", empty)
