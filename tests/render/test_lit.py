"""The ``lit`` preview layout (matloom.render.lit): what each channel does to the image, the two
implementations against each other, the API and CLI layouts, and the layout notes' claims."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

import matloom
from matloom.cli.main import cli
from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps
from matloom.render import lit_model
from matloom.render.api import preview
from matloom.render.lit import (
    FLAT_LAYOUT_NOTE,
    LIT_LAYOUT_NOTE,
    NOT_READ,
    available_backends,
    shade_lit,
)
from matloom.render.preview import Light, shade
from matloom.vocab.layout import LAYOUT

N = 64
BACKENDS = available_backends()
#: Neutral maps: mid-grey dielectric, roughness 0.5, flat, covered, unoccluded.
DEFAULTS = {"basecolor_linear": 0.5, "alpha": 1.0, "roughness": 0.5, "ior": 1.5, "ao": 1.0}
PROGRAM = (
    "Material(\n  Layer(1)\n    .basecolor(180, 120, 80)\n    .roughness(0.3)\n"
    "    .height(fBm(octaves=3, base_freq=4, to_01=True, seed=5) * 0.02)\n)"
)


def make_maps(size: int = N, width: int | None = None, **channels: object) -> MaterialMaps:
    """Maps of ``size`` rows (``width`` columns) from :data:`DEFAULTS`, channels overridden by
    scalars, colours or arrays; the normal is +z unless given."""
    shape2 = (size, width or size)
    arrays = {}
    for name in ARRAY_FIELDS:
        shape = shape2 + ((3,) if LAYOUT.components(name) == 3 else ())
        value = channels.get(name, (0.0, 0.0, 1.0) if name == "normal" else DEFAULTS.get(name, 0))
        arrays[name] = np.broadcast_to(np.asarray(value, np.float32), shape).copy()
    return MaterialMaps.from_arrays(arrays)


def dome_normals(size: int = N) -> np.ndarray:
    """Unit normals of a round bump in the middle of the swatch (flat around it)."""
    y, x = np.mgrid[0:size, 0:size]
    u, v = (x + 0.5) / size * 2 - 1, 1 - (y + 0.5) / size * 2
    height = np.sqrt(np.maximum(0.6 - (u * u + v * v), 0.0))
    gx = np.clip(np.gradient(height, axis=1) * size / 2, -1.5, 1.5)
    gy = np.clip(-np.gradient(height, axis=0) * size / 2, -1.5, 1.5)
    n = np.stack([-gx, -gy, np.ones_like(gx)], axis=-1)
    return (n / np.linalg.norm(n, axis=-1, keepdims=True)).astype(np.float32)


def luminance(img: np.ndarray) -> np.ndarray:
    return img.astype(np.float64).mean(axis=-1)


def random_maps(rng: np.random.Generator, rows: int, cols: int) -> MaterialMaps:
    """Every map random (normals with relief, angles, ior beyond 3), with NaN and inf sprinkled."""
    arrays = {}
    for name in ARRAY_FIELDS:
        shape = (rows, cols) + ((3,) if LAYOUT.components(name) == 3 else ())
        arrays[name] = rng.uniform(-0.1, 1.1, shape).astype(np.float32)
    arrays["ior"] = rng.uniform(0.5, 4.0, (rows, cols)).astype(np.float32)
    arrays["anisotropy_angle"] = rng.uniform(-360, 360, (rows, cols)).astype(np.float32)
    arrays["emissive_linear"] *= rng.random((rows, cols, 1)) < 0.2
    normal = rng.normal(size=(rows, cols, 3)) * (0.4, 0.4, 1.0) + (0, 0, 1.5)
    arrays["normal"] = (normal / np.linalg.norm(normal, axis=-1, keepdims=True)).astype(np.float32)
    for name in ("alpha", "roughness", "normal", "ior", "emissive_linear", "anisotropy_angle"):
        flat = arrays[name].reshape(-1)
        picks = rng.choice(flat.size, 6, replace=False)
        flat[picks] = [np.nan, np.inf, -np.inf, np.nan, 1e30, -1e30]
    return MaterialMaps.from_arrays(arrays)


# --- output and implementations ------------------------------------------------------------


@pytest.mark.parametrize("backend", BACKENDS)
def test_output_is_srgb_uint8_and_bad_values_never_raise(backend: str) -> None:
    maps = random_maps(np.random.default_rng(1), 24, 40)
    img = shade_lit(maps, backend=backend)
    assert img.dtype == np.uint8 and img.shape == (24, 40, 3)
    assert shade_lit(maps, backend=backend, tile=3).shape == (72, 120, 3)
    assert np.array_equal(img, shade_lit(maps, backend=backend))  # deterministic


@pytest.mark.numba
def test_numba_matches_numpy() -> None:
    if "numba" not in BACKENDS:
        pytest.skip("numba is not installed")
    rng = np.random.default_rng(7)
    cases = [
        (random_maps(rng, 48, 32), 1),
        (random_maps(rng, 33, 50), 2),
        (matloom.evaluate(PROGRAM, 64, 64), 1),
    ]
    for maps, tile in cases:
        fast = shade_lit(maps, backend="numba", tile=tile).astype(np.int16)
        slow = shade_lit(maps, backend="numpy", tile=tile).astype(np.int16)
        diff = np.abs(fast - slow)
        # float rounding (fast-math, FMA) can tip a texel on a checker or light-box edge
        assert np.count_nonzero(diff > 1) <= 2e-3 * diff.size
        assert np.count_nonzero(diff) <= 5e-3 * diff.size


def test_refuses_bad_arguments() -> None:
    maps = make_maps(8)
    with pytest.raises(ValueError, match="tile"):
        shade_lit(maps, tile=0)
    with pytest.raises(ValueError, match="shader"):
        shade_lit(maps, backend="cuda")
    arrays = maps.arrays()
    arrays["roughness"] = arrays["roughness"][:4]
    with pytest.raises(ValueError, match="roughness"):
        shade_lit(MaterialMaps.from_arrays(arrays))


def test_every_map_is_read_except_the_height() -> None:
    """A new channel must be given a meaning in the lit shading (or listed as not read)."""
    assert NOT_READ == {LAYOUT["height"].field}


# --- what the channels do ------------------------------------------------------------------


def test_metal_reflects_the_studio_and_differs_from_dielectric() -> None:
    colour = (0.8, 0.05, 0.05)
    metal = shade_lit(make_maps(basecolor_linear=colour, metallic=1.0, roughness=0.1))
    plastic = shade_lit(make_maps(basecolor_linear=colour, metallic=0.0, roughness=0.1))
    assert np.abs(metal.astype(int) - plastic).mean() > 15
    chrome = luminance(shade_lit(make_maps(basecolor_linear=0.9, metallic=1.0, roughness=0.05)))
    assert chrome.max() - chrome.min() > 150  # not mid-grey: bright band and dark ground
    assert chrome[:, N // 2].argmax() < N // 2  # the softbox is reflected in the upper half
    rows = chrome.mean(axis=1)
    assert rows[: N // 2].mean() > rows[N // 2 :].mean() + 40  # sky above, ground below


def test_roughness_blurs_the_reflection() -> None:
    steps = {}
    for rough in (0.05, 0.5):
        img = shade_lit(make_maps(basecolor_linear=0.9, metallic=1.0, roughness=rough))
        steps[rough] = np.abs(np.diff(luminance(img)[:, N // 2])).max()
    assert steps[0.05] > 4 * steps[0.5]


@pytest.mark.parametrize("channel", ["coat", "sheen", "transmission"])
def test_layer_channels_change_only_where_nonzero(channel: str) -> None:
    base = {"normal": dome_normals(), "basecolor_linear": (0.3, 0.1, 0.05), "roughness": 0.6}
    left = np.zeros((N, N), np.float32)
    left[:, : N // 2] = 1.0
    without = shade_lit(make_maps(**base)).astype(int)
    with_left = shade_lit(make_maps(**base, **{channel: left})).astype(int)
    diff = np.abs(with_left - without)
    assert diff[:, N // 2 :].max() == 0
    assert diff[:, : N // 2].mean() > 4


def test_transmission_shows_the_tinted_checker_backdrop() -> None:
    glass = luminance(
        shade_lit(make_maps(basecolor_linear=(0.9, 0.9, 0.9), transmission=1.0, roughness=0.0))
    )
    cell = N // 8  # 8 checker cells across the swatch
    centres = glass[cell // 2 :: cell, cell // 2 :: cell]
    odd = (np.add.outer(np.arange(8), np.arange(8)) % 2).astype(bool)
    assert abs(centres[odd].mean() - centres[~odd].mean()) > 60
    red = shade_lit(make_maps(basecolor_linear=(0.9, 0.1, 0.1), transmission=1.0, roughness=0.0))
    assert red[..., 0].mean() > red[..., 1].mean() + 30  # tinted by the base colour
    frosted = luminance(shade_lit(make_maps(basecolor_linear=0.9, transmission=1.0, roughness=0.6)))
    assert frosted.std() < 0.5 * glass.std()  # roughness blurs the backdrop


def test_uncovered_texels_show_the_backdrop_whatever_the_material() -> None:
    a = shade_lit(make_maps(alpha=0.0, metallic=1.0, basecolor_linear=(1, 0.5, 0)))
    b = shade_lit(make_maps(alpha=0.0, coat=1.0, sheen=1.0, emissive_linear=(3.0, 0.0, 0.0)))
    assert np.array_equal(a, b)


def test_anisotropy_stretches_the_reflection_across_its_angle() -> None:
    """The angle is the brushing direction: the image varies little across it (the stretch,
    as on real grooves: tests/render/test_lit_brushing.py) and much along it."""
    lum = {}
    for angle in (0.0, 45.0, 90.0, 135.0):
        maps = make_maps(
            basecolor_linear=0.9, metallic=1.0, roughness=0.3, anisotropy=1.0,
            anisotropy_angle=angle,
        )  # fmt: skip
        lum[angle] = luminance(shade_lit(maps))

    def change(img: np.ndarray, drow: int, dcol: int) -> float:
        """Mean change to the neighbour one row down (drow = 1) or up (-1) and dcol right."""
        a = img[max(drow, 0) : N + min(drow, 0), max(dcol, 0) : N + min(dcol, 0)]
        b = img[max(-drow, 0) : N + min(-drow, 0), max(-dcol, 0) : N + min(-dcol, 0)]
        return float(np.abs(a - b).mean())

    # image steps along each brushing direction: +x is (0, 1); +y (up) is one row up, (-1, 0)
    along = {0.0: (0, 1), 45.0: (-1, 1), 90.0: (-1, 0), 135.0: (-1, -1)}
    across = {0.0: (-1, 0), 45.0: (1, 1), 90.0: (0, 1), 135.0: (-1, 1)}
    for angle, img in lum.items():
        assert 4 * change(img, *across[angle]) < change(img, *along[angle]), angle


def test_angle_without_anisotropy_changes_nothing() -> None:
    plain = shade_lit(make_maps(metallic=1.0, roughness=0.3))
    assert np.array_equal(
        plain, shade_lit(make_maps(metallic=1.0, roughness=0.3, anisotropy_angle=45))
    )


def test_relief_is_lit_from_the_upper_left() -> None:
    img = luminance(shade_lit(make_maps(normal=dome_normals(), roughness=0.8)))
    upper_left, lower_right = img[N // 2 - 12, N // 2 - 12], img[N // 2 + 12, N // 2 + 12]
    assert upper_left > lower_right + 30


def test_key_light_can_be_replaced() -> None:
    maps = make_maps(normal=dome_normals(), roughness=0.4)
    studio = Light(lit_model.KEY_AZIMUTH_DEG, lit_model.KEY_ELEVATION_DEG)
    assert np.array_equal(shade_lit(maps), shade_lit(maps, key_light=studio))
    assert not np.array_equal(shade_lit(maps), shade_lit(maps, key_light=Light(-45.0, 25.0)))


# --- API and CLI ---------------------------------------------------------------------------


def test_preview_layouts() -> None:
    maps = matloom.evaluate(PROGRAM, 32, 32)
    flat = preview(PROGRAM, 32)
    assert np.array_equal(flat, shade(maps))  # the default stays the reference's swatch
    assert np.array_equal(preview(PROGRAM, 32, layout="flat"), flat)
    lit = preview(PROGRAM, 32, layout="lit")
    assert np.array_equal(lit, shade_lit(maps))
    assert np.array_equal(preview(PROGRAM, 32, layout="both"), np.concatenate([flat, lit], 1))
    tiled = preview(PROGRAM, 32, layout="both", tile=2)
    assert tiled.shape == (64, 128, 3)
    assert np.array_equal(tiled[:, 64:], shade_lit(maps, tile=2))
    with pytest.raises(ValueError, match="layout"):
        preview(PROGRAM, 32, layout="studio")  # type: ignore[arg-type]


def test_cli_preview_layout_both(tmp_path: Path) -> None:
    program = tmp_path / "p.mat"
    program.write_text(PROGRAM + "\n", encoding="utf-8")
    out = tmp_path / "both.png"
    args = ["preview", str(program), "-o", str(out), "--size", "24", "--layout", "both"]
    result = CliRunner().invoke(cli, [*args, "--tile", "2", "--light", "120,30"])
    assert result.exit_code == 0, result.output
    with Image.open(out) as image:
        assert image.size == (96, 48)
        img = np.asarray(image.convert("RGB"))
    maps = matloom.evaluate(PROGRAM, 24, 24)
    light = Light(120.0, 30.0)
    assert np.array_equal(img[:, :48], np.tile(shade(maps, light=light), (2, 2, 1)))
    assert np.array_equal(img[:, 48:], shade_lit(maps, key_light=light, tile=2))
    bad = CliRunner().invoke(cli, [*args[:-1], "studio"])
    assert bad.exit_code == 2 and "studio" in bad.output


# --- the layout notes ----------------------------------------------------------------------


def test_lit_note_states_the_studio_numbers() -> None:
    assert f"{lit_model.KEY_ELEVATION_DEG:g} degrees elevation" in LIT_LAYOUT_NOTE
    assert "upper left" in LIT_LAYOUT_NOTE and "height" in LIT_LAYOUT_NOTE


def test_flat_note_claims_hold_for_the_flat_shader() -> None:
    """What FLAT_LAYOUT_NOTE says the flat preview cannot show, checked on :func:`shade`."""
    elevation = math.degrees(math.asin(1 / math.sqrt(1.5)))
    assert f"elevation {elevation:.1f} degrees" in FLAT_LAYOUT_NOTE
    # transmission and uncovered areas: flat 50 % grey, whatever the colour
    glass = shade(make_maps(basecolor_linear=(0.9, 0.1, 0.1), transmission=1.0))
    assert np.all(glass == 128)
    assert np.all(shade(make_maps(alpha=0.0, metallic=1.0)) == 128)
    # a flat polished metal shows ambient only (0.2 x base colour) plus a tiny highlight
    chrome = shade(make_maps(basecolor_linear=0.9, metallic=1.0, roughness=0.0))
    assert chrome.max() - chrome.min() == 0 and chrome.max() < 0.25 * 255
    # coat: a near-uniform lift of at most 0.04
    lift = shade(make_maps(coat=1.0)).astype(int) - shade(make_maps())
    assert 0 < lift.max() <= math.ceil(0.04 * 255)
    # sheen on a flat surface: the base colour 10 % brighter, nothing else
    base = make_maps(basecolor_linear=0.2)
    assert "10 %" in FLAT_LAYOUT_NOTE
    sheen = shade(make_maps(basecolor_linear=0.2, sheen=1.0)).astype(int) - shade(base)
    assert 0 < sheen.max() <= math.ceil(0.1 * 255 * 0.49) + 1
