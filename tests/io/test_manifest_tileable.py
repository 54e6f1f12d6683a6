"""The manifest's ``tileable`` is true only when every map repeats seamlessly: each exported
map's seam ratio within the bound of docs/tileable.md; otherwise false, with the reason."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

import matloom
from matloom.cli.main import cli
from matloom.io.export import SEAM_BOUND, write_maps
from matloom.library import author

#: repeats with the View: every map's seam ratio is small
TILES = """View(0, 0, 2, 1, tileable=True)
Material(Layer(1)
  .roughness(fBm(octaves=5, base_freq=3, to_01=True, seed=2))
  .height(fBm(octaves=5, base_freq=3, seed=2) * 0.02 + Worley(base_freq=5, seed=1) * 0.01))"""
#: a ramp in X() does not repeat (W010): the height, normal and AO have a seam
RAMP = """View(0, 0, 1, 1)
Material(Layer(1).basecolor(120, 110, 100).height(X() * 0.05 + fBm(seed=3) * 0.002))"""


def _render(tmp_path: Path, text: str, *extra: str, size: int = 96) -> dict:
    src = tmp_path / "m.mat"
    src.write_text(text + "\n", encoding="utf-8")
    out = tmp_path / "out"
    args = ["render", str(src), "-o", str(out), "--size", str(size), "--backend", "numpy", *extra]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    return json.loads((out / "material.json").read_text(encoding="utf-8"))


def test_a_map_with_a_seam_makes_the_manifest_say_not_tileable(tmp_path: Path) -> None:
    manifest = _render(tmp_path, RAMP, "--tileable")
    assert manifest["seam_ratio"]["height"] > SEAM_BOUND
    assert manifest["tileable"] is False
    assert "height" in manifest["tileable_reason"]
    assert f"over {SEAM_BOUND:g}" in manifest["tileable_reason"]


def test_a_seamless_render_is_tileable_with_no_reason(tmp_path: Path) -> None:
    manifest = _render(tmp_path, TILES)
    assert all(r <= SEAM_BOUND for r in manifest["seam_ratio"].values())
    assert manifest["tileable"] is True
    assert "tileable_reason" not in manifest


@pytest.mark.parametrize(
    ("prompt", "entry"),
    [("corrugated metal", "corrugated-metal"), ("herringbone parquet", "wood-herringbone")],
)
def test_a_library_entry_forced_tileable_is_not_claimed_to_tile(
    tmp_path: Path, prompt: str, entry: str
) -> None:
    # both draw from X() non-periodically (W010): the offline author leaves them plain, and a
    # forced --tileable render says they do not tile, naming the maps with the seam
    r = author(prompt)
    assert r.entry == entry and r.tileable is False
    assert "tileable=True" not in r.program
    manifest = _render(tmp_path, r.program, "--tileable", size=256)
    assert manifest["tileable"] is False
    over = {k for k, v in manifest["seam_ratio"].items() if v > SEAM_BOUND}
    assert over and all(name in manifest["tileable_reason"] for name in over)


def test_write_maps_applies_the_same_rule(tmp_path: Path) -> None:
    maps = matloom.evaluate(RAMP, 64, 64, tileable=True, backend="numpy")
    result = write_maps(maps, tmp_path)
    assert result.manifest["tileable"] is False and "tileable_reason" in result.manifest
