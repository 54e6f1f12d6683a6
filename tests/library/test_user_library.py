"""User libraries (`--library DIR`, `MATLOOM_LIBRARY_PATH`): their entries are ranked with the
built-in ones, replace those of the same name, say where they came from, and a bad or escaping
file is a one-line error or is skipped (docs/library.md, "Your own library")."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from matloom.cli.main import cli
from matloom.library import LibraryError, author, library, search
from matloom.library.user import ENV, library_dirs, library_for, split_path

PROGRAM = """View(0, 0, 4, 4, tileable=True)
Define(base_r, 40)
Define(base_g, 120)
Define(base_b, 200)
Define(rough, 0.4)
Material(Layer(1).basecolor(base_r, base_g, base_b).roughness(rough).height(0))
"""


def entry_text(
    description: str = "Zorblax house tile: our studio's signature flat blue glaze",
    category: str = "tiles",
    tags: str = '["zorblax", "house", "tile", "blue"]',
    program: str = PROGRAM,
) -> str:
    return (
        "# ---\n"
        f'# description = "{description}"\n'
        f'# category = "{category}"\n'
        f"# tags = {tags}\n"
        "# size_m = 1\n"
        "# tileable = true\n"
        '# colours = ["base"]\n'
        "# [scalars]\n"
        '# rough = "roughness"\n'
        "# ---\n" + program
    )


def write(folder: Path, name: str, text: str | None = None) -> Path:
    path = folder / f"{name}.mat"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text if text is not None else entry_text(), encoding="utf-8")
    return path


def run(*args: str, env: dict[str, str] | None = None) -> tuple[int, str]:
    res = CliRunner().invoke(cli, ["library", *args], env=env)
    return res.exit_code, res.output


@pytest.fixture(autouse=True)
def _no_env_library(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(ENV, raising=False)


def test_user_entries_are_ranked_with_the_built_in_ones(tmp_path: Path) -> None:
    write(tmp_path, "zorblax-tile")
    lib = library_for([tmp_path])
    assert len(lib.entries) == len(library().entries) + 1
    ranked = [c.name for c in search("zorblax blue tile", lib)]
    assert ranked[0] == "zorblax-tile"
    assert len(ranked) > 1  # the built-in tiles are ranked in the same index
    assert lib.source("zorblax-tile") == str(tmp_path.resolve())
    assert lib.source(ranked[1]) == "built-in"
    assert "zorblax-tile" not in library().entries  # the built-in library is untouched


def test_category_folders_and_flat_files_are_both_read(tmp_path: Path) -> None:
    write(tmp_path, "flat-one")
    write(tmp_path / "tiles", "in-folder")
    write(tmp_path / "notes", "ignored-folder")  # not a category: not read
    (tmp_path / "readme.txt").write_text("not an entry", encoding="utf-8")
    lib = library_for([tmp_path])
    assert {"flat-one", "in-folder"} <= lib.sources.keys()
    assert "ignored-folder" not in lib.entries


def test_a_user_entry_replaces_a_built_in_one_of_the_same_name(tmp_path: Path) -> None:
    built_in = library().entry("checker-tiles").path
    write(tmp_path, "checker-tiles")
    lib = library_for([tmp_path])
    assert lib.entry("checker-tiles").description.startswith("Zorblax house tile")
    assert lib.replaced["checker-tiles"] == str(built_in)
    names = [c.name for c in search("checker tiles", lib)]
    assert names.count("checker-tiles") == 1
    code, out = run("show", "checker-tiles", "--library", str(tmp_path))
    assert code == 0
    assert f"# library: {tmp_path.resolve()}, replacing {built_in}" in out
    code, out = run("list", "--category", "tiles", "--library", str(tmp_path))
    line = next(ln for ln in out.splitlines() if " checker-tiles " in ln)
    assert str(tmp_path.resolve()) in line and "replacing" in line


def test_a_later_folder_wins_over_an_earlier_one(tmp_path: Path) -> None:
    first, second = tmp_path / "team", tmp_path / "mine"
    write(first, "zorblax-tile")
    write(second, "zorblax-tile", entry_text(description="Zorblax mine"))
    lib = library_for(library_dirs([second], os.pathsep.join([str(first)])))
    assert lib.entry("zorblax-tile").description == "Zorblax mine"
    assert lib.replaced["zorblax-tile"] == str(first / "zorblax-tile.mat")


def test_library_path_variable(tmp_path: Path) -> None:
    write(tmp_path, "zorblax-tile")
    assert split_path(f"{tmp_path}{os.pathsep}{os.pathsep}") == (str(tmp_path),)
    code, out = run("search", "zorblax", env={ENV: str(tmp_path)})
    assert code == 0 and "zorblax-tile" in out.splitlines()[0]
    code, out = run("search", "zorblax")
    assert "zorblax-tile" not in out


def test_author_uses_the_user_entry_and_says_where_it_came_from(tmp_path: Path) -> None:
    write(tmp_path, "zorblax-tile")
    result = author("zorblax blue tile", lib=library_for([tmp_path]))
    assert result.entry == "zorblax-tile"
    assert f"note: entry from the user library {tmp_path.resolve()}" in result.explanation


def test_an_entry_added_since_is_read(tmp_path: Path) -> None:
    assert "zorblax-tile" not in library_for([tmp_path]).entries
    write(tmp_path, "zorblax-tile")
    assert "zorblax-tile" in library_for([tmp_path]).entries


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (entry_text(category="spaceship"), "front matter key 'category'"),
        (entry_text(tags='"zorblax"'), "front matter key 'tags'"),
        ("Material(Layer(1))\n", "must start with"),
        (entry_text(program="View(0, 0, 1, 1)\nMaterial(Layer(1).basecolor(nope))\n"), "error E"),
    ],
)
def test_a_bad_user_entry_is_one_line_naming_the_file(
    tmp_path: Path, text: str, expected: str
) -> None:
    path = write(tmp_path, "broken-entry", text)
    with pytest.raises(LibraryError, match=expected):
        library_for([tmp_path])
    code, out = run("search", "zorblax", "--library", str(tmp_path))
    assert code == 1
    assert out.startswith("Error: ") and str(path) in out and expected in out
    assert len(out.strip().splitlines()) == 1 and "Traceback" not in out


def test_a_category_folder_mismatch_and_a_duplicate_are_refused(tmp_path: Path) -> None:
    write(tmp_path / "wood", "zorblax-tile")
    with pytest.raises(LibraryError, match="but the file is in wood/"):
        library_for([tmp_path])
    (tmp_path / "wood" / "zorblax-tile.mat").unlink()
    write(tmp_path, "zorblax-tile")
    write(tmp_path / "tiles", "zorblax-tile")
    with pytest.raises(LibraryError, match="entry name 'zorblax-tile' is also"):
        library_for([tmp_path])


def test_a_missing_folder_is_one_line(tmp_path: Path) -> None:
    code, out = run("list", "--library", str(tmp_path / "nowhere"))
    assert code == 1 and "does not exist" in out and len(out.strip().splitlines()) == 1


def test_symlinks_leading_out_of_the_folder_are_not_followed(tmp_path: Path) -> None:
    outside, lib_dir = tmp_path / "outside", tmp_path / "lib"
    write(outside, "escaped-entry")
    write(outside / "tiles", "escaped-in-folder")
    lib_dir.mkdir()
    (lib_dir / "escaped-entry.mat").symlink_to(outside / "escaped-entry.mat")
    (lib_dir / "tiles").symlink_to(outside / "tiles", target_is_directory=True)
    write(lib_dir, "inside-entry")
    lib = library_for([lib_dir])
    assert "inside-entry" in lib.entries
    assert "escaped-entry" not in lib.entries and "escaped-in-folder" not in lib.entries
    assert len(lib.skipped) == 2 and all("not followed" in s for s in lib.skipped)
    code, out = run("list", "--library", str(lib_dir))
    assert code == 0 and "skipped" in out and "escaped-entry " not in out


def test_check_with_a_user_library_checks_its_entries(tmp_path: Path) -> None:
    write(tmp_path, "zorblax-tile")
    code, out = run("check", "--library", str(tmp_path))
    assert code == 0, out
    assert "1 of 1 passed" in out
