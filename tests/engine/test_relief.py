"""Relief maps: parity with the reference fixtures, plus analytic and property checks."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from matloom.engine import relief
from matloom.engine.maps import View

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
MANIFEST = json.loads((PARITY / "manifest.json").read_text())["programs"]
CASES = [(name, size) for name in sorted(MANIFEST) for size in ("64x64", "48x32")]


def _fixture(name: str, size: str) -> tuple[dict[str, np.ndarray], float, float]:
    arrays = dict(np.load(PARITY / f"{name}_{size}.npz"))
    height, width = arrays["height"].shape
    dx, dy = View(*MANIFEST[name]["view"]).texel_size(width, height)
    return arrays, dx, dy


@pytest.mark.parametrize(("name", "size"), CASES)
def test_normals_match_reference(name: str, size: str) -> None:
    arrays, dx, dy = _fixture(name, size)
    got = relief.normals(arrays["height"], dx, dy)
    assert got.dtype == np.float32
    assert got.shape == arrays["normal"].shape
    np.testing.assert_allclose(got, arrays["normal"], atol=1e-5, rtol=0)


@pytest.mark.parametrize(("name", "size"), CASES)
def test_ambient_occlusion_matches_reference(name: str, size: str) -> None:
    arrays, dx, _ = _fixture(name, size)
    got = relief.ambient_occlusion(arrays["height"], dx)
    assert got.dtype == np.float32
    np.testing.assert_allclose(got, arrays["ao"], atol=1e-5, rtol=0)


def test_fixtures_have_relief() -> None:
    """Guard: the parity set must contain non-flat normals and some occlusion."""
    arrays, _, _ = _fixture("carved_grooves", "64x64")
    assert np.ptp(arrays["normal"][..., 0]) > 0.1
    assert arrays["ao"].min() < 0.95


def test_normals_of_a_tilted_plane() -> None:
    """height = a*X + b*Y has the exact normal (-a, -b, 1)/|.| everywhere (borders included)."""
    width, height, a, b = 9, 7, 0.5, -0.25
    dx, dy = 0.5, 0.25
    x = (np.arange(width) + 0.5) * dx
    y = (height - 1 - np.arange(height) + 0.5) * dy  # row 0 is the largest Y
    h = (a * x[None, :] + b * y[:, None]).astype(np.float32)
    got = relief.normals(h, dx, dy)
    expected = np.array([-a, -b, 1.0]) / np.sqrt(a * a + b * b + 1)
    np.testing.assert_allclose(got, np.broadcast_to(expected, got.shape), atol=1e-6)


@pytest.mark.parametrize("shape", [(1, 5), (5, 1), (1, 1), (2, 2)])
def test_normals_degenerate_axes(shape: tuple[int, int]) -> None:
    h = np.arange(np.prod(shape), dtype=np.float32).reshape(shape)
    got = relief.normals(h, 1.0, 1.0)
    assert got.shape == shape + (3,)
    assert np.all(np.isfinite(got))
    if shape[1] == 1:
        assert np.all(got[..., 0] == 0)
    if shape[0] == 1:
        assert np.all(got[..., 1] == 0)


def test_zero_spacing_does_not_crash() -> None:
    h = np.array([[0.0, 1.0], [0.0, 1.0]], dtype=np.float32)
    got = relief.normals(h, 0.0, 1.0)
    assert got.shape == (2, 2, 3)


def test_flat_height_is_unoccluded() -> None:
    h = np.full((20, 30), 0.3, dtype=np.float32)
    for radius in (0.0, 0.5, 2.5, 8.0, 100.0):
        np.testing.assert_array_equal(relief.ambient_occlusion(h, 0.1, radius, radius), 1.0)


def test_pit_is_occluded_and_peak_is_not() -> None:
    h = np.zeros((21, 21), dtype=np.float32)
    h[10, 10] = -1.0
    ao_pit = relief.ambient_occlusion(h, 1.0, 3, 3)
    assert ao_pit[10, 10] < 1.0
    ao_peak = relief.ambient_occlusion(-h, 1.0, 3, 3)
    assert ao_peak[10, 10] == 1.0


def test_fractional_radius_is_continuous_and_between_integers() -> None:
    rng = np.random.default_rng(3)
    h = rng.random((24, 31)).astype(np.float32)
    at2 = relief.box_mean(h, 2.0, 2.0)
    just_above = relief.box_mean(h, 2.0 + 1e-7, 2.0 + 1e-7)
    np.testing.assert_allclose(just_above, at2, atol=1e-5)
    at3 = relief.box_mean(h, 3.0, 3.0)
    almost3 = relief.box_mean(h, 3.0 - 1e-7, 3.0 - 1e-7)
    np.testing.assert_allclose(almost3, at3, atol=1e-5)


def test_fractional_weights_on_an_impulse() -> None:
    """R = 1.5: taps -1..1 weigh 1, taps +-2 weigh 0.5, divided by 2R + 1 = 4."""
    row = np.zeros((1, 9), dtype=np.float32)
    row[0, 4] = 4.0
    got = relief.box_mean(row, 1.5, 0.0)[0]
    np.testing.assert_allclose(got, [0, 0, 0.5, 1, 1, 1, 0.5, 0, 0], atol=1e-7)


@pytest.mark.parametrize("radius", [1.0, 2.5, 8.0, 8.7, 20.0, 40.0])
def test_prefix_sum_path_agrees_with_tap_sum(
    radius: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(7)
    h = (rng.random((50, 37)) * 3 - 1).astype(np.float32)
    taps = relief.box_mean(h, radius, radius / 2)
    monkeypatch.setattr(relief, "EXACT_TAP_LIMIT", 0)
    prefix = relief.box_mean(h, radius, radius / 2)
    np.testing.assert_allclose(prefix, taps, atol=1e-6)


def test_radius_larger_than_image() -> None:
    rng = np.random.default_rng(11)
    h = rng.random((5, 6)).astype(np.float32)
    got = relief.box_mean(h, 30.0, 30.0)
    assert np.all(np.isfinite(got))
    assert h.min() <= got.min() and got.max() <= h.max()


def test_ao_radius_from_units() -> None:
    assert relief.ao_radius_from_units(0.125, 1 / 64, 1 / 32) == (8.0, 4.0)
    with pytest.raises(ValueError):
        relief.ao_radius_from_units(0.1, 0.0, 1.0)
    with pytest.raises(ValueError):
        relief.ao_radius_from_units(-1.0, 0.1, 0.1)


def test_negative_radius_rejected() -> None:
    with pytest.raises(ValueError):
        relief.box_mean(np.zeros((3, 3), np.float32), -1.0, 1.0)
