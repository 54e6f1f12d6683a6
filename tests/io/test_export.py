"""Export: byte parity with the reference PNGs, float round trips, manifest, atomicity."""

from __future__ import annotations

import dataclasses
import hashlib
import json
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.maps import MaterialMaps, View
from matloom.io import atomic, exr, png
from matloom.io.export import MAP_NAMES
from matloom.io.outdir import OutputError
from matloom.runtime.export import export_maps

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
MANIFEST = json.loads((PARITY / "manifest.json").read_text())["programs"]
REFERENCE_PNGS = (
    "basecolor", "metallic", "roughness", "sheen", "coat", "transmission", "subsurface",
    "anisotropy", "normal", "ao",
)  # fmt: skip


def _fixture_maps(name: str, size: str = "64x64") -> MaterialMaps:
    arrays = dict(np.load(PARITY / f"{name}_{size}.npz"))
    return MaterialMaps.from_arrays(arrays, View(*MANIFEST[name]["view"]))


def _encoded_floats(maps: MaterialMaps, map_name: str) -> np.ndarray:
    """The float each PNG sample encodes, in float64 (only used to find rounding boundaries)."""
    if map_name == "basecolor":
        linear = maps.basecolor_linear.astype(np.float64)
        with np.errstate(invalid="ignore"):
            srgb = np.where(
                linear <= 0.0031308, 12.92 * linear, 1.055 * np.abs(linear) ** (1 / 2.4) - 0.055
            )
        return np.concatenate([srgb, maps.alpha.astype(np.float64)[..., None]], axis=2)
    if map_name == "normal":
        return maps.normal.astype(np.float64) * 0.5 + 0.5
    return getattr(maps, map_name).astype(np.float64)


def _near_rounding_boundary(values: np.ndarray, tolerance: float = 1e-5) -> np.ndarray:
    """True where a unit-range value lies within ``tolerance`` of a k + 0.5 step of x255."""
    scaled = np.clip(values, 0, 1) * 255 + 0.5
    return np.abs(scaled - np.round(scaled)) <= tolerance * 255


@pytest.mark.parametrize("name", sorted(MANIFEST))
def test_png_bytes_match_reference(name: str, tmp_path: Path) -> None:
    maps = _fixture_maps(name)
    export_maps(maps, tmp_path / name)
    for map_name in REFERENCE_PNGS:
        want = png.read_png(PARITY / f"{name}_64x64_files" / f"{map_name}.png").astype(int)
        file = "normal_gl" if map_name == "normal" else map_name  # the convention in the name
        got = png.read_png(tmp_path / name / f"{file}.png").astype(int)
        assert got.shape == want.shape, map_name
        floats = _encoded_floats(maps, map_name).reshape(got.shape)
        compared = ~np.isnan(floats)
        diff = np.abs(got - want)
        assert diff[compared].max(initial=0) <= 1, map_name
        off_by_one = (diff == 1) & compared
        assert np.all(_near_rounding_boundary(floats[off_by_one])), map_name


def test_reference_png_set_is_what_we_compare() -> None:
    files = sorted(p.stem for p in (PARITY / "bricks_64x64_files").glob("*.png"))
    assert files == sorted(REFERENCE_PNGS)


def test_export_writes_all_maps_and_manifest(tmp_path: Path) -> None:
    maps = _fixture_maps("all_channels")
    result = export_maps(maps, tmp_path / "out", program_text="Material(Layer())")
    names = sorted(p.name for p in (tmp_path / "out").iterdir() if not p.name.startswith("."))
    expected = sorted(
        [f"{n}.png" for n in REFERENCE_PNGS if n != "normal"]
        + ["normal_gl.png", "ior.exr", "emissive.exr", "height.exr"]
        + ["anisotropy_angle.png", "anisotropy_angle.exr"]  # written on every render
    )
    assert names == sorted(expected + ["material.json"])
    manifest = json.loads(result.manifest_path.read_text())
    assert manifest == result.manifest
    assert sorted(manifest["files"]) == expected  # every file but the manifest, with its SHA-256
    for name, digest in manifest["files"].items():
        assert hashlib.sha256((tmp_path / "out" / name).read_bytes()).hexdigest() == digest
    assert [m["name"] for m in manifest["maps"]] == list(MAP_NAMES)
    assert len(MAP_NAMES) == 14
    assert manifest["width"] == 64 and manifest["height"] == 64
    assert manifest["program_sha256"] == hashlib.sha256(b"Material(Layer())").hexdigest()
    by_name = {m["name"]: m for m in manifest["maps"]}
    height_range = by_name["height"]["value_range"]
    assert height_range["min"] == pytest.approx(float(maps.height.min()))
    assert height_range["max"] == pytest.approx(float(maps.height.max()))
    assert by_name["basecolor"]["colour_space"].startswith("sRGB")
    assert set(result.files) == set(MAP_NAMES) | {"manifest", "anisotropy_angle_float"}


def test_float_maps_round_trip_exactly(tmp_path: Path) -> None:
    maps = _fixture_maps("nan_inf_fields")
    export_maps(maps, tmp_path / "out")
    np.testing.assert_array_equal(exr.read_exr(tmp_path / "out" / "height.exr"), maps.height)
    np.testing.assert_array_equal(exr.read_exr(tmp_path / "out" / "ior.exr"), maps.ior)
    emissive = exr.read_exr(tmp_path / "out" / "emissive.exr")
    np.testing.assert_array_equal(emissive, maps.emissive_linear)  # +inf kept
    assert np.isposinf(emissive).sum() == 6144


def test_exr_round_trip_with_nan(tmp_path: Path) -> None:
    rng = np.random.default_rng(1)
    grey = rng.standard_normal((13, 17)).astype(np.float32) * 1e6
    grey[0, 0], grey[1, 1], grey[2, 2] = np.nan, np.inf, -np.inf
    exr.write_exr(tmp_path / "g.exr", grey)
    np.testing.assert_array_equal(exr.read_exr(tmp_path / "g.exr"), grey)
    rgb = rng.random((5, 4, 3)).astype(np.float32)
    exr.write_exr(tmp_path / "c.exr", rgb)
    np.testing.assert_array_equal(exr.read_exr(tmp_path / "c.exr"), rgb)
    with pytest.raises(ValueError):
        exr.write_exr(tmp_path / "bad.exr", np.zeros((2, 2, 2), np.float32))


def test_png16_height(tmp_path: Path) -> None:
    maps = _fixture_maps("carved_grooves")
    result = export_maps(maps, tmp_path / "out", float_format="png16")
    info = result.manifest["height_png16"]
    assert info["units"] == "coordinate units"
    assert (tmp_path / "out" / "height.exr").exists()
    assert (tmp_path / "out" / "ior.exr").exists() and (tmp_path / "out" / "emissive.exr").exists()
    samples = png.read_png(tmp_path / "out" / "height16.png")
    assert samples.dtype == np.uint16 and samples.shape == maps.height.shape
    assert samples.min() == 0 and samples.max() == 65535
    decoded = info["min"] + samples / 65535 * (info["max"] - info["min"])
    step = (info["max"] - info["min"]) / 65535
    np.testing.assert_allclose(decoded, maps.height, atol=step / 2 + 1e-12)
    assert info["min"] == pytest.approx(float(maps.height.min()))


def test_png16_flat_height(tmp_path: Path) -> None:
    maps = dataclasses.replace(_fixture_maps("bricks"), height=np.full((64, 64), 0.25, np.float32))
    result = export_maps(maps, tmp_path / "o", float_format="png16")
    assert np.all(png.read_png(tmp_path / "o" / "height16.png") == 0)
    assert result.manifest["height_png16"]["min"] == result.manifest["height_png16"]["max"] == 0.25


def test_quantisation_rules() -> None:
    values = np.array([np.nan, np.inf, -np.inf, -0.5, 0.0, 0.5 / 255, 0.999, 1.0, 7.0])
    np.testing.assert_array_equal(png.quantize_unit8(values), [0, 255, 0, 0, 0, 1, 255, 255, 255])


def test_non_finite_counts_reported(tmp_path: Path) -> None:
    maps = _fixture_maps("nan_inf_fields")
    result = export_maps(maps, tmp_path / "out")
    assert result.nonfinite_counts == {"basecolor": 2936, "roughness": 2936, "emissive": 6144}
    stored = json.loads(result.manifest_path.read_text())
    assert stored["nonfinite_values"] == result.nonfinite_counts
    roughness = png.read_png(tmp_path / "out" / "roughness.png")
    assert np.all(roughness[np.isnan(maps.roughness)] == 0)


def test_maps_subset(tmp_path: Path) -> None:
    result = export_maps(
        _fixture_maps("bricks"), tmp_path / "o", maps_subset=["normal", "basecolor"]
    )
    assert sorted(p.name for p in (tmp_path / "o").iterdir() if p.name[0] != ".") == [
        "basecolor.png", "material.json", "normal_gl.png",
    ]  # fmt: skip
    assert [m["name"] for m in result.manifest["maps"]] == ["basecolor", "normal"]


def test_unknown_map_name_writes_nothing(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="bogus"):
        export_maps(_fixture_maps("bricks"), tmp_path / "o", maps_subset=["normal", "bogus"])
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError):
        export_maps(_fixture_maps("bricks"), tmp_path / "o", float_format="hdr")
    assert list(tmp_path.iterdir()) == []


def _failing_writer(*args: object, **kwargs: object) -> None:
    raise OSError("disk full (injected)")


def test_failure_mid_export_leaves_an_empty_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(exr, "write_exr", _failing_writer)  # PNGs before ior are already written
    with pytest.raises(OutputError, match="injected"):
        export_maps(_fixture_maps("bricks"), tmp_path / "out")
    assert list((tmp_path / "out").iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_failure_keeps_previous_export(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    export_maps(_fixture_maps("bricks"), out)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    monkeypatch.setattr(png, "write_grey8", _failing_writer)
    with pytest.raises(OutputError, match="injected"):
        export_maps(_fixture_maps("tile"), out)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_successful_export_replaces_its_own_previous_files_only(tmp_path: Path) -> None:
    out = tmp_path / "out"
    export_maps(_fixture_maps("bricks"), out)
    (out / "notes.txt").write_text("the user's")
    export_maps(_fixture_maps("tile"), out, maps_subset=["ao"])
    names = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert names == ["ao.png", "material.json", "notes.txt"]
    assert (out / "notes.txt").read_text() == "the user's"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_atomic_write_bytes(tmp_path: Path) -> None:
    target = tmp_path / "a.bin"
    atomic.atomic_write_bytes(target, b"one")
    atomic.atomic_write_bytes(target, b"two")
    assert target.read_bytes() == b"two"
    assert [p.name for p in tmp_path.iterdir()] == ["a.bin"]


def test_export_refuses_a_file_as_folder(tmp_path: Path) -> None:
    target = tmp_path / "file"
    target.write_text("keep")
    with pytest.raises(OutputError, match="not a folder"):
        export_maps(_fixture_maps("bricks"), target)
    assert target.read_text() == "keep"
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


def test_extra_meta_and_version(tmp_path: Path) -> None:
    result = export_maps(
        _fixture_maps("bricks"), tmp_path / "o", engine_version="9.9", extra_meta={"seed": 3}
    )
    assert result.manifest["engine_version"] == "9.9"
    assert result.manifest["extra"] == {"seed": 3}
