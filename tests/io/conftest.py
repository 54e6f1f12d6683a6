"""Fixtures of the preset tests: programs and a small render helper (64x64 renders)."""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache
from pathlib import Path
from typing import Any

import pytest

import matloom
from matloom.engine.maps import MaterialMaps
from matloom.io.export import ExportResult
from matloom.runtime.export import export_maps

#: Every channel varies (extensions, ior texture, anisotropy texture, emissive strength > 1).
FULL = """View(0, 0, 2, 2)
Define(n, fBm(octaves=3, base_freq=3, to_01=True, seed=1))
Define(w, Worley(base_freq=4, to_01=True, seed=2))
Material(
  Layer(0.6 + 0.4 * n).basecolor(200, 120, 80).roughness(n).metallic(w).coat(n).sheen(w)
    .transmission(n * 0.5).ior(1.3 + n).anisotropy(w).anisotropy_angle(n * 90)
    .emissive(255, 100, 50, n * 3).subsurface(n).height(n * 0.1),
  Layer(w * 0.5).basecolor(20, 20, 200)
)
"""
#: Only base colour, roughness and height: no extension, constant metallic.
PLAIN = """View(0, 0, 10, 10)
Define(brick, Bricks())
Material(
  Layer(1).basecolor(255, 0, 0).roughness(0.5).height(0),
  Layer(brick).basecolor(127, 127, 127).roughness(0.8).height(brick * 0.5)
)
"""
#: Every map constant.
FLAT = "Material(Layer(1).basecolor(40, 80, 120).roughness(0.25).metallic(1))"


PROGRAMS = {"full": FULL, "plain": PLAIN, "flat": FLAT}


@pytest.fixture(scope="session")
def programs() -> dict[str, str]:
    return PROGRAMS


@pytest.fixture(scope="session")
def preset_maps() -> Callable[[str], MaterialMaps]:
    """The 64x64 maps of a program of :data:`PROGRAMS` (evaluated once per session)."""
    return lru_cache(maxsize=None)(lambda name: matloom.evaluate(PROGRAMS[name], 64, 64))


@pytest.fixture
def render_presets(
    tmp_path: Path, preset_maps: Callable[[str], MaterialMaps]
) -> Callable[..., tuple[MaterialMaps, ExportResult]]:
    """render_presets(name, **export_options) -> (maps, result), written into tmp_path/name."""

    def run(name: str, **kwargs: Any) -> tuple[MaterialMaps, ExportResult]:
        maps = preset_maps(name)
        kwargs.setdefault("name", name)
        return maps, export_maps(maps, tmp_path / name, program_text=PROGRAMS[name], **kwargs)

    return run
