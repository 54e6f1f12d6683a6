"""Preview shading against the reference's previews, plus tiling and contact sheets."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps, View
from matloom.render.preview import DEFAULT_LIGHT, Light, available_shaders, shade, tile_image
from matloom.render.sheet import contact_sheet, save_png

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
MANIFEST = json.loads((PARITY / "manifest.json").read_text())["programs"]

#: The reference blends the maps in float64 and our maps are float32, and our albedo/emissive
#: sRGB pow runs in float32 (numpy SIMD, whose last ulp may differ between CPUs). Either can
#: move a value sitting within ~1e-6 of a rounding boundary by one level: allow that for at
#: most 0.05 % of the values of a preview (6 of 64x64x3), never more than one level.
MAX_LEVEL_DIFF = 1
MAX_DIFFERING_FRACTION = 5e-4


def load_maps(name: str, size: str = "64x64") -> MaterialMaps:
    entry = MANIFEST[name]
    with np.load(PARITY / f"{name}_{size}.npz") as arrays:
        return MaterialMaps.from_arrays(
            dict(arrays), view=View(*entry["view"]), n_layers=entry["n_layers"]
        )


def reference_preview(name: str) -> np.ndarray:
    with Image.open(PARITY / f"{name}_preview_64.png") as image:
        return np.asarray(image.convert("RGB"))


@pytest.mark.parametrize("backend", ["numba", "numpy"])
@pytest.mark.parametrize("name", sorted(MANIFEST))
def test_shade_reproduces_reference_preview(name: str, backend: str) -> None:
    if backend not in available_shaders():
        pytest.skip(f"{backend} is not installed")
    ours = shade(load_maps(name), backend=backend).astype(np.int16)
    ref = reference_preview(name).astype(np.int16)
    assert ours.shape == ref.shape == (64, 64, 3)
    diff = np.abs(ours - ref)
    assert diff.max() <= MAX_LEVEL_DIFF, f"{name}: off by {diff.max()} levels"
    assert np.count_nonzero(diff) <= MAX_DIFFERING_FRACTION * diff.size, (
        f"{name}: {np.count_nonzero(diff)} values differ"
    )


def test_parity_set_exercises_non_finite_inputs() -> None:
    """The NaN/inf programs are in the parity set, so the NaN -> 0 rule is checked above."""
    maps = load_maps("nan_inf_fields")
    assert np.isnan(maps.basecolor_linear).any()
    assert np.isinf(maps.emissive_linear).any()
    out = shade(maps)
    assert (out[np.isnan(maps.basecolor_linear).any(axis=-1)] == 0).all()


def random_maps(seed: int, rows: int = 48, cols: int = 40) -> MaterialMaps:
    """Every channel active, normals tilted up to ~80 degrees, some NaN / inf texels."""
    rng = np.random.default_rng(seed)
    arrays = {name: rng.random((rows, cols)).astype(np.float32) for name in ARRAY_FIELDS}
    arrays["basecolor_linear"] = rng.random((rows, cols, 3)).astype(np.float32) ** 2
    arrays["emissive_linear"] = (rng.random((rows, cols, 3)) * 4 - 1).astype(np.float32)
    normal = rng.normal(size=(rows, cols, 3))
    normal[..., 2] = np.abs(normal[..., 2]) + 0.2
    arrays["normal"] = (normal / np.linalg.norm(normal, axis=-1, keepdims=True)).astype(np.float32)
    arrays["ior"] = (rng.random((rows, cols)) * 4).astype(np.float32)  # clamped to [1, 3]
    arrays["alpha"] = (rng.random((rows, cols)) * 1.4 - 0.2).astype(np.float32)  # clamped
    for name, value in [("roughness", np.nan), ("normal", np.nan), ("emissive_linear", np.inf)]:
        arrays[name][rng.random((rows, cols)) < 0.02] = value
    return MaterialMaps.from_arrays(arrays)


@pytest.mark.parametrize("seed", range(4))
def test_backends_agree(seed: int) -> None:
    """The kernel and whole-array implementations of the same formulas give the same bytes
    (the kernel's float32 sRGB pow may move a value on a rounding boundary by one level)."""
    if "numba" not in available_shaders():
        pytest.skip("numba is not installed")
    maps = random_maps(seed)
    for light in (None, Light(200.0, 30.0)):
        fast = shade(maps, light=light, backend="numba").astype(np.int16)
        plain = shade(maps, light=light, backend="numpy").astype(np.int16)
        diff = np.abs(fast - plain)
        assert diff.max() <= 1 and np.count_nonzero(diff) <= 2


def test_preview_works_without_numba() -> None:
    """numba is an optional extra: without it, shade() falls back to the numpy path."""
    code = (
        "import sys; sys.modules['numba'] = None\n"
        "import numpy as np\n"
        "from matloom.render import preview\n"
        "assert preview.available_shaders() == ['numpy']\n"
        "from matloom.engine.maps import MaterialMaps\n"
        f"arrays = dict(np.load({str(PARITY / 'bricks_64x64.npz')!r}))\n"
        "print(preview.shade(MaterialMaps.from_arrays(arrays)).tobytes().hex())\n"
    )
    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root)}
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert bytes.fromhex(result.stdout.strip()) == reference_preview("bricks").tobytes()


def flat_maps(rows: int = 8, cols: int = 8) -> MaterialMaps:
    """An opaque, flat, mid-grey dielectric with every other channel at its default."""
    arrays = {name: np.zeros((rows, cols), np.float32) for name in ARRAY_FIELDS}
    arrays["basecolor_linear"] = np.full((rows, cols, 3), 0.2, np.float32)
    arrays["emissive_linear"] = np.zeros((rows, cols, 3), np.float32)
    arrays["normal"] = np.zeros((rows, cols, 3), np.float32)
    arrays["normal"][..., 2] = 1.0
    arrays["alpha"][:] = 1.0
    arrays["roughness"][:] = 0.5
    arrays["ior"][:] = 1.5
    arrays["ao"][:] = 1.0
    return MaterialMaps.from_arrays(arrays)


def with_array(maps: MaterialMaps, name: str, value: np.ndarray) -> MaterialMaps:
    arrays = maps.arrays()
    arrays[name] = value
    return MaterialMaps.from_arrays(arrays, view=maps.view, n_layers=maps.n_layers)


def test_non_finite_normals_shade_as_flat() -> None:
    maps = flat_maps()
    normal = maps.normal.copy()
    normal[0, 0] = (np.nan, np.inf, -np.inf)
    normal[1, 1] = (np.nan, np.nan, np.nan)
    assert np.array_equal(shade(with_array(maps, "normal", normal)), shade(maps))


def test_non_finite_values_do_not_raise_and_nan_texels_are_zero() -> None:
    maps = flat_maps()
    emissive = maps.emissive_linear.copy()
    emissive[0, 0] = np.inf  # inf / (1 + inf) is NaN in the reference
    base = maps.basecolor_linear.copy()
    base[1, 1, 0] = np.nan
    with np.errstate(all="raise"):  # nothing may raise, warnings included
        out = shade(
            with_array(with_array(maps, "emissive_linear", emissive), "basecolor_linear", base)
        )
    assert (out[0, 0] == 0).all()
    assert out[1, 1, 0] == 0 and out[1, 1, 1] == out[2, 2, 1]


def test_zero_coverage_is_half_grey() -> None:
    maps = with_array(flat_maps(), "alpha", np.zeros((8, 8), np.float32))
    assert (shade(maps) == 128).all()  # floor(255 * 0.5 + 0.5)


def test_mis_shaped_maps_are_refused() -> None:
    maps = flat_maps()
    maps.roughness = np.zeros((4, 4), np.float32)
    with pytest.raises(ValueError, match="roughness"):
        shade(maps)


def test_default_light_is_the_reference_vector() -> None:
    expected = np.array([0.5, 0.5, 1.0]) / math.sqrt(1.5)
    assert DEFAULT_LIGHT.direction() == tuple(expected)
    assert DEFAULT_LIGHT == Light()
    # azimuth 45 deg, elevation atan(sqrt(2)) = 54.7356103172 deg is the same direction
    assert np.allclose(Light(45.0, 54.7356103172).direction(), expected, rtol=0, atol=1e-9)


def test_light_direction_moves_the_lighting() -> None:
    maps = load_maps("carved_grooves")
    assert np.array_equal(shade(maps, light=DEFAULT_LIGHT), shade(maps))
    east, west = Light(0.0, 45.0), Light(180.0, 45.0)
    tilted = with_array(
        flat_maps(),
        "normal",
        np.broadcast_to(np.array([0.5, 0.0, math.sqrt(0.75)], np.float32), (8, 8, 3)).copy(),
    )
    assert shade(tilted, light=east).astype(int).sum() > shade(tilted, light=west).astype(int).sum()


@pytest.mark.parametrize("shape", [(5, 7, 3), (5, 7), (1, 1, 4)])
@pytest.mark.parametrize("n", [1, 2, 3])
def test_tile_image_repeats_the_image(shape: tuple[int, ...], n: int) -> None:
    img = np.arange(np.prod(shape), dtype=np.uint8).reshape(shape)
    tiled = tile_image(img, n)
    assert tiled.shape == (shape[0] * n, shape[1] * n, *shape[2:])
    assert np.array_equal(tiled[-shape[0] :, -shape[1] :], img)
    assert np.array_equal(tiled[: shape[0], shape[1] : 2 * shape[1]] if n > 1 else img, img)


def test_tile_image_rejects_zero() -> None:
    with pytest.raises(ValueError):
        tile_image(np.zeros((2, 2, 3), np.uint8), 0)


def test_contact_sheet_layout() -> None:
    images = [np.full((64, 32, 3), 10 * i, np.uint8) for i in range(7)]
    sheet = contact_sheet(images, [f"seed {i}" for i in range(7)], columns=3, cell=100)
    assert sheet.dtype == np.uint8 and sheet.ndim == 3 and sheet.shape[2] == 3
    assert sheet.shape[1] == 300
    label_strip = sheet.shape[0] / 3 - 100
    assert sheet.shape[0] % 3 == 0 and 8 <= label_strip <= 30
    # A 64x32 image is scaled to 100x50 and centred: cell (1, 0) holds image 3 (value 30).
    row_top = sheet.shape[0] // 3
    assert (sheet[row_top + 50, 25:75] == 30).all()
    assert (sheet[row_top + 50, :25] == 24).all()  # background around the narrow image


def test_contact_sheet_accepts_grey_and_rgba_and_checks_labels() -> None:
    images = [np.zeros((16, 16), np.uint8), np.zeros((300, 300, 4), np.uint8)]
    sheet = contact_sheet(images, ["grey", "rgba " * 30], columns=5, cell=64)
    assert sheet.shape[1] == 128
    with pytest.raises(ValueError):
        contact_sheet(images, ["only one"])
    with pytest.raises(ValueError):
        contact_sheet([np.zeros((4, 4, 3), np.float32)], ["float"])


def test_save_png_round_trips_and_leaves_no_temp_file(tmp_path: Path) -> None:
    img = (np.arange(6 * 5 * 3) % 256).astype(np.uint8).reshape(6, 5, 3)
    target = tmp_path / "out.png"
    save_png(target, img)
    save_png(str(target), img[::-1].copy())  # replacing an existing file
    with Image.open(target) as written:
        assert np.array_equal(np.asarray(written), img[::-1])
    assert [p.name for p in tmp_path.iterdir()] == ["out.png"]
