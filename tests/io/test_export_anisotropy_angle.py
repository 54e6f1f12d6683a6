"""Export of the anisotropy direction: an 8-bit axial PNG, the degrees as float32 EXR, and its
manifest entry; written on every render."""

from __future__ import annotations

import dataclasses
import hashlib
import json
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.evaluate import evaluate
from matloom.engine.maps import MaterialMaps
from matloom.io import exr, png
from matloom.io.export import MAP_NAMES, periodic_unit, planned_files
from matloom.runtime.export import export_maps

ANGLES = np.array(
    [[0.0, 45.0, 90.0, 135.0], [180.0, -90.0, 540.0, 359.0], [np.nan, np.inf, -30.0, 1e-3]],
    np.float32,
)
#: Hand-worked samples of ANGLES: round((angle mod 180) / 180 * 255) (half up); NaN and inf
#: (whose remainder is NaN) -> 0; 359 -> 179 -> 253.58 -> 254; -30 -> 150 -> 212.5 -> 213.
EXPECTED_PNG = np.array([[0, 64, 128, 191], [0, 128, 0, 254], [0, 0, 213, 0]], np.uint8)

PROGRAM = (
    "Material(\n  Layer(1)\n    .metallic(1)\n    .anisotropy(0.8)\n"
    "    .anisotropy_angle(X() * 360 - 45)\n)"
)


def _maps_with(angles: np.ndarray) -> MaterialMaps:
    maps = evaluate("Material(Layer(1).anisotropy(0.5))", angles.shape[1], angles.shape[0])
    return dataclasses.replace(maps, anisotropy_angle=angles)


def test_png_holds_the_axial_angle_and_exr_the_degrees(tmp_path: Path) -> None:
    result = export_maps(_maps_with(ANGLES), tmp_path / "out")
    got = png.read_png(tmp_path / "out" / "anisotropy_angle.png")
    assert got.dtype == np.uint8 and got.shape == ANGLES.shape
    np.testing.assert_array_equal(got, EXPECTED_PNG)
    np.testing.assert_array_equal(got, png.quantize_unit8(periodic_unit(ANGLES, 180.0)))
    floats = exr.read_exr(tmp_path / "out" / "anisotropy_angle.exr")
    np.testing.assert_array_equal(floats, ANGLES)  # unreduced degrees, NaN and inf kept
    assert result.files["anisotropy_angle"].name == "anisotropy_angle.png"
    assert result.files["anisotropy_angle_float"].name == "anisotropy_angle.exr"
    assert result.nonfinite_counts["anisotropy_angle"] == 2


def test_manifest_entry(tmp_path: Path) -> None:
    result = export_maps(_maps_with(ANGLES), tmp_path / "out")
    manifest = json.loads(result.manifest_path.read_text())
    entry = {m["name"]: m for m in manifest["maps"]}["anisotropy_angle"]
    assert entry["file"] == "anisotropy_angle.png" and entry["encoding"] == "png8-grey"
    assert entry["float_file"] == "anisotropy_angle.exr"
    assert entry["float_encoding"] == "exr-float32"
    assert entry["colour_space"] == "linear (non-color)"
    assert "value / 255 * 180" in entry["decode"] and "axial" in entry["decode"]
    assert "counter-clockwise from +x" in entry["meaning"]
    assert entry["value_range"] == {"min": -90.0, "max": 540.0}  # the degrees, finite ones
    assert entry["nonfinite_values"] == 2
    assert manifest["nonfinite_values"]["anisotropy_angle"] == 2
    for name in ("anisotropy_angle.png", "anisotropy_angle.exr"):
        digest = hashlib.sha256((tmp_path / "out" / name).read_bytes()).hexdigest()
        assert manifest["files"][name] == digest
    aniso = {m["name"]: m for m in manifest["maps"]}["anisotropy"]
    assert "anisotropy_angle" in aniso["meaning"]


def test_written_on_every_render_even_unused(tmp_path: Path) -> None:
    """Like every other map, whether or not the program writes the channel (documented)."""
    maps = evaluate("Material(Layer(1).roughness(0.5))", 8, 8)
    export_maps(maps, tmp_path / "out")
    assert not png.read_png(tmp_path / "out" / "anisotropy_angle.png").any()
    assert not exr.read_exr(tmp_path / "out" / "anisotropy_angle.exr").any()
    assert "anisotropy_angle" in MAP_NAMES
    planned = planned_files(None, "png")
    assert "anisotropy_angle.png" in planned and "anisotropy_angle.exr" in planned
    written = {p.name for p in (tmp_path / "out").iterdir() if not p.name.startswith(".")}
    assert written == set(planned) - {"material.mat"}


@pytest.mark.parametrize("float_format", ["png", "png16"])
def test_maps_subset_selects_both_files(tmp_path: Path, float_format: str) -> None:
    maps = evaluate(PROGRAM, 16, 8)
    export_maps(maps, tmp_path / "a", maps_subset=["anisotropy_angle"], float_format=float_format)
    names = sorted(p.name for p in (tmp_path / "a").iterdir() if not p.name.startswith("."))
    assert names == ["anisotropy_angle.exr", "anisotropy_angle.png", "material.json"]
    assert planned_files(["anisotropy_angle"], float_format) == [
        "anisotropy_angle.png",
        "anisotropy_angle.exr",
        "material.json",
        "material.mat",
    ]
    export_maps(maps, tmp_path / "b", maps_subset=["anisotropy"])
    assert not list((tmp_path / "b").glob("anisotropy_angle*"))


def test_evaluated_angles_round_trip(tmp_path: Path) -> None:
    maps = evaluate(PROGRAM, 32, 4)
    export_maps(maps, tmp_path / "out")
    floats = exr.read_exr(tmp_path / "out" / "anisotropy_angle.exr")
    np.testing.assert_array_equal(floats, maps.anisotropy_angle)
    decoded = png.read_png(tmp_path / "out" / "anisotropy_angle.png") / 255 * 180
    error = np.abs(decoded - np.mod(maps.anisotropy_angle.astype(np.float64), 180))
    axial_error = np.minimum(error, 180 - error)  # 180 and 0 are the same direction
    assert axial_error.max() <= 180 / 255 / 2 + 1e-9
