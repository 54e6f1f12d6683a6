"""Visible statistics (issue 15 item 2) on synthetic maps of known period and orientation.

Orientation convention (matloom.render.spectrum): the direction in which the value changes,
degrees counter-clockwise from +X with +Y up (row 0 is the top row): 0 = vertical stripes,
90 = horizontal bands.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from matloom.engine.colour import srgb_to_linear
from matloom.engine.evaluate import evaluate
from matloom.engine.limits import LimitError
from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps, View
from matloom.render import api, spectral_peaks, spectrum
from matloom.render.visible_stats import (
    MIN_LUMINANCE_STD,
    format_visible_stats,
    orientation_words,
    visible_stats,
    visible_stats_text,
)

N = 256


def coords(n: int = N) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) pixel coordinates with y up: x = column, y = n - 1 - row."""
    rows, cols = np.mgrid[0:n, 0:n].astype(np.float64)
    return cols, (n - 1) - rows


def wave(period: float, angle_deg: float, n: int = N, square: bool = False) -> np.ndarray:
    """A unit wave of ``period`` px whose value changes along ``angle_deg``."""
    x, y = coords(n)
    t = math.radians(angle_deg)
    value = np.sin(2.0 * np.pi * (x * math.cos(t) + y * math.sin(t)) / period + 0.3)
    return np.sign(value) if square else value


def broad_noise(n: int, seed: int, exponent: float = 1.5) -> np.ndarray:
    """Unit-variance noise whose amplitude falls as 1/f**exponent (big soft blobs)."""
    rng = np.random.default_rng(seed)
    fy = np.fft.fftfreq(n)[:, None]
    fx = np.fft.fftfreq(n)[None, :]
    radius = np.maximum(np.hypot(fx, fy), 1.0 / n)
    field = np.fft.ifft2(np.fft.fft2(rng.normal(size=(n, n))) / radius**exponent).real
    return (field - field.mean()) / field.std()


def grey_maps(srgb: np.ndarray, **arrays: np.ndarray) -> MaterialMaps:
    """Opaque flat material whose albedo is the grey level ``srgb`` (0..1, H x W)."""
    rows, cols = srgb.shape
    base = {name: np.zeros((rows, cols), np.float32) for name in ARRAY_FIELDS}
    level = srgb_to_linear(np.clip(srgb, 0.0, 1.0))
    base["basecolor_linear"] = np.repeat(level[..., None], 3, axis=-1)
    base["emissive_linear"] = np.zeros((rows, cols, 3), np.float32)
    base["normal"] = np.zeros((rows, cols, 3), np.float32)
    base["normal"][..., 2] = 1.0
    base["alpha"][:] = 1.0
    base["ior"][:] = 1.5
    base["ao"][:] = 1.0
    base["roughness"][:] = 0.5
    for name, value in arrays.items():
        base[name] = np.broadcast_to(np.asarray(value, np.float32), base[name].shape).copy()
    return MaterialMaps.from_arrays(base, view=View(0, 0, 1, 1), n_layers=1)


def peaks(field: np.ndarray, limit: int = 2) -> list[spectral_peaks.Peak]:
    spec = spectrum.power_spectrum(field)
    assert spec is not None
    return spectral_peaks.find_peaks(spec, limit=limit)


def assert_period(peak: spectral_peaks.Peak, period: float, angle: float) -> None:
    assert peak.period_px == pytest.approx(period, rel=0.1)
    assert spectrum.angle_difference(peak.orientation_deg, angle) <= 10.0


# --------------------------------------------------------------------------------------------
# The spectrum: periods and orientations


@pytest.mark.parametrize("angle", [0.0, 45.0, 90.0])
@pytest.mark.parametrize("period", [6.0, 16.0, 40.0])
def test_stripes_report_their_period_and_orientation(period: float, angle: float) -> None:
    found = peaks(wave(period, angle), limit=1)
    assert len(found) == 1
    assert_period(found[0], period, angle)
    assert found[0].strength >= spectral_peaks.MIN_PEAK_STRENGTH


def test_orientation_convention_on_plain_arrays() -> None:
    """Columns changing = 0 deg (vertical stripes); rows changing = 90 (horizontal bands);
    a value that grows toward the top-right = 45 (lines from top-left to bottom-right)."""
    rows, cols = np.mgrid[0:N, 0:N].astype(np.float64)
    along_x = np.sin(2 * np.pi * cols / 16)
    along_y = np.sin(2 * np.pi * rows / 16)
    up_right = np.sin(2 * np.pi * (cols - rows) / 16 / math.sqrt(2))
    assert peaks(along_x)[0].orientation_deg == pytest.approx(0.0, abs=1.0)
    assert peaks(along_y)[0].orientation_deg == pytest.approx(90.0, abs=1.0)
    assert peaks(up_right)[0].orientation_deg == pytest.approx(45.0, abs=1.0)
    assert orientation_words(0.0) == "vertical stripes"
    assert orientation_words(179.6) == "vertical stripes"
    assert orientation_words(90.0) == "horizontal bands"
    assert "top-left to bottom-right" in orientation_words(45.0)
    assert "bottom-left to top-right" in orientation_words(135.0)


@settings(max_examples=40, deadline=None)
@given(
    period=st.floats(min_value=4.0, max_value=N / 4),
    angle=st.floats(min_value=0.0, max_value=179.9),
    square=st.booleans(),
)
def test_period_recovery_over_periods_and_angles(period: float, angle: float, square: bool) -> None:
    """Sine waves from 4 px, square waves from 8 px (below that their harmonics alias back
    onto the fundamental), up to a quarter of the image."""
    if square:
        period = max(period, 8.0)
    found = peaks(wave(period, angle, square=square), limit=1)
    assert found, "a clean wave always has a peak"
    assert_period(found[0], period, angle)


@settings(max_examples=15, deadline=None)
@given(
    period=st.floats(min_value=5.0, max_value=20.0),
    angle=st.floats(min_value=0.0, max_value=179.9),
    seed=st.integers(min_value=0, max_value=2**31),
)
def test_fine_stripes_are_found_under_broad_noise(period: float, angle: float, seed: int) -> None:
    """Broad noise has about 20 times the stripes' variance, but no period: the fine
    stripes are reported."""
    field = broad_noise(N, seed, exponent=2.0) + 0.3 * wave(period, angle)
    found = peaks(field, limit=1)
    assert found
    assert_period(found[0], period, angle)


@pytest.mark.parametrize(("period", "angle"), [(10.0, 30.0), (16.0, 90.0), (12.0, 135.0)])
def test_non_square_maps_keep_pixel_periods_and_screen_angles(period: float, angle: float) -> None:
    rows, cols = np.mgrid[0:192, 0:320].astype(np.float64)
    x, y = cols, 191.0 - rows
    t = math.radians(angle)
    field = np.sin(2 * np.pi * (x * math.cos(t) + y * math.sin(t)) / period)
    found = peaks(field, limit=1)
    assert_period(found[0], period, angle)


def test_square_wave_reports_its_fundamental() -> None:
    """Odd harmonics only: 3x and 5x are present but the period is the square wave's."""
    found = peaks(wave(24.0, 90.0, square=True), limit=1)
    assert_period(found[0], 24.0, 90.0)


def test_thin_lines_report_their_spacing_not_a_harmonic() -> None:
    """2 px dark lines every 32 px over broad noise: every harmonic is about as strong as the
    fundamental (which the broad noise swamps), and the reported period is the spacing."""
    x, y = coords()
    lines = (np.mod(y, 32.0) < 2.0).astype(np.float64)
    field = 0.6 * broad_noise(N, seed=5, exponent=2.0) - lines
    found = peaks(field, limit=1)
    assert found
    assert_period(found[0], 32.0, 90.0)
    assert found[0].harmonics >= 3


def test_checker_reports_both_diagonals() -> None:
    """A checker of 16 px squares is two diagonal waves of period 16 * sqrt(2)."""
    rows, cols = np.mgrid[0:N, 0:N]
    checker = ((rows // 16 + cols // 16) % 2).astype(np.float64)
    found = peaks(checker, limit=2)
    assert len(found) == 2
    for peak in found:
        assert peak.period_px == pytest.approx(16.0 * math.sqrt(2.0), rel=0.1)
    angles = sorted(peak.orientation_deg for peak in found)
    assert angles[0] == pytest.approx(45.0, abs=10.0)
    assert angles[1] == pytest.approx(135.0, abs=10.0)
    spec = spectrum.power_spectrum(checker)
    assert spec is not None
    anisotropy, _, _ = spectrum.directionality(spec)
    assert anisotropy < 0.1  # two orientations at right angles balance


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_white_noise_has_no_period_and_no_direction(seed: int) -> None:
    field = np.random.default_rng(seed).normal(size=(N, N))
    assert peaks(field) == []
    spec = spectrum.power_spectrum(field)
    assert spec is not None
    anisotropy, _, _ = spectrum.directionality(spec)
    assert anisotropy < 0.05


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_broad_noise_has_no_period(seed: int) -> None:
    assert peaks(broad_noise(N, seed, exponent=2.0)) == []


def test_streaky_noise_has_a_direction_but_no_period() -> None:
    """Noise smeared along X (fibres, brushing): strongly directional, not periodic."""
    rng = np.random.default_rng(9)
    fx = np.fft.fftfreq(N)[None, :]
    field = np.fft.ifft2(np.fft.fft2(rng.normal(size=(N, N))) * np.exp(-((fx * N / 2) ** 2))).real
    spec = spectrum.power_spectrum(field)
    assert spec is not None
    assert spectral_peaks.find_peaks(spec) == []
    anisotropy, orientation, _ = spectrum.directionality(spec)
    assert anisotropy > 0.9
    assert spectrum.angle_difference(orientation, 90.0) <= 5.0  # it changes along Y


def test_tiny_fields_have_no_spectrum() -> None:
    assert spectrum.power_spectrum(np.ones((8, 8))) is None
    assert spectrum.power_spectrum(np.ones((32, 32)), np.zeros((32, 32), bool)) is None


# --------------------------------------------------------------------------------------------
# visible_stats on maps


def test_flat_swatch_has_no_pattern_and_no_direction() -> None:
    """The issue's case: a nearly flat swatch (std about 1.2 of 255) had anisotropy 0.93."""
    rng = np.random.default_rng(4)
    srgb = 0.5 + (1.2 / 255.0) * wave(20.0, 30.0) + (0.3 / 255.0) * rng.normal(size=(N, N))
    stats = visible_stats(grey_maps(srgb))
    albedo = stats["albedo"]
    assert albedo["luminance_std"] < MIN_LUMINANCE_STD
    assert albedo["patterns"] is None
    assert albedo["directionality"] is None
    text = format_visible_stats(stats)
    assert "Albedo repeating pattern: n/a" in text
    assert "Albedo directionality (0 = none, 1 = all contrast in one orientation): n/a" in text


def test_constant_albedo_is_a_constant() -> None:
    stats = visible_stats(grey_maps(np.full((N, N), 0.5)))
    assert "albedo" not in stats
    r, g, b = stats["constants"]["basecolor_srgb"]
    assert r == g == b == pytest.approx(127.5, abs=0.5)
    assert "base colour sRGB (128, 128, 128)" in visible_stats_text(grey_maps(np.full((N, N), 0.5)))


def test_visible_horizontal_bands_are_directional() -> None:
    """The issue's case: visible horizontal bands read anisotropy 0.04. Bands of 64 px
    (+-20 of 255) over fine noise (+-10 of 255) are mostly directional, toward 90 deg."""
    rng = np.random.default_rng(6)
    srgb = 0.5 + (20 / 255) * wave(64.0, 90.0) + (10 / 255) * rng.normal(size=(N, N))
    albedo = visible_stats(grey_maps(srgb))["albedo"]
    direction = albedo["directionality"]
    assert direction["value"] > 0.5
    assert spectrum.angle_difference(direction["orientation_deg"], 90.0) <= 5.0
    assert albedo["patterns"][0]["period_px"] == pytest.approx(64.0, rel=0.1)


def test_white_noise_albedo_reads_no_pattern() -> None:
    rng = np.random.default_rng(8)
    srgb = 0.5 + 0.1 * rng.normal(size=(N, N))
    stats = visible_stats(grey_maps(srgb))
    assert stats["albedo"]["patterns"] == []
    assert stats["albedo"]["directionality"]["value"] < 0.05
    text = format_visible_stats(stats)
    assert "Albedo repeating pattern: none" in text
    assert "(no preferred direction)" in text


def test_constant_channels_are_reported_once_as_values() -> None:
    srgb = 0.5 + 0.2 * wave(16.0, 0.0)
    roughness = 0.3 + 0.2 * (wave(32.0, 90.0) > 0)
    text = visible_stats_text(grey_maps(srgb, roughness=roughness, coat=0.25))
    constants = next(line for line in text.splitlines() if line.startswith("- Constant"))
    for item in ("metallic 0", "clearcoat 0.25", "transmission 0", "IOR 1.5", "emissive 0"):
        assert item in constants
    assert "height 0 (flat)" in constants
    assert "anisotropy angle" not in text  # no anisotropy, so its angle is not reported
    assert "- Roughness: 0.3–0.5 (5–95 %)" in text
    assert "Metallic:" not in text and "metallic_mean" not in text
    assert "every 16.0 px" in text and "vertical stripes" in text


def test_relief_reports_range_in_units_and_pixels_and_its_pattern() -> None:
    """A height of about 0.004 units peak to peak on a 1-unit View at 256 px: about 1 px;
    ridges every 12 px along X. The normal is not derived here; its tilt is set to 10 degrees."""
    height = 0.002 * wave(12.0, 0.0)
    normal = np.zeros((N, N, 3))
    normal[..., 0] = math.sin(math.radians(10.0))
    normal[..., 2] = math.cos(math.radians(10.0))
    stats = visible_stats(grey_maps(np.full((N, N), 0.5), height=height, normal=normal))
    relief = stats["relief"]
    span = float(np.ptp(height.astype(np.float32)))
    assert span == pytest.approx(0.004, rel=0.05)
    assert relief["range_units"] == pytest.approx(span, rel=1e-6)
    assert relief["range_px"] == pytest.approx(span * N, rel=1e-6)
    assert relief["tilt_mean_deg"] == pytest.approx(10.0, abs=0.1)
    assert relief["patterns"][0]["period_px"] == pytest.approx(12.0, rel=0.1)
    assert relief["directionality"]["value"] > 0.9
    text = format_visible_stats(stats)
    assert "- Height: range 0.0039 units = 1 px of the maps" in text
    assert "- Height repeating pattern: every 12.0 px" in text


def test_shallow_relief_has_no_direction() -> None:
    height = 1e-6 * wave(12.0, 0.0)
    relief = visible_stats(grey_maps(np.full((N, N), 0.5), height=height))["relief"]
    assert relief["tilt_mean_deg"] < 0.5
    assert relief["patterns"] is None and relief["directionality"] is None


def test_coverage_metal_share_and_emission() -> None:
    alpha = np.zeros((N, N))
    alpha[:, : N // 2] = 1.0
    metallic = np.zeros((N, N))
    metallic[: N // 4, :] = 1.0
    emissive = np.zeros((N, N, 3))
    emissive[0, 0] = 2.0
    stats = visible_stats(
        grey_maps(np.full((N, N), 0.5), alpha=alpha, metallic=metallic, emissive_linear=emissive)
    )
    assert stats["coverage"] == pytest.approx(0.5)
    assert stats["metal_share"] == pytest.approx(0.25)
    assert stats["emissive"]["max"] == pytest.approx(2.0, rel=1e-3)
    text = format_visible_stats(stats)
    assert "- Material covers 50 % of the image (1 layer)" in text
    assert "metal (> 0.5) on 25 % of the material" in text
    assert "- Emission: mean luminance" in text


def test_only_the_material_region_counts() -> None:
    """Stripes inside the covered half; the uncovered half holds unrelated noise."""
    rng = np.random.default_rng(12)
    srgb = 0.5 + 0.3 * rng.normal(size=(N, N))
    srgb[:, : N // 2] = 0.5 + 0.2 * wave(8.0, 90.0)[:, : N // 2]
    alpha = np.zeros((N, N))
    alpha[:, : N // 2] = 1.0
    albedo = visible_stats(grey_maps(srgb, alpha=alpha))["albedo"]
    assert albedo["patterns"][0]["period_px"] == pytest.approx(8.0, rel=0.1)
    assert albedo["directionality"]["value"] > 0.8


def test_empty_material_says_so() -> None:
    maps = grey_maps(np.full((N, N), 0.5), alpha=0.0)
    stats = visible_stats(maps)
    assert stats["coverage"] == 0.0
    assert "No material" in format_visible_stats(stats)


def test_stats_are_json_ready() -> None:
    srgb = 0.5 + 0.2 * wave(16.0, 45.0)
    stats = visible_stats(grey_maps(srgb, height=0.001 * wave(20.0, 0.0)))
    assert json.loads(json.dumps(stats))["size"] == [N, N]


# --------------------------------------------------------------------------------------------
# Programs


WEAVE = """View(0, 0, 1, 1)
Define(threads, Weave(over=1, under=1, base_freq=40, warp_width=0.8))
Material(
  Layer(1).basecolor(30, 30, 30).roughness(0.9),
  Layer(threads).basecolor(200, 190, 170).roughness(0.7).height((threads * 0.002))
)
"""


def test_fine_weave_program_at_512_shows_its_thread_spacing() -> None:
    """40 threads per unit on a 1-unit View at 512 px: a thread every 12.8 px on both axes,
    which a 128x128 grid (3.2 px per thread) cannot show."""
    stats = visible_stats(evaluate(WEAVE, 512, 512))
    for section in (stats["albedo"], stats["relief"]):
        found = section["patterns"]
        assert len(found) == 2
        for pattern in found:
            assert pattern["period_px"] == pytest.approx(12.8, rel=0.1)
        angles = sorted(spectrum.angle_difference(p["orientation_deg"], 0.0) for p in found)
        assert angles[0] <= 10.0 and angles[1] >= 80.0  # one along X, one along Y


def test_api_visible_stats_text_evaluates_at_the_given_size() -> None:
    text = api.visible_stats_text(WEAVE, size=256)
    assert text.startswith("Visible statistics (computed on the 256x256 maps")
    assert "every 6.4 px" in text


def test_api_visible_stats_text_checks_the_size() -> None:
    with pytest.raises(LimitError):
        api.visible_stats_text(WEAVE, size=100_000)
