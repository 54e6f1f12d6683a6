"""The 28 critic statistics on analytic materials whose values follow by hand from §7."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.engine.colour import srgb_to_linear
from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps, View
from matloom.render.stats import (
    STAT_DEFINITIONS,
    STAT_NAMES,
    format_stat_value,
    format_stats,
    material_stats,
    stat_label,
)

N = 128

#: The reference's keys in its reporting order (spec §7 table).
REFERENCE_ORDER = (
    "albedo_luminance_mean albedo_luminance_std albedo_rms_contrast albedo_saturation "
    "albedo_edge_density albedo_dominant_freq albedo_freq_bandwidth albedo_anisotropy "
    "albedo_color_span albedo_tonal_entropy roughness_mean roughness_std metallic_mean "
    "metallic_coverage height_range height_std height_dominant_freq height_anisotropy "
    "normal_mean_tilt_deg ao_mean ao_std sheen_mean coat_mean transmission_mean "
    "subsurface_mean anisotropy_mean ior_mean emissive_mean"
).split()


def make_maps(
    rows: int = N, cols: int = N, n_layers: int = 1, **arrays: np.ndarray
) -> MaterialMaps:
    """Opaque flat mid-grey material; keyword arrays (broadcast to the grid) override maps."""
    base = {name: np.zeros((rows, cols), np.float32) for name in ARRAY_FIELDS}
    base["basecolor_linear"] = np.full((rows, cols, 3), srgb_to_linear(0.5), np.float32)
    base["emissive_linear"] = np.zeros((rows, cols, 3), np.float32)
    base["normal"] = np.zeros((rows, cols, 3), np.float32)
    base["normal"][..., 2] = 1.0
    base["alpha"][:] = 1.0
    base["ior"][:] = 1.5
    base["ao"][:] = 1.0
    for name, value in arrays.items():
        base[name] = np.broadcast_to(np.asarray(value, np.float32), base[name].shape).copy()
    return MaterialMaps.from_arrays(base, n_layers=n_layers)


def grey(srgb: np.ndarray) -> np.ndarray:
    """Linear basecolor whose sRGB encoding is the grey level ``srgb`` (H, W) -> (H, W, 3)."""
    return np.repeat(srgb_to_linear(np.asarray(srgb, np.float64))[..., None], 3, axis=-1)


def columns_index(rows: int = N, cols: int = N) -> np.ndarray:
    return np.broadcast_to(np.arange(cols, dtype=np.float64), (rows, cols))


def rows_index(rows: int = N, cols: int = N) -> np.ndarray:
    return np.broadcast_to(np.arange(rows, dtype=np.float64)[:, None], (rows, cols))


# --- names, definitions, formatting --------------------------------------------------------


def test_names_are_the_reference_keys_in_order() -> None:
    assert STAT_NAMES == tuple(REFERENCE_ORDER)
    assert list(material_stats(make_maps())) == REFERENCE_ORDER


def test_every_statistic_has_a_one_line_definition() -> None:
    for name in STAT_NAMES:
        definition = STAT_DEFINITIONS[name]
        assert definition and "\n" not in definition and "—" not in definition


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (0.0, "0"),
        (-0.0, "0"),
        (0.0001, "0.000"),
        (1.23456, "1.235"),
        (-2.5, "-2.500"),
        (9.9994, "9.999"),
        (10.0, "10.00"),
        (12.3456, "12.35"),
        (-15.0, "-15.00"),
        (99.99, "99.99"),
        (100.0, "100.0"),
        (127.5, "127.5"),
        (-150.0, "-150.0"),
        (1234.56, "1234.6"),
    ],
)
def test_value_format(value: float, text: str) -> None:
    assert format_stat_value(value) == text


@pytest.mark.parametrize(
    ("name", "label"),
    [
        ("ao_mean", "AO mean"),
        ("ao_std", "AO std"),
        ("albedo_rms_contrast", "Albedo RMS contrast"),
        ("ior_mean", "IOR mean"),
        ("albedo_luminance_mean", "Albedo luminance mean"),
        ("normal_mean_tilt_deg", "Normal mean tilt deg"),
        ("anisotropy_mean", "Anisotropy mean"),
    ],
)
def test_labels(name: str, label: str) -> None:
    assert stat_label(name) == label


def test_critic_block_layout() -> None:
    stats = material_stats(make_maps())
    lines = format_stats(stats).split("\n")
    assert lines[0] == "Appearance scalars (computed on a 128x128 grid):"
    assert len(lines) == 1 + 28
    pattern = re.compile(r"^- ([A-Z][^:]*): (\S+) — (.+)$")
    for name, line in zip(STAT_NAMES, lines[1:], strict=True):
        match = pattern.match(line)
        assert match, line
        assert match.group(1) == stat_label(name)
        assert match.group(2) == format_stat_value(stats[name])
        assert match.group(3) == STAT_DEFINITIONS[name]
    assert "- IOR mean: 1.500 — " in format_stats(stats)
    assert "- Roughness std: 0 — " in format_stats(stats)


# --- empty material and masking -----------------------------------------------------------


@pytest.mark.parametrize("alpha", [0.0, 5e-4, np.nan])
def test_no_material_region_gives_all_zeros(alpha: float) -> None:
    stats = material_stats(make_maps(alpha=alpha, roughness=0.7, metallic=1.0, height=0.3))
    assert stats == dict.fromkeys(STAT_NAMES, 0.0)


def test_no_layers_gives_all_zeros() -> None:
    assert set(material_stats(make_maps(n_layers=0, roughness=0.7)).values()) == {0.0}


def test_only_texels_with_coverage_above_threshold_count() -> None:
    alpha = np.where(columns_index() < 32, 5e-4, 1.0)
    roughness = np.where(columns_index() < 32, 1.0, 0.25)
    stats = material_stats(make_maps(alpha=alpha, roughness=roughness))
    assert stats["roughness_mean"] == 0.25
    assert stats["roughness_std"] == 0.0


def test_non_finite_blended_values_count_as_zero() -> None:
    left = columns_index() < 64
    base = np.where(left[..., None], np.nan, 1.0)
    emissive = np.where(left[..., None], np.inf, np.array([2.0, 0.0, 0.0]))
    stats = material_stats(
        make_maps(
            roughness=np.where(left, np.nan, 1.0),
            ior=np.where(left, -np.inf, 1.5),
            basecolor_linear=base,
            emissive_linear=emissive,
        )
    )
    assert stats["roughness_mean"] == pytest.approx(0.5)
    assert stats["ior_mean"] == pytest.approx(0.75)
    assert stats["albedo_luminance_mean"] == pytest.approx(127.5, abs=1e-4)  # black + white
    assert stats["emissive_mean"] == pytest.approx(0.2126)  # 0.2126 * 2 on half the texels
    assert all(math.isfinite(v) for v in stats.values())


# --- albedo statistics -----------------------------------------------------------------------


def test_constant_material() -> None:
    stats = material_stats(make_maps(roughness=0.3))
    assert stats["albedo_luminance_mean"] == pytest.approx(127.5, abs=1e-4)
    zero = [
        "albedo_luminance_std",
        "albedo_rms_contrast",
        "albedo_saturation",
        "albedo_edge_density",
        "albedo_dominant_freq",
        "albedo_freq_bandwidth",
        "albedo_anisotropy",
        "albedo_color_span",
        "albedo_tonal_entropy",
        "roughness_std",
        "height_range",
        "height_std",
        "height_dominant_freq",
        "height_anisotropy",
        "normal_mean_tilt_deg",
        "ao_std",
        "emissive_mean",
    ]
    for name in zero:
        assert stats[name] == pytest.approx(0.0, abs=1e-9), name
    assert stats["roughness_mean"] == pytest.approx(0.3)
    assert stats["ao_mean"] == 1.0
    assert stats["ior_mean"] == 1.5


def test_black_material_has_zero_contrast_and_saturation() -> None:
    stats = material_stats(make_maps(basecolor_linear=0.0))
    assert stats["albedo_luminance_mean"] == 0.0
    assert stats["albedo_rms_contrast"] == 0.0
    assert stats["albedo_saturation"] == 0.0


@pytest.mark.parametrize(
    ("srgb", "saturation"),
    [((1.0, 0.0, 0.0), 1.0), ((1.0, 0.5, 0.5), 0.5), ((0.2, 0.8, 0.4), 0.75), ((0.3,) * 3, 0.0)],
)
def test_saturation_is_one_minus_min_over_max(srgb: tuple, saturation: float) -> None:
    stats = material_stats(make_maps(basecolor_linear=srgb_to_linear(np.array(srgb))))
    assert stats["albedo_saturation"] == pytest.approx(saturation, abs=1e-6)


def test_luminance_uses_rec709_weights_on_srgb_values() -> None:
    red = material_stats(make_maps(basecolor_linear=(1.0, 0.0, 0.0)))
    green = material_stats(make_maps(basecolor_linear=(0.0, 1.0, 0.0)))
    assert red["albedo_luminance_mean"] == pytest.approx(0.2126 * 255)
    assert green["albedo_luminance_mean"] == pytest.approx(0.7152 * 255)
    assert red["albedo_color_span"] == 0.0  # constant colour: no per-channel range


def test_checker() -> None:
    """16-texel cells of sRGB grey 0.25 / 0.75: 4 cycles per axis, fundamental at radius 5.66."""
    cell = ((rows_index() // 16 + columns_index() // 16) % 2).astype(bool)
    stats = material_stats(make_maps(basecolor_linear=grey(np.where(cell, 0.75, 0.25))))
    assert stats["albedo_luminance_mean"] == pytest.approx(127.5, abs=1e-4)
    assert stats["albedo_luminance_std"] == pytest.approx(63.75, abs=1e-4)
    assert stats["albedo_rms_contrast"] == pytest.approx(0.5, abs=1e-6)
    assert stats["albedo_color_span"] == pytest.approx(127.5, abs=1e-4)
    assert stats["albedo_tonal_entropy"] == pytest.approx(1 / 5)  # two equal tones = 1 bit
    assert stats["albedo_dominant_freq"] == 5.0  # int(4 * sqrt(2))
    assert stats["albedo_anisotropy"] == pytest.approx(0.0, abs=1e-6)  # 4-fold symmetric
    # Each of the 7 inner cell borders per axis puts two texel lines at |d/dx| = 0.5 / 2; the
    # 14 x 14 texels where such lines cross have |gradient| = 0.25 * sqrt(2); the rest is 0.
    lines = 2 * 7
    crossing = lines * lines
    one_axis = 2 * (lines * N - crossing)
    expected = (one_axis * 0.25 + crossing * 0.25 * math.sqrt(2)) / (N * N)
    assert stats["albedo_edge_density"] == pytest.approx(expected, rel=1e-5)


@pytest.mark.parametrize(("cycles", "axis"), [(1, 1), (6, 1), (6, 0), (17, 0), (40, 1)])
def test_sinusoid_stripes(cycles: int, axis: int) -> None:
    index = columns_index() if axis == 1 else rows_index()
    wave = np.sin(2 * np.pi * cycles * index / N)
    stats = material_stats(make_maps(basecolor_linear=grey(0.5 + 0.25 * wave), height=0.1 * wave))
    assert stats["albedo_dominant_freq"] == cycles
    assert stats["height_dominant_freq"] == cycles
    assert stats["albedo_anisotropy"] > 0.999
    assert stats["height_anisotropy"] > 0.999
    assert stats["albedo_freq_bandwidth"] < 0.01  # all energy in one radial bin
    assert stats["height_range"] == pytest.approx(0.2, abs=1e-6)
    assert stats["height_std"] == pytest.approx(0.1 / math.sqrt(2), rel=1e-6)
    assert stats["albedo_luminance_std"] == pytest.approx(255 * 0.25 / math.sqrt(2), rel=1e-5)


def test_two_frequencies() -> None:
    """4 cycles along x plus 12 along y, equal amplitude.

    |F| has two equal peaks in radial bin 4 and two in bin 12, so the bin means are the peak sum
    divided by each bin's texel count: the dominant frequency is 4 (the smaller ring), the
    bandwidth is the count-weighted spread of {4, 12} over r_max = 64, and the energy second
    moments are 2E * 4^2 along x and 2E * 12^2 along y: anisotropy 1 - 16/144 = 8/9.
    """
    wave = np.sin(2 * np.pi * 4 * columns_index() / N) + np.sin(2 * np.pi * 12 * rows_index() / N)
    stats = material_stats(make_maps(basecolor_linear=grey(0.5 + 0.2 * wave), height=wave))
    w4, w12 = 1 / _bin_count(4), 1 / _bin_count(12)
    mean = (4 * w4 + 12 * w12) / (w4 + w12)
    variance = (w4 * (4 - mean) ** 2 + w12 * (12 - mean) ** 2) / (w4 + w12)
    assert stats["albedo_freq_bandwidth"] == pytest.approx(math.sqrt(variance) / 64, rel=1e-5)
    assert stats["albedo_dominant_freq"] == stats["height_dominant_freq"] == 4.0
    assert stats["albedo_anisotropy"] == pytest.approx(8 / 9, rel=1e-6)
    assert stats["height_anisotropy"] == pytest.approx(8 / 9, rel=1e-6)


def _bin_count(radius: int, n: int = N) -> int:
    """Texels of an n x n grid whose distance from (n//2, n//2) truncates to ``radius``."""
    d = np.arange(n) - n // 2
    r = np.sqrt(d[:, None] ** 2 + d[None, :] ** 2).astype(int)
    return int(np.count_nonzero(r == radius))


def test_non_square_grid_uses_its_own_centre_and_rmax() -> None:
    rows, cols = 64, 128
    wave = np.sin(2 * np.pi * 10 * columns_index(rows, cols) / cols)
    stats = material_stats(make_maps(rows, cols, height=wave))
    assert stats["height_dominant_freq"] == 10.0
    wave = np.sin(2 * np.pi * 20 * rows_index(rows, cols) / rows)
    assert material_stats(make_maps(rows, cols, height=wave))["height_dominant_freq"] == 20.0
    # 40 cycles across is beyond r_max = min(32, 64): it is not in the band
    wave = np.sin(2 * np.pi * 40 * columns_index(rows, cols) / cols)
    assert material_stats(make_maps(rows, cols, height=wave))["height_dominant_freq"] <= 32


def test_spectral_statistics_need_a_grid_of_at_least_4() -> None:
    checker = (np.indices((3, 3)).sum(axis=0) % 2).astype(np.float32)
    stats = material_stats(make_maps(3, 3, height=checker))
    assert stats["height_dominant_freq"] == stats["height_anisotropy"] == 0.0
    assert stats["height_range"] == 1.0


def test_edge_density_of_a_ramp_is_its_slope() -> None:
    slope = 0.5 / (N - 1)
    stats = material_stats(make_maps(basecolor_linear=grey(0.25 + slope * columns_index())))
    assert stats["albedo_edge_density"] == pytest.approx(slope, rel=1e-4)


def test_edge_density_of_a_step() -> None:
    step = np.where(columns_index() < 64, 0.0, 1.0)
    stats = material_stats(make_maps(basecolor_linear=grey(step)))
    # columns 63 and 64 have central differences of 1/2; every other texel 0
    assert stats["albedo_edge_density"] == pytest.approx(2 * N * 0.5 / (N * N))


def test_edge_density_ignores_the_material_boundary() -> None:
    """A white material on the left half over nothing: the eroded mask drops the boundary."""
    left = columns_index() < 64
    stats = material_stats(
        make_maps(alpha=np.where(left, 1.0, 0.0), basecolor_linear=grey(np.where(left, 1.0, 0.0)))
    )
    assert stats["albedo_edge_density"] == 0.0
    assert stats["albedo_luminance_mean"] == pytest.approx(255.0, abs=1e-4)


def test_tonal_entropy_of_32_equal_tones_is_one() -> None:
    tones = (columns_index() // 4 + 0.5) / 32  # 4 columns per histogram-bin centre
    stats = material_stats(make_maps(basecolor_linear=grey(tones)))
    assert stats["albedo_tonal_entropy"] == pytest.approx(1.0)


# --- other channels ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("metallic", "mean", "coverage"),
    [(1.0, 1.0, 1.0), (0.5, 0.5, 0.0), (0.0, 0.0, 0.0), ("halves", 0.45, 0.5)],
)
def test_metallic(metallic: float | str, mean: float, coverage: float) -> None:
    value = np.where(columns_index() < 64, 0.7, 0.2) if metallic == "halves" else metallic
    stats = material_stats(make_maps(metallic=value))
    assert stats["metallic_mean"] == pytest.approx(mean)
    assert stats["metallic_coverage"] == coverage


def test_height_ao_and_tilt() -> None:
    left = columns_index() < 64
    tilt = math.radians(30.0)
    stats = material_stats(
        make_maps(
            height=np.where(left, 0.0, 0.2),
            ao=np.where(left, 1.0, 0.5),
            normal=np.array([math.sin(tilt), 0.0, math.cos(tilt)]),
        )
    )
    assert stats["height_range"] == pytest.approx(0.2)
    assert stats["height_std"] == pytest.approx(0.1)
    assert stats["ao_mean"] == 0.75
    assert stats["ao_std"] == 0.25
    assert stats["normal_mean_tilt_deg"] == pytest.approx(30.0, abs=1e-4)


def test_plain_channel_means() -> None:
    stats = material_stats(
        make_maps(sheen=0.1, coat=0.2, transmission=0.3, subsurface=0.4, anisotropy=0.6, ior=2.25)
    )
    expected = {"sheen": 0.1, "coat": 0.2, "transmission": 0.3, "subsurface": 0.4}
    expected |= {"anisotropy": 0.6, "ior": 2.25}
    for name, value in expected.items():
        assert stats[f"{name}_mean"] == pytest.approx(value), name


def test_emissive_luminance_clips_negatives() -> None:
    stats = material_stats(make_maps(emissive_linear=(-1.0, 1.0, 0.0)))
    assert stats["emissive_mean"] == pytest.approx(0.7152)
    stats = material_stats(make_maps(emissive_linear=(2.0, 2.0, 2.0)))
    assert stats["emissive_mean"] == pytest.approx(2.0)  # may exceed 1


# --------------------------------------------------------------------------------------------
# Fixture programs: the statistics of our maps equal those of the reference's own maps.

_PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
_MANIFEST = json.loads((_PARITY / "manifest.json").read_text())["programs"]


@pytest.mark.parametrize("name", sorted(_MANIFEST))
def test_fixture_statistics_match_those_of_the_reference_maps(name: str) -> None:
    """The fixtures hold the reference's maps (64x64), not its statistics: the 28 statistics of
    our evaluation must equal those computed from the reference's arrays, and the critic text
    must be the same line for line."""
    entry = _MANIFEST[name]
    view = View(*entry["view"])
    with np.load(_PARITY / f"{name}_64x64.npz") as data:
        reference = MaterialMaps.from_arrays(dict(data), view=view, n_layers=entry["n_layers"])
    baked = _PARITY / f"{name}.baked.mat"
    text = (baked if baked.exists() else _PARITY / f"{name}.mat").read_text()
    ours = matloom.evaluate(text, 64, 64)
    want, got = material_stats(reference), material_stats(ours)
    assert list(got) == list(want)
    for key, value in want.items():
        assert got[key] == pytest.approx(value, rel=1e-5, abs=1e-6), (name, key)
    assert format_stats(got) == format_stats(want)
