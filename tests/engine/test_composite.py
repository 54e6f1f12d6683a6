"""composite(): parity with reference fixtures (hand-evaluated programs) and rule checks."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from matloom.engine.composite import RawLayer, composite
from matloom.engine.maps import ARRAY_FIELDS, NEWER_FIELDS, SCALAR_CHANNELS, View

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
MANIFEST = json.loads((PARITY / "manifest.json").read_text())["programs"]
F32 = np.float32


def _axes(view: View, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """X (1, W) and Y (H, 1) sample coordinates as the reference builds them (float32 axes),
    widened to float64 because the reference's Constant grids promote arithmetic to float64."""
    x = (np.arange(width, dtype=F32) + F32(0.5)) * F32((view.x2 - view.x1) / width) + F32(view.x1)
    y = (np.arange(height, dtype=F32) + F32(0.5)) * F32((view.y1 - view.y2) / height)
    y = y + F32(view.y2)
    return x.astype(np.float64)[None, :], y.astype(np.float64)[:, None]


# Hand transcriptions of three fixture programs (see tests/data/parity/<name>.mat); only plain
# numpy maths appears in them, so the composite is the only MatLoom code under test.


def _ghost_layer(x: np.ndarray, y: np.ndarray) -> list[RawLayer]:
    return [
        RawLayer(
            alpha=1.0,
            basecolor=(90.0, 120.0, 90.0),
            roughness=0.7,
            height=np.sin(x * 2 * np.pi) * 0.01 + 0 * y,
        ),
        RawLayer(
            alpha=0.0,
            basecolor=(255.0, 0.0, 255.0),
            emissive=(255.0, 0.0, 255.0, 10.0),
            height=1.0,
        ),
        RawLayer(alpha=x - 2, basecolor=(0.0, 255.0, 255.0), roughness=0.0, height=0.5),
    ]


def _nan_inf_fields(x: np.ndarray, y: np.ndarray) -> list[RawLayer]:
    with np.errstate(invalid="ignore", divide="ignore"):
        dome = np.sqrt(0.36 - x**2 - y**2)
        log_band = np.log(np.floor(np.abs(y) * 2) / 2) + 0 * x
    return [
        RawLayer(alpha=1.0, basecolor=(200.0, 200.0, 200.0), roughness=0.5, height=-0.05),
        RawLayer(
            alpha=0.8,
            basecolor=(255 * dome, 120.0, 60.0),
            roughness=dome,
            metallic=log_band,
            height=dome * 0.2,
        ),
        RawLayer(
            alpha=0.5,
            basecolor=(40.0, 40.0, 40.0),
            emissive=(255.0, 200.0, 100.0, -log_band),
            height=-log_band * 0.01,
        ),
    ]


def _trig_ripples(x: np.ndarray, y: np.ndarray) -> list[RawLayer]:
    r = np.sqrt(x**2 + y**2)
    wave = np.cos(r * 6 * np.pi) * 0.5 + 0.5
    swirl = np.sin(x * 3 * np.pi) * np.cos(y * 2 * np.pi)
    return [
        RawLayer(
            alpha=1.0,
            basecolor=(30 + wave * 60, 80 + wave * 80, 140 + wave * 100),
            roughness=0.05 + swirl * swirl * 0.2,
            transmission=0.6,
            ior=1.33,
            height=wave * 0.01 * (1 - np.minimum(r, 1)),
        )
    ]


PROGRAMS: dict[str, Callable[[np.ndarray, np.ndarray], list[RawLayer]]] = {
    "ghost_layer": _ghost_layer,
    "nan_inf_fields": _nan_inf_fields,
    "trig_ripples": _trig_ripples,
}


@pytest.mark.parametrize("size", [(64, 64), (48, 32)])
@pytest.mark.parametrize("name", sorted(PROGRAMS))
def test_composite_matches_reference(name: str, size: tuple[int, int]) -> None:
    width, height = size
    view = View(*MANIFEST[name]["view"])
    layers = PROGRAMS[name](*_axes(view, width, height))
    maps = composite(layers, width, height, view)
    expected = np.load(PARITY / f"{name}_{width}x{height}.npz")
    assert set(expected.files) <= set(ARRAY_FIELDS), f"{name}: unknown arrays in the fixture"
    # The fixtures predate the language-2 channels: they hold every other map.
    assert set(ARRAY_FIELDS) - set(expected.files) == set(NEWER_FIELDS)
    for field in NEWER_FIELDS:  # no layer writes them: their default, 0
        assert np.all(getattr(maps, field) == 0), field
    for field in expected.files:
        got, want = getattr(maps, field), expected[field]
        assert got.dtype == np.float32, field
        assert got.shape == want.shape, field
        np.testing.assert_array_equal(np.isnan(got), np.isnan(want), err_msg=field)
        np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-6, err_msg=field)
    assert maps.n_layers == len(layers)
    assert maps.view == view


def test_nan_inf_fixture_counts_match_manifest() -> None:
    view = View(*MANIFEST["nan_inf_fields"]["view"])
    maps = composite(_nan_inf_fields(*_axes(view, 64, 64)), 64, 64, view)
    assert maps.nonfinite_counts() == MANIFEST["nan_inf_fields"]["nonfinite_values"]["64x64"]


# ---------------------------------------------------------------------------------------------
# Rule checks on synthetic layers


def _one(layers: list[RawLayer], width: int = 2, height: int = 1) -> object:
    return composite(layers, width, height, View())


def test_over_rule_two_layers() -> None:
    bottom = RawLayer(alpha=0.5, metallic=1.0, roughness=0.2)
    top = RawLayer(alpha=0.25, metallic=0.0, roughness=1.0)
    maps = _one([bottom, top])
    v_top, v_bottom = 0.25, 0.5 * (1 - 0.25)
    coverage = 1 - (1 - 0.25) * (1 - 0.5)
    np.testing.assert_allclose(maps.alpha, coverage, rtol=1e-6)
    np.testing.assert_allclose(maps.metallic, v_bottom / coverage, rtol=1e-6)
    np.testing.assert_allclose(maps.roughness, (v_top + v_bottom * 0.2) / coverage, rtol=1e-6)


def test_order_matters_for_colour_but_not_height() -> None:
    red = RawLayer(alpha=1.0, basecolor=(255, 0, 0), height=0.1)
    blue = RawLayer(alpha=1.0, basecolor=(0, 0, 255), height=0.3)
    a, b = _one([red, blue]), _one([blue, red])
    np.testing.assert_array_equal(a.basecolor_linear[0, 0], [0, 0, 1])
    np.testing.assert_array_equal(b.basecolor_linear[0, 0], [1, 0, 0])
    np.testing.assert_array_equal(a.height, b.height)
    np.testing.assert_allclose(a.height, 0.3, rtol=1e-7)


def test_zero_coverage_gives_zero_everywhere() -> None:
    layer = RawLayer(
        alpha=np.array([[0.0, 0.5]]),
        basecolor=(255, 255, 255),
        ior=2.0,
        emissive=(255, 255, 255, 4.0),
        roughness=1.0,
    )
    maps = _one([layer])
    for field in (*SCALAR_CHANNELS, "ior", "alpha"):
        assert getattr(maps, field)[0, 0] == 0, field
    assert np.all(maps.basecolor_linear[0, 0] == 0)
    assert np.all(maps.emissive_linear[0, 0] == 0)
    assert maps.ior[0, 1] == pytest.approx(2.0)
    # partial coverage keeps full intensity (un-premultiplied)
    np.testing.assert_allclose(maps.basecolor_linear[0, 1], 1.0)


def test_clamps() -> None:
    layer = RawLayer(
        alpha=3.0,
        basecolor=(-20, 300, 127.5),
        metallic=-1,
        roughness=2,
        sheen=0.25,
        ior=0.5,
        emissive=(255, 0, 0, -5.0),
        height=-7.5,
    )
    maps = _one([layer])
    assert maps.alpha[0, 0] == 1
    assert maps.metallic[0, 0] == 0 and maps.roughness[0, 0] == 1
    assert maps.sheen[0, 0] == 0.25
    assert maps.ior[0, 0] == 1
    assert np.all(maps.emissive_linear == 0)
    assert maps.height[0, 0] == np.float32(-7.5)  # height is not clamped
    r, g, b = maps.basecolor_linear[0, 0]
    assert (r, g) == (0, 1)
    assert b == pytest.approx(((127.5 / 255 + 0.055) / 1.055) ** 2.4, rel=1e-6)


def test_nan_passes_through_clamps() -> None:
    maps = _one([RawLayer(roughness=np.nan, ior=np.nan)])
    assert np.isnan(maps.roughness).all() and np.isnan(maps.ior).all()
    assert maps.metallic[0, 0] == 0


def test_emissive_is_linear_colour_times_strength() -> None:
    maps = _one([RawLayer(emissive=(255, 0, 10, 3.0))])
    low = (10 / 255) / 12.92
    np.testing.assert_allclose(maps.emissive_linear[0, 0], [3.0, 0.0, 3 * low], rtol=1e-6)


def test_height_gate_and_non_finite_rules() -> None:
    alpha = np.array([[1.0, 0.0, 1.0, 1.0, 0.001]])
    ground = RawLayer(alpha=alpha, height=np.array([[-0.5, 9.0, np.nan, np.inf, -0.0]]))
    maps = composite([ground], 5, 1, View())
    # alpha 0 -> no height (0); NaN/inf -> ignored (0); any alpha > 0 counts fully; -0 -> +0
    np.testing.assert_array_equal(maps.height[0], [-0.5, 0.0, 0.0, 0.0, 0.0])
    assert not np.signbit(maps.height[0, 1:]).any()


def test_height_is_max_over_present_layers() -> None:
    low = RawLayer(alpha=1.0, height=np.array([[0.2, -0.3]]))
    high = RawLayer(alpha=0.01, height=np.array([[0.1, -0.1]]))
    maps = composite([low, high], 2, 1, View())
    np.testing.assert_allclose(maps.height[0], [0.2, -0.1])


def test_empty_material_raises() -> None:
    with pytest.raises(ValueError, match="material has no layers"):
        composite([], 4, 4, View())


def test_bad_channel_shape_raises() -> None:
    with pytest.raises(ValueError):
        composite([RawLayer(roughness=np.zeros((3, 3)))], 4, 4, View())


def test_ao_radius_options() -> None:
    rng = np.random.default_rng(5)
    h = rng.random((64, 64))
    layer = [RawLayer(height=h)]
    default = composite(layer, 64, 64, View())
    in_units = composite(layer, 64, 64, View(), ao_radius_units=8 / 64)
    np.testing.assert_array_equal(default.ao, in_units.ao)
    wider = composite(layer, 64, 64, View(), ao_radius_texels=2.5)
    assert not np.array_equal(default.ao, wider.ao)
    with pytest.raises(ValueError):
        composite(layer, 64, 64, View(), ao_radius_texels=2, ao_radius_units=0.1)


def test_bands_do_not_change_results(monkeypatch: pytest.MonkeyPatch) -> None:
    from matloom.engine import composite as composite_module

    view = View(*MANIFEST["nan_inf_fields"]["view"])
    layers = _nan_inf_fields(*_axes(view, 48, 32))
    whole = composite(layers, 48, 32, view)
    monkeypatch.setattr(composite_module, "BAND_ROWS", 5)
    banded = composite(layers, 48, 32, view)
    for field in ARRAY_FIELDS:
        np.testing.assert_array_equal(getattr(banded, field), getattr(whole, field))


def test_colour_decode_matches_reference_texel() -> None:
    """alpha_override, top-left texel: only the opaque bottom layer (50, 60, 70) is present."""
    from matloom.engine.composite import colour_to_linear

    want = np.load(PARITY / "alpha_override_64x64.npz")["basecolor_linear"][0, 0]
    got = [colour_to_linear(np.float64(c)) for c in (50, 60, 70)]
    np.testing.assert_array_equal(np.array(got, dtype=np.float32), want)
