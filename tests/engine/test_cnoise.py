"""The compiled fBm loops (``_cnoise`` via ``noise_c``) against the pure-numpy loops, bit for bit.

``noise_numpy.FBM_LOOPS`` is the numpy code the C kernel must reproduce exactly (it is what the
numpy backend runs with ``MATLOOM_PURE_NUMPY=1``); the real ``opensimplex`` package is the
independent reference for the noise itself.  These tests FAIL (they do not skip) when the
extension was not built: CI always has a C compiler.
"""

from __future__ import annotations

import math
import subprocess
import sys
import threading
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from matloom.engine import backends
from matloom.engine.kernels import noise, noise_c, noise_numpy, opensimplex
from matloom.engine.session import Session
from matloom.ops import periodic

ROOT = Path(__file__).resolve().parents[2]
BASE: dict[str, Any] = dict(
    octaves=4, lacunarity=2.0, gain=0.5, freq_x=8.0, freq_y=8.0, to_01=False, seed=3
)
#: Coordinates that stress floor/int conversion: negative, huge, non-finite, signed zeros.
SPECIAL = [
    -1e19, -1e12, -1e6, -3.75, -1.0, -0.0, 0.0, 1e-310, 0.5, 1.0, 1e6, 1e12, 1e19,
    5e18, 2.0**63, -(2.0**63), 2.0**62, 1e300, -1e300, math.nan, math.inf, -math.inf,
]  # fmt: skip
SEEDS = [0, 1, -1, 7, 1145088217, 2**31 - 1, 2**63 - 1, -(2**63), 2**63 + 5, 2**64 + 3, 2**70]


def _opensimplex_package():  # type: ignore[no-untyped-def]
    """The opensimplex package the reference calls (pinned in the test extra: a missing or
    different version fails the cross-checks instead of skipping them)."""
    import opensimplex

    assert opensimplex.__version__ == "0.4.5.1", "the test extra pins opensimplex==0.4.5.1"
    return opensimplex


MISSING = (
    "matloom.engine.kernels._cnoise is not built or unusable: reinstall with a C compiler "
    "present (e.g. `pip install -e .` with gcc installed)"
)


@pytest.fixture(autouse=True)
def _require_extension() -> None:
    """Fail (not skip) every test here when the compiled kernel is missing."""
    if not noise_c.available():
        pytest.fail(MISSING)


def test_extension_is_built() -> None:
    assert noise_c.available(), MISSING


def assert_bit_identical(got: np.ndarray, expected: np.ndarray) -> None:
    """Same shape/dtype, NaN at the same places, every other value with the same 64 bits."""
    assert got.shape == expected.shape and got.dtype == expected.dtype == np.float64
    nan_got, nan_exp = np.isnan(got), np.isnan(expected)
    assert np.array_equal(nan_got, nan_exp)
    got_bits = np.ascontiguousarray(got).view(np.uint64)[~nan_got]
    exp_bits = np.ascontiguousarray(expected).view(np.uint64)[~nan_exp]
    mismatch = np.flatnonzero(got_bits != exp_bits)
    assert mismatch.size == 0, f"{mismatch.size} values differ, first at {mismatch[:5]}"


def c_fbm(x: np.ndarray, y: np.ndarray, **kw: Any) -> np.ndarray:
    """The fBm on the C extension's loops."""
    return noise.fbm(x, y, loops=noise_c.FBM_LOOPS, **kw)


def numpy_fbm(x: np.ndarray, y: np.ndarray, **kw: Any) -> np.ndarray:
    """The fBm on the pure-numpy loops."""
    return noise.fbm(x, y, loops=noise_numpy.FBM_LOOPS, **kw)


def check(x: np.ndarray, y: np.ndarray, **params: Any) -> np.ndarray:
    """C fBm == numpy fBm bit for bit on (x, y); returns the result."""
    kw = {**BASE, **params}
    with np.errstate(all="ignore"):  # overflow/0-division warnings of the numpy code
        expected = numpy_fbm(x, y, **kw)
        got = c_fbm(x, y, **kw)
    assert_bit_identical(got, expected)
    return got


def axes(width: int, height: int, dtype: type, lo: float = -1.3, hi: float = 2.2) -> tuple:
    """Pixel-centre axes x (1, W), y (H, 1) in ``dtype`` (y decreasing, like a View)."""
    span = dtype(hi - lo)
    x = (np.arange(width, dtype=dtype) + dtype(0.5)) * (span / dtype(width)) + dtype(lo)
    y = (np.arange(height, dtype=dtype) + dtype(0.5)) * (span / dtype(height)) + dtype(lo)
    return x[None, :], y[::-1].copy()[:, None]


def rotated(x: np.ndarray, y: np.ndarray, deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Full grids rotated by ``deg`` in the axes' dtype (no separable fast path)."""
    cos, sin = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return cos * x + sin * y, -sin * x + cos * y


# --- separable axes and rotated grids --------------------------------------------------------


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("shape", [(1, 1), (1, 97), (83, 1), (37, 53), (3, 300), (2, 513)])
def test_separable_axes(dtype: type, shape: tuple[int, int]) -> None:
    x, y = axes(shape[1], shape[0], dtype)
    assert check(x, y).shape == shape
    check(x, y, to_01=True, seed=91, freq_x=3.0, freq_y=11.0, lacunarity=2.7, gain=0.65)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("shape", [(1, 1), (1, 97), (83, 1), (37, 53), (17, 301)])
@pytest.mark.parametrize("deg", [37.0, -113.0])
def test_rotated_grids(dtype: type, shape: tuple[int, int], deg: float) -> None:
    gx, gy = rotated(*axes(shape[1], shape[0], dtype), deg)
    assert gx.dtype == gy.dtype == dtype and gx.shape == shape
    check(gx, gy, to_01=True)
    check(gx, gy, freq_x=-5.0, freq_y=40.0, octaves=6, seed=-12)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_work_split_over_threads(dtype: type, monkeypatch: pytest.MonkeyPatch) -> None:
    """Row slices (separable) and flat spans (grids) on several threads give the same bits."""
    monkeypatch.setattr(noise_c, "MIN_TEXELS_PER_THREAD", 7)
    monkeypatch.setattr(noise_c.os, "cpu_count", lambda: 3)
    x, y = axes(61, 29, dtype)
    assert noise_c._threads(61 * 29, 29) == 3
    check(x, y, octaves=5)
    check(*rotated(x, y, 21.0), octaves=5)


def test_mixed_and_unusual_layouts() -> None:
    """float32 x with float64 y, 1-D/0-D/3-D inputs, int inputs and empty outputs."""
    x32, y32 = axes(29, 23, np.float32)
    x64, y64 = axes(29, 23, np.float64)
    check(x32, y64)
    gx, _ = rotated(x32, y32, 21.0)
    _, gy = rotated(x64, y64, 21.0)
    check(gx, gy)  # grid with float32 x and float64 y
    check(x64[0], np.float64(0.25))  # 1-D x, scalar y
    check(np.float64(1.5), np.float64(-2.25))  # 0-D
    check(np.arange(5)[None, :], np.arange(4)[:, None])  # ints -> float64
    cube = np.linspace(-2.0, 3.0, 60).reshape(3, 4, 5)
    check(cube, cube[:, :1, :] * 0.5)  # 3-D broadcast
    check(np.zeros((1, 0)), np.zeros((4, 1)))
    check(np.zeros((0, 3)), np.zeros((0, 3)))


@pytest.mark.parametrize("octaves", range(1, 17))
@pytest.mark.parametrize("rotate", [False, True])
def test_octave_counts(octaves: int, rotate: bool) -> None:
    x, y = axes(41, 19, np.float32, -0.3, 1.9)
    if rotate:
        x, y = rotated(x, y, 63.0)
    check(x, y, octaves=octaves, freq_x=7.0, freq_y=7.0, to_01=octaves % 2 == 0)


@pytest.mark.parametrize(
    ("lacunarity", "gain"),
    [(2.0, 0.5), (1.87, 0.63), (3.1, -0.7), (0.5, 1.5), (2.0, 0.0), (2.0, -1.0), (1.0, 1.0)],
)
@pytest.mark.parametrize("to_01", [False, True])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_lacunarity_gain_variants(lacunarity: float, gain: float, to_01: bool, dtype: type) -> None:
    """Including gain -1 with 4 octaves: norm 0, so the result is +-inf or NaN everywhere."""
    x, y = axes(31, 27, dtype)
    kw = dict(lacunarity=lacunarity, gain=gain, to_01=to_01)
    check(x, y, **kw)
    check(*rotated(x, y, 11.0), **kw)


@pytest.mark.parametrize("seed", SEEDS)
def test_seeds(seed: int) -> None:
    x, y = axes(45, 13, np.float32)
    check(x, y, seed=seed)
    check(*rotated(x, y, 80.0), seed=seed, to_01=True)


# --- extreme coordinates -------------------------------------------------------------------------


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("freq", [1.0, 7.0, 1e-3])
def test_special_coordinates_separable(dtype: type, freq: float) -> None:
    """Every pair of special values (huge, +-0, NaN, inf) as separable axes."""
    with np.errstate(over="ignore"):
        vals = np.array(SPECIAL, dtype=dtype)
    for to_01 in (False, True):
        check(vals[None, :], vals[:, None], freq_x=freq, freq_y=freq, to_01=to_01, octaves=3)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_special_coordinates_grid(dtype: type) -> None:
    with np.errstate(over="ignore"):
        vals = np.array(SPECIAL, dtype=dtype)
    gx, gy = np.meshgrid(vals, vals[::-1])
    for freq in (1.0, 3.0):
        check(gx, gy, freq_x=freq, freq_y=-freq, octaves=2)


@pytest.mark.parametrize("scale", [1e6, 1e12, 1e15, 1e17, 1e19, 3e19])
def test_huge_coordinates_near_lattice(scale: float) -> None:
    """Huge coordinates whose rounding residues are 0 (attenuation > 0 at huge lattice points)."""
    base = np.array([-3.0, -1.0, 0.0, 1.0, 2.0, 7.0])
    x = (scale * base)[None, :]
    y = (scale * np.array([-2.0, 0.0, 1.0, 5.0]))[:, None]
    for freq in (1.0, 2.0, 7.0):
        check(x, y, freq_x=freq, freq_y=freq, octaves=3, to_01=False)
    check(x + y, x - y, freq_x=1.0, freq_y=1.0, octaves=1)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    coords=st.lists(st.tuples(st.floats(width=64), st.floats(width=64)), min_size=1, max_size=40),
    seed=st.integers(min_value=-(2**70), max_value=2**70),
    octaves=st.integers(min_value=1, max_value=6),
    freq=st.floats(min_value=-1e3, max_value=1e3),
    use_float32=st.booleans(),
)
def test_random_points_property(
    coords: list[tuple[float, float]], seed: int, octaves: int, freq: float, use_float32: bool
) -> None:
    """Arbitrary float64 pairs (any magnitude, NaN, inf) as flat grids, float64 or float32."""
    pts = np.array(coords, dtype=np.float64)
    if use_float32:
        with np.errstate(over="ignore"):
            pts = pts.astype(np.float32)
    check(pts[:, 0], pts[:, 1], seed=seed, octaves=octaves, freq_x=freq, freq_y=freq * 0.75)


# --- the real opensimplex package ----------------------------------------------------------------


def test_single_octave_matches_opensimplex_package() -> None:
    """octaves=1, freq 1, to_01=False: fBm = clip(0 + noise2 * FBM_SCALE * 1 / 1, -1, 1)."""
    package = _opensimplex_package()
    rng = np.random.default_rng(5)
    pts = np.concatenate([rng.uniform(-300.0, 300.0, (300, 2)), rng.normal(0.0, 2.0, (100, 2))])
    kw = dict(octaves=1, lacunarity=2.0, gain=0.5, freq_x=1.0, freq_y=1.0, to_01=False)
    for seed in (0, 77, 1145088217, -5):
        noise = package.OpenSimplex(seed)
        raw = np.array([noise.noise2(float(a), float(b)) for a, b in pts])
        expected = np.clip((0.0 + raw * opensimplex.FBM_SCALE * 1.0) / 1.0, -1.0, 1.0)
        assert_bit_identical(c_fbm(pts[:, 0], pts[:, 1], seed=seed, **kw), expected)


def test_constants_match_python_module() -> None:
    from matloom.engine.kernels import _cnoise

    assert _cnoise.STRETCH_CONSTANT2 == periodic.STRETCH_CONSTANT2
    assert _cnoise.SQUISH_CONSTANT2 == periodic.SQUISH_CONSTANT2
    assert _cnoise.NORM_CONSTANT2 == opensimplex.NORM_CONSTANT2
    assert _cnoise.FBM_SCALE == opensimplex.FBM_SCALE


# --- dispatch, import cost, threads ---------------------------------------------------------------


def test_numpy_backend_chooses_c_unless_pure_numpy(monkeypatch: pytest.MonkeyPatch) -> None:
    """The numpy backend runs the C loops unless MATLOOM_PURE_NUMPY=1 (read when a session is
    made), for single fields and seed batches alike; same numbers either way."""
    calls: list[int] = []
    real = noise_c.FBM_LOOPS

    def spy(*args: Any) -> None:
        calls.append(1)
        real.separable(*args)

    monkeypatch.setattr(noise_c, "FBM_LOOPS", replace(real, separable=spy))
    x, y = axes(23, 17, np.float32)
    monkeypatch.delenv("MATLOOM_PURE_NUMPY", raising=False)
    numpy_backend = backends.session_backend(Session.from_env(), "numpy")
    assert numpy_backend.fbm_loops is not None and numpy_backend.fbm_loops().name == "c"
    with_c = numpy_backend.fbm(x, y, **BASE)
    assert calls == [1]
    monkeypatch.setenv("MATLOOM_PURE_NUMPY", "1")
    pure_backend = backends.session_backend(Session.from_env(), "numpy")
    assert pure_backend.fbm_loops is not None and pure_backend.fbm_loops().name == "numpy"
    pure = pure_backend.fbm(x, y, **BASE)
    assert calls == [1]
    assert_bit_identical(with_c, pure)
    monkeypatch.setenv("MATLOOM_PURE_NUMPY", "0")
    kw = {k: v for k, v in BASE.items() if k != "seed"}
    backends.session_backend(Session.from_env(), "numpy").fbm_seed_batch(x, y, seeds=[1, 2], **kw)
    assert calls == [1, 1, 1]


def test_seed_batch_through_c_matches_numpy() -> None:
    x, y = axes(19, 11, np.float32)
    kw = {k: v for k, v in BASE.items() if k != "seed"}
    fast = backends.get_backend("numpy").fbm_seed_batch(x, y, seeds=[3, -4, 2**64], **kw)
    pure_backend = backends.get_backend("numpy", pure_numpy=True)
    pure = pure_backend.fbm_seed_batch(x, y, seeds=[3, -4, 2**64], **kw)
    assert fast.dtype == pure.dtype == np.float32
    assert np.array_equal(fast, pure)


def test_import_path_does_not_import_numba() -> None:
    """The numpy backend's fBm (C path) must stay cheap to import: no numba anywhere."""
    code = (
        "import sys, numpy as np\n"
        "from matloom.engine.backends import get_backend\n"
        "from matloom.engine.kernels import noise_c\n"
        "assert noise_c.available()\n"
        "x = np.linspace(0, 1, 8)[None, :]\n"
        "get_backend('numpy').fbm(x, x.T, octaves=3, lacunarity=2.0, gain=0.5, freq_x=7.0,"
        " freq_y=7.0, to_01=True, seed=1)\n"
        "assert 'numba' not in sys.modules, 'numba was imported'\n"
    )
    env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_concurrent_calls_in_threads() -> None:
    """The GIL is released in the loops: concurrent calls still give the sequential results."""
    x, y = axes(150, 90, np.float32)
    grids = [(x, y), rotated(x, y, 30.0)]
    expected = [c_fbm(gx, gy, **{**BASE, "seed": s}) for s in range(4) for gx, gy in grids]
    results: list[np.ndarray | None] = [None] * len(expected)

    def work(i: int) -> None:
        gx, gy = grids[i % 2]
        results[i] = c_fbm(gx, gy, **{**BASE, "seed": i // 2})

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(expected))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for got, want in zip(results, expected, strict=True):
        assert got is not None
        assert_bit_identical(got, want)


# --- argument validation of the raw module ---------------------------------------------------------


def _separable_args() -> list[Any]:
    perm = opensimplex.perm_from_seed(1)
    xs, ys, amps = np.zeros((2, 5)), np.zeros((2, 3)), np.ones(2)
    return [np.empty((3, 5)), xs, ys, amps, perm, (0, 0, 0), 2.0, True]


def test_raw_module_rejects_bad_arguments() -> None:
    from matloom.engine.kernels import _cnoise

    _cnoise.fbm_separable(*_separable_args())  # the valid call

    def fails(exc: type[Exception], index: int, value: Any, match: str) -> None:
        args = _separable_args()
        args[index] = value
        with pytest.raises(exc, match=match):
            _cnoise.fbm_separable(*args)

    fails(TypeError, 1, np.zeros((2, 5), dtype=np.float32), "xs has item format")
    fails(TypeError, 1, np.zeros((2, 10))[:, ::2], "xs must be a C-contiguous")
    fails(TypeError, 0, np.empty((3, 5)).copy().view(np.int64), "out has item format")
    read_only = np.empty((3, 5))
    read_only.setflags(write=False)
    fails(TypeError, 0, read_only, "out must be a C-contiguous writable")
    fails(TypeError, 4, np.arange(256, dtype=np.int32), "perm has item format")
    fails(ValueError, 4, np.arange(255, dtype=np.int64), "perm must hold 256")
    fails(ValueError, 4, np.arange(256, dtype=np.int64) + 1, "outside 0..255")
    fails(ValueError, 0, np.empty((3, 4)), "out must hold H \\* W")
    fails(ValueError, 3, np.ones(3), "divisible")
    fails(ValueError, 3, np.ones(0), "divisible")
    fails(TypeError, 1, [0.0] * 10, "xs must be a C-contiguous")

    out, grid = np.empty(6), np.zeros(6, dtype=np.float32)
    perm = opensimplex.perm_from_seed(1)
    good_freqs = np.ones(2)
    _cnoise.fbm_grid(out, grid, grid, good_freqs, good_freqs, np.ones(2), perm, (0, 0, 0), 2.0, 0)
    with pytest.raises(TypeError, match="freqs_x has item format"):
        _cnoise.fbm_grid(
            out, grid, grid, np.ones(2, np.float32), good_freqs, np.ones(2), perm, (0, 0, 0), 2.0, 0
        )
    with pytest.raises(ValueError, match="one frequency per octave"):
        _cnoise.fbm_grid(
            out, grid, grid, good_freqs, good_freqs, np.ones(3), perm, (0, 0, 0), 2.0, 0
        )
    with pytest.raises(ValueError, match="same number of items"):
        _cnoise.fbm_grid(
            out, grid[:5], grid, good_freqs, good_freqs, np.ones(2), perm, (0, 0, 0), 2.0, 0
        )
