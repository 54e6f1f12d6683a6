"""Coverage culling (matloom.engine.cull): fBm computed only where a layer can see it.

Culled maps must equal the unculled fused maps and the numpy path bit for bit, including where
culling must be refused (channel values that could be NaN/inf over the placeholder).
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("numba")

from matloom.engine.backends import get_backend  # noqa: E402
from matloom.engine.cull import channel_bounds  # noqa: E402
from matloom.engine.evaluate import EvalStats, evaluate, prepare  # noqa: E402
from matloom.engine.grid import sample_axes  # noqa: E402
from matloom.engine.lazy import DeferredField, make_lazy  # noqa: E402
from matloom.engine.maps import View  # noqa: E402
from matloom.engine.schedules import banded as fused  # noqa: E402
from matloom.examples import example_text  # noqa: E402
from matloom.lang.random_program import random_program  # noqa: E402


def _fused(text: str, size: int, cull: bool) -> tuple[dict[str, np.ndarray], EvalStats]:
    program = prepare(text)
    view = View(*program.view_tuple)
    x, y = sample_axes(view, size, size)
    stats = EvalStats()
    maps = fused.evaluate_fused(program, x, y, view, get_backend("numba"), stats=stats, cull=cull)
    return maps.arrays(), stats


def _assert_same(a: dict[str, np.ndarray], b: dict[str, np.ndarray], label: str) -> None:
    for name, array in a.items():
        other = b[name]
        same = np.array_equal(array.view(np.uint32), other.view(np.uint32))
        assert same, f"{label}: {name} differs"


def _check(text: str, size: int = 96) -> EvalStats:
    culled, stats = _fused(text, size, cull=True)
    plain, _ = _fused(text, size, cull=False)
    _assert_same(culled, plain, "culled vs unculled")
    _assert_same(culled, evaluate(text, size, size, backend="numpy").arrays(), "culled vs numpy")
    return stats


def test_tile_program_culls_the_grout_noise_and_keeps_every_map() -> None:
    stats = _check(example_text("black_ceramic_tiles"), 128)
    assert stats.noise_texels == 3 * 128 * 128
    share = stats.noise_texels_computed / stats.noise_texels
    assert share < 0.8, share  # the grout noise is computed in the mortar lines only


TOP_FBM = "fBm(octaves=3, base_freq=9, to_01=True, seed=5)"
BRICK = "Bricks(brick_width=0.5, brick_height=0.25, mortar=0.1, feather=0.02)"


@pytest.mark.parametrize(
    ("channel", "culled"),
    [
        (f"roughness({TOP_FBM} * 0.5 + 0.1)", True),
        (f"basecolor(200 * {TOP_FBM}, 10, Min({TOP_FBM}, 0.3) * 255)", True),
        (f"roughness(Sqrt({TOP_FBM} - 0.5))", False),  # NaN below 0.5: must not cull
        (f"roughness(1 / ({TOP_FBM} - 0.5))", False),  # unbounded near 0.5
        # a divisor is needed everywhere (the zero-division count), so it is never deferred
        (f"ior(1 / ({TOP_FBM} + 0.5))", False),
        (f"ior(({TOP_FBM} + 0.5) / 4 + 1)", True),
        (f"roughness(Threshold({TOP_FBM}, below_at=0.4, below_to=0))", False),
        (f"height({TOP_FBM} * 0.1)", True),  # gated by alpha, any value is fine
        (f"emissive(255, 128, 0, {TOP_FBM} * 4)", True),
    ],
)
def test_gated_channels_cull_only_when_provably_exact(channel: str, culled: bool) -> None:
    text = (
        "View(0, 0, 2, 2)\nMaterial(\n  Layer(1).basecolor(90, 90, 90).roughness(0.5),\n"
        f"  Layer({BRICK}).{channel}\n)"
    )
    stats = _check(text)
    computed = stats.noise_texels_computed < stats.noise_texels
    assert computed == culled, (channel, stats)


def test_bottom_layer_noise_is_computed_where_the_top_layer_leaves_gaps() -> None:
    text = (
        "View(0, 0, 3, 3)\nMaterial(\n"
        "  Layer(1).basecolor(40 + fBm(octaves=4, base_freq=30, to_01=True, seed=3) * 12, 40, 40)"
        ".roughness(fBm(octaves=2, base_freq=5, seed=9) * 0.2 + 0.5),\n"
        f"  Layer(Rotate({BRICK}, degrees=17)).basecolor(180, 20, 20).roughness(0.3)\n)"
    )
    stats = _check(text, 120)
    assert stats.noise_texels_computed < stats.noise_texels


def test_noise_under_a_rotation_is_culled_on_the_grid_kernel() -> None:
    text = (
        "View(0, 0, 2, 2)\nMaterial(\n"
        "  Layer(1).basecolor(Rotate(fBm(octaves=5, base_freq=20, to_01=True, seed=1), "
        "degrees=40) * 255, 10, 10),\n"
        f"  Layer({BRICK}).basecolor(10, 200, 10)\n)"
    )
    stats = _check(text, 100)
    assert stats.noise_texels_computed < stats.noise_texels


def test_noise_in_alpha_is_always_computed_in_full() -> None:
    text = (
        "View(0, 0, 2, 2)\nMaterial(\n  Layer(1).basecolor(90, 90, 90),\n"
        f"  Layer({TOP_FBM}).basecolor(255 * {TOP_FBM}, 0, 0)\n)"
    )
    stats = _check(text)
    assert stats.noise_texels_computed == stats.noise_texels


def _long_alpha(ops: int) -> tuple[str, str]:
    """(Defines, alpha): a coverage of about ``ops`` element-wise operations on a pattern, 0 in
    its joints (a mask that costs that many full-size numpy passes to materialise), as chains
    of 10 Defines (the nesting limit) joined by Min."""
    lines, ends = [], []
    for c in range(max(1, ops // 20)):
        lines.append(f"Define(c{c}_0, ({BRICK} * {1 + c / 100}))")
        steps = min(10, ops // 2)
        for k in range(1, steps + 1):
            lines.append(f"Define(c{c}_{k}, ((c{c}_{k - 1} * 0.99) * 1.01))")
        ends.append(f"c{c}_{steps}")
    alpha = ends[0] if len(ends) == 1 else f"Min({', '.join(ends)})"
    return "\n".join(lines), f"Clamp({alpha})"


@pytest.mark.parametrize(("ops", "culled"), [(4, True), (120, False)])
def test_noise_is_culled_only_when_the_masks_cost_less_than_it_saves(ops, culled) -> None:  # noqa: ANN001
    # a 2-octave noise under a coverage of ``ops`` operations: the masks are worth building
    # for a short coverage, not for a long one (cull.MASK_OPS_PER_OCTAVE); the maps are the
    # unculled ones either way
    defines, alpha = _long_alpha(ops)
    text = (
        f"View(0, 0, 2, 2)\n{defines}\nMaterial(\n  Layer(1).basecolor(90, 90, 90),\n"
        f"  Layer({alpha}).roughness(fBm(octaves=2, base_freq=9, to_01=True, seed=5)"
        " * 0.5 + 0.1)\n)"
    )
    stats = _check(text)
    assert (stats.noise_texels_computed < stats.noise_texels) == culled, stats


@pytest.mark.slow
def test_random_programs_culled_equal_unculled() -> None:
    for seed in range(60):
        text = random_program(seed=seed, layers=3, defines=3)
        culled, _ = _fused(text, 48, cull=True)
        plain, _ = _fused(text, 48, cull=False)
        _assert_same(culled, plain, f"random program {seed}")


def test_masked_fbm_kernel_matches_dense_values() -> None:
    rng = np.random.default_rng(7)
    kw = dict(octaves=6, lacunarity=2.1, gain=0.45, freq_x=13.0, freq_y=11.0, to_01=False)
    for dtype in (np.float64, np.float32):
        x = np.linspace(-3, 5, 173, dtype=dtype)[None, :]
        y = np.linspace(4, -2, 61, dtype=dtype)[:, None]
        grid = (dtype(0.6) * x + dtype(0.8) * y, dtype(0.6) * y - dtype(0.8) * x)
        for cx, cy in ((x, y), grid):
            dense = get_backend("numba").fbm(cx, cy, seed=11, **kw)
            mask = rng.random(dense.shape) < 0.4
            mask[5] = True  # a full row
            mask[6] = False  # an empty row
            masked = get_backend("numba").fbm_masked(cx, cy, mask, fill=0.25, seed=11, **kw)
            assert np.array_equal(masked[mask], dense[mask])
            assert np.all(masked[~mask] == 0.25)


def test_channel_bounds_interval_rules() -> None:
    deferred = DeferredField(lambda mask: np.zeros((2, 2)), (2, 2), 0.0, 1.0, True)
    memo: dict = {}
    assert channel_bounds(make_lazy("*", deferred, np.float64(12)), memo) == (0.0, 12.0)
    assert channel_bounds(make_lazy("-", np.float64(1), deferred), {}) == (0.0, 1.0)
    assert channel_bounds(make_lazy("sqrt", make_lazy("-", deferred, 0.5)), {}) is None
    assert channel_bounds(make_lazy("/", 1.0, deferred), {}) is None
    assert channel_bounds(make_lazy("/", 1.0, make_lazy("+", deferred, 1.0)), {}) == (0.5, 1.0)
    assert channel_bounds(np.array([[1.0, np.nan]]), {}) is None
    assert channel_bounds(np.array([[1.0, np.inf]]), {}) is None
    assert channel_bounds(make_lazy("*", deferred, np.float64(1e38)), {}) is None
    nan_coords = DeferredField(lambda mask: np.zeros((2, 2)), (2, 2), 0.0, 1.0, False)
    assert channel_bounds(make_lazy("+", nan_coords, 1.0), {}) is None
