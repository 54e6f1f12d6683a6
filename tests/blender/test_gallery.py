"""docs/gallery/blender/: 12 programs that check clean, each rendered flat and staged by the
command, and all shown in the gallery's README."""

from __future__ import annotations

from pathlib import Path

import pytest

import matloom
from matloom.io.png import read_png, written_by_matloom

GALLERY = Path(__file__).resolve().parents[2] / "docs" / "gallery" / "blender"
PROGRAMS = sorted((GALLERY / "programs").glob("*.mat"))
REQUIRED = {"glass", "brushed_metal", "velvet", "tiles"}


def test_twelve_programs_including_the_required_ones() -> None:
    names = {p.stem for p in PROGRAMS}
    assert len(names) == 12 and REQUIRED <= names


@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.stem)
def test_program_is_clean_and_canonical(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    assert [d.format() for d in matloom.check(text)] == []
    assert matloom.format(text) + "\n" == text  # what `matloom fmt --write` leaves


@pytest.mark.parametrize("path", PROGRAMS, ids=lambda p: p.stem)
def test_renders_exist_and_are_shown(path: Path) -> None:
    readme = (GALLERY / "README.md").read_text(encoding="utf-8")
    for layout in ("flat", "staged"):
        image = GALLERY / "renders" / path.stem / f"{layout}.png"
        assert written_by_matloom(image)  # written by `matloom blender`
        assert read_png(image).shape == (384, 384, 4)
        assert f"(renders/{path.stem}/{layout}.png)" in readme
    assert f"(programs/{path.stem}.mat)" in readme


def test_gallery_stays_small() -> None:
    total = sum(p.stat().st_size for p in GALLERY.rglob("*") if p.is_file())
    assert total < 8 * 1024 * 1024
