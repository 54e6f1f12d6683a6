"""`matloom blender PROGRAM --unit-m` behaves as `render --unit-m`: a size the presets can store,
and a note when it replaces the program's own unit_m (no Blender needed: the maps are rendered
by MatLoom before Blender starts)."""

from __future__ import annotations

from pathlib import Path

import pytest

from matloom.blender.job import BlenderJobError, load_source

COBBLE = "View(0, 0, 4, 4, unit_m=0.05)\nMaterial(Layer(1).basecolor(90, 90, 90))\n"


def test_a_replaced_unit_m_is_said(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "cobble.mat"
    program.write_text(COBBLE)
    source = load_source(str(program), size=8, unit_m=1.5)
    try:
        err = capsys.readouterr().err
        assert "--unit-m 1.5 replaces the program's View unit_m=0.05" in err
        assert "6 m wide instead of 0.2 m" in err
    finally:
        source.cleanup()


def test_the_same_unit_m_says_nothing(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "cobble.mat"
    program.write_text(COBBLE)
    source = load_source(str(program), size=8, unit_m=0.05)
    source.cleanup()
    assert "replaces" not in capsys.readouterr().err


def test_a_size_no_preset_can_store_is_one_error(tmp_path: Path) -> None:
    program = tmp_path / "cobble.mat"
    program.write_text(COBBLE)
    with pytest.raises(BlenderJobError, match="physical size"):
        load_source(str(program), size=8, unit_m=1e308)
