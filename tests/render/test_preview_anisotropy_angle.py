"""The quick preview rotates the anisotropic highlight by ``anisotropy_angle``; previews without
the channel (angle 0 everywhere) keep every byte."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import matloom
from matloom.engine.maps import MaterialMaps, View
from matloom.render import preview
from matloom.render.preview import ShadeParams, anisotropy_direction_factor, shade

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
MANIFEST = json.loads((PARITY / "manifest.json").read_text())["programs"]
SHADERS = preview.available_shaders()

#: Brushed metal; ANGLE is replaced by the angle expression.
BRUSHED = (
    "Material(\n  Layer(1)\n    .basecolor(190, 190, 200)\n    .metallic(1)\n"
    "    .roughness(0.25)\n    .anisotropy(0.9)\n    .anisotropy_angle(ANGLE)\n)"
)


def _fixture_maps(name: str) -> MaterialMaps:
    with np.load(PARITY / f"{name}_64x64.npz") as arrays:
        assert "anisotropy_angle" not in arrays.files  # made before the channel existed
        return MaterialMaps.from_arrays(dict(arrays), view=View(*MANIFEST[name]["view"]))


def _reference_preview(name: str) -> np.ndarray:
    with Image.open(PARITY / f"{name}_preview_64.png") as image:
        return np.asarray(image.convert("RGB"))


def _with_angle(maps: MaterialMaps, angle: float | np.ndarray) -> MaterialMaps:
    arrays = maps.arrays()
    arrays["anisotropy_angle"] = np.broadcast_to(np.float32(angle), maps.alpha.shape).copy()
    return MaterialMaps.from_arrays(arrays, view=maps.view, n_layers=maps.n_layers)


@pytest.mark.parametrize("backend", SHADERS)
@pytest.mark.parametrize("name", sorted(MANIFEST))
def test_previews_without_the_channel_keep_every_byte(
    name: str, backend: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The 30 reference previews, byte for byte, with the angle map absent or explicitly 0;
    the rotation is not even computed then."""

    def never(*args: object) -> np.ndarray:
        raise AssertionError("the direction factor was computed for angle 0")

    maps = _fixture_maps(name)
    want = _reference_preview(name)
    monkeypatch.setattr(preview, "anisotropy_direction_factor", never)
    assert np.array_equal(shade(maps, backend=backend), want)
    assert np.array_equal(shade(_with_angle(maps, 0.0), backend=backend), want)
    assert np.array_equal(shade(_with_angle(maps, -0.0), backend=backend), want)


def test_direction_factor() -> None:
    half = ShadeParams.of().half
    angles = np.array([0.0, 45.0, 135.0, 225.0, -45.0, 90.0])
    full = anisotropy_direction_factor(angles, np.ones(6), half)
    assert full[0] == 1.0  # exactly: the reference's exponent
    # the default half vector lies along 45 degrees; the stretch is across the brushing angle,
    # along it for 135 and -45: k = 1 / 5, factors 2k / (1 + k), 2 / (1 + k)
    np.testing.assert_allclose(full[1:5], [5 / 3, 1 / 3, 5 / 3, 1 / 3], rtol=1e-12)
    assert 1 / 3 < full[5] < 5 / 3
    # no anisotropy, or a head-on half vector: the angle has no effect, exactly
    assert np.all(anisotropy_direction_factor(angles, np.zeros(6), half) == 1.0)
    assert np.all(anisotropy_direction_factor(angles, np.ones(6), np.array([0, 0, 1.0])) == 1.0)
    # axial: angle and angle + 180 agree; NaN propagates like every NaN map
    np.testing.assert_allclose(
        anisotropy_direction_factor(angles + 180, np.full(6, 0.5), half),
        anisotropy_direction_factor(angles, np.full(6, 0.5), half),
        rtol=1e-12,
    )
    assert np.isnan(anisotropy_direction_factor(np.array([np.nan]), np.ones(1), half)[0])


def _brushed(angle: str, size: int = 24) -> MaterialMaps:
    return matloom.evaluate(BRUSHED.replace("ANGLE", angle), size, size)


@pytest.mark.parametrize("backend", SHADERS)
def test_angle_rotates_the_highlight(backend: str) -> None:
    images = {a: shade(_brushed(a), backend=backend).astype(int) for a in ("0", "45", "135")}
    # the default light's half vector points along 45 degrees: brushing across it (135)
    # stretches the highlight along it, as real grooves do, widening the highlight seen head-on
    # (brighter); brushing along it (45) stretches it across, narrowing it (darker)
    assert images["135"].sum() > images["0"].sum() > images["45"].sum()
    axial = shade(_brushed("315"), backend=backend).astype(int)
    assert np.abs(axial - images["135"]).max() <= 1
    # without anisotropy the angle changes nothing, byte for byte
    plain = BRUSHED.replace(".anisotropy(0.9)", ".anisotropy(0)")
    maps0 = matloom.evaluate(plain.replace("ANGLE", "0"), 24, 24)
    maps1 = matloom.evaluate(plain.replace("ANGLE", "X() * 300 + 17"), 24, 24)
    assert maps1.anisotropy_angle.any()
    assert np.array_equal(shade(maps0, backend=backend), shade(maps1, backend=backend))


def test_shaders_agree_with_a_varying_angle() -> None:
    if "numba" not in SHADERS:
        pytest.skip("numba is not installed")
    rng = np.random.default_rng(3)
    maps = _with_angle(_fixture_maps("all_channels"), rng.random((64, 64)) * 720 - 360)
    arrays = maps.arrays()
    arrays["anisotropy"] = rng.random((64, 64)).astype(np.float32)
    maps = MaterialMaps.from_arrays(arrays, view=maps.view)
    fast = shade(maps, backend="numba").astype(np.int16)
    plain = shade(maps, backend="numpy").astype(np.int16)
    assert not np.array_equal(plain, shade(_with_angle(maps, 0.0), backend="numpy"))
    diff = np.abs(fast - plain)
    assert diff.max() <= 1 and np.count_nonzero(diff) <= 2


def test_sweep_preview_follows_the_angle() -> None:
    """The sweep's float32 shading kernel rotates the highlight like matloom.preview."""
    pytest.importorskip("numba")
    from matloom.engine.schedules.sweep import run_sweep

    noisy = BRUSHED.replace(
        ".roughness(0.25)",
        ".roughness(0.2 + 0.2 * fBm(octaves=2, base_freq=3, to_01=True, seed=4))",
    )
    originals = {}
    for angle in ("0", "45", "X() * 360 - 30"):
        text = noisy.replace("ANGLE", angle)
        result = run_sweep(text, variants=2, shading=ShadeParams.of(), size=32, jobs=1, keep=3)
        originals[angle] = dict(result.top_images)[0].astype(np.int16)
        exact = matloom.preview(text, 32).astype(np.int16)
        diff = np.abs(originals[angle] - exact)
        assert diff.max() <= 1 and np.count_nonzero(diff) <= diff.size // 100, angle
    assert originals["45"].sum() < originals["0"].sum()  # brushing along the half vector
    assert not math.isclose(originals["X() * 360 - 30"].sum(), originals["0"].sum())
