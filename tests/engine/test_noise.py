"""Noise kernels (fBm, Worley) against the reference's parity fixtures, and backend agreement.

The fixture values in tests/data/parity/expressions.json were produced by the reference engine;
each fixture expression string is mapped to kernel keyword arguments by a small regex parse of
its ``name=value`` pairs (defaults as in the reference's function registry).
"""

from __future__ import annotations

import importlib
import json
import math
import os
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from matloom.engine.backends import Backend, get_backend, noise_kernels
from matloom.engine.kernels import noise_numpy
from matloom.engine.kernels.opensimplex import gradient_table, perm_from_seed, perms_for_seeds

ROOT = Path(__file__).resolve().parents[2]
EXPRESSIONS = ROOT / "tests" / "data" / "parity" / "expressions.json"
NOISE_CALL = re.compile(r"(fBm|Worley)\(([^()]*)\)")
SCALE_WRAP = re.compile(r"^Scale\(.*\),\s*([-\d.]+),\s*([-\d.]+)\)$")
ROTATE_WRAP = re.compile(r"^Rotate\(.*\),\s*([-\d.]+)\)$")
KWARG = re.compile(r"(\w+)\s*=\s*(\"[^\"]*\"|[-\w.]+)")
DISTANCES = ("euclidean", "manhattan", "chebyshev")
COMBINATIONS = ("F1", "F2", "F2-F1", "F2+F1")


def _opensimplex_package():  # type: ignore[no-untyped-def]
    """The opensimplex package the reference calls (pinned in the test extra: a missing or
    different version fails the cross-checks instead of skipping them)."""
    import opensimplex

    assert opensimplex.__version__ == "0.4.5.1", "the test extra pins opensimplex==0.4.5.1"
    return opensimplex


#: The numpy backend as shipped: its fBm runs the C extension's loops where they are built.
NUMPY = get_backend("numpy")
#: The numpy backend on the pure-numpy fBm loops (what ``MATLOOM_PURE_NUMPY=1`` selects).
PURE_NUMPY = replace(
    NUMPY, **noise_kernels(lambda: noise_numpy.FBM_LOOPS, noise_numpy.WORLEY_LOOPS)
)


@pytest.fixture(params=["numpy", "pure-numpy", "numba"])
def backend(request: pytest.FixtureRequest) -> Backend:
    """Each noise backend; the numba one is skipped when numba is not installed."""
    if request.param == "numba":
        return _numba()
    return PURE_NUMPY if request.param == "pure-numpy" else NUMPY


def _numba() -> Backend:
    pytest.importorskip("numba")
    return get_backend("numba")


# --- fixture expressions -----------------------------------------------------------------------


def _kernel_call(expr: str) -> tuple[str, dict[str, Any]]:
    """('fbm' | 'worley', kwargs) for the single noise call inside a fixture expression."""
    match = NOISE_CALL.search(expr)
    assert match, expr
    args = {k: v.strip('"') for k, v in KWARG.findall(match.group(2))}
    base = float(args.get("base_freq", 1.0))
    common = {
        "freq_x": float(args.get("base_freq_x", base)),
        "freq_y": float(args.get("base_freq_y", base)),
        "to_01": args.get("to_01", "False") == "True",
        "seed": int(args["seed"]),
    }
    if match.group(1) == "fBm":
        extra = {
            "octaves": int(args.get("octaves", 6)),
            "lacunarity": float(args.get("lacunarity", 2.0)),
            "gain": float(args.get("gain", 0.5)),
        }
        return "fbm", {**common, **extra}
    extra = {
        "distance": args.get("distance", "euclidean"),
        "combination": args.get("combination", "F1"),
    }
    return "worley", {**common, **extra}


def _transformed(expr: str, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Apply an outer Scale/Rotate of a fixture expression to the sample coordinates."""
    if scale := SCALE_WRAP.match(expr):
        return x / float(scale.group(1)), y / float(scale.group(2))
    if rotate := ROTATE_WRAP.match(expr):
        rad = math.radians(float(rotate.group(1)))
        cos, sin = math.cos(rad), math.sin(rad)
        return cos * x + sin * y, -sin * x + cos * y
    return x, y


def _fixture_cases() -> list[Any]:
    cases = []
    for entry in json.loads(EXPRESSIONS.read_text()):
        if not NOISE_CALL.search(entry["expr"]):
            continue
        for key, dtype in (("points", np.float64), ("points_f32_axes", np.float32)):
            for px, py, value in entry.get(key, []):
                label = f"{entry['expr']}@({px},{py}){'f32' if dtype is np.float32 else ''}"
                cases.append(pytest.param(entry["expr"], dtype, px, py, value, id=label))
    return cases


FIXTURE_CASES = _fixture_cases()


def test_fixture_set_covers_noise() -> None:
    """The parity file really holds fBm and Worley samples (guards the regex selection)."""
    exprs = {case.values[0] for case in FIXTURE_CASES}
    assert sum(e.count("fBm(") for e in exprs) >= 5
    assert sum(e.count("Worley(") for e in exprs) >= 9
    assert len(FIXTURE_CASES) >= 150


@pytest.mark.parametrize(("expr", "dtype", "px", "py", "value"), FIXTURE_CASES)
def test_matches_reference_fixture(
    backend: Backend, expr: str, dtype: type, px: float, py: float, value: float
) -> None:
    """Point samples of the reference (float64 axes, and float32 axes where they differ)."""
    name, kwargs = _kernel_call(expr)
    x, y = _transformed(expr, np.array([[px]], dtype=dtype), np.array([[py]], dtype=dtype))
    got = getattr(backend, name)(x, y, **kwargs)
    assert got.shape == (1, 1) and got.dtype == np.float64
    assert abs(got[0, 0] - value) <= max(1e-12, 1e-9 * abs(value)), (got[0, 0], value)


def test_numpy_scalar_parameters_behave_like_python_floats(backend: Backend) -> None:
    """np.float64 frequencies must not turn the float32 per-octave scaling into float64."""
    x32, y32 = np.array([[-0.3]], np.float32), np.array([[2.7]], np.float32)
    kw = dict(octaves=5, lacunarity=2.5, gain=0.6, to_01=True, seed=123)
    plain = backend.fbm(x32, y32, freq_x=2.0, freq_y=2.0, **kw)
    numpy_scalars = backend.fbm(
        x32,
        y32,
        freq_x=np.float64(2.0),
        freq_y=np.float64(2.0),
        **{**kw, "lacunarity": np.float64(2.5)},
    )
    assert numpy_scalars[0, 0] == plain[0, 0]


def test_fbm_origin_is_zero_and_known_value(backend: Backend) -> None:
    """fBm(seed=5): exactly 0 at the origin; the spec's example value at (0.1, 0.2)."""
    kw = dict(octaves=6, lacunarity=2.0, gain=0.5, freq_x=1.0, freq_y=1.0, to_01=False, seed=5)
    x = np.array([[0.0, 0.1]])
    y = np.array([[0.0], [0.2]])
    out = backend.fbm(x, y, **kw)
    assert out[0, 0] == 0.0
    assert abs(out[1, 1] - 0.36799036667171914) <= 1e-12


def test_float32_axes_scale_per_octave_in_float32(backend: Backend) -> None:
    """On float32 axes each octave's ``x * f_k`` is rounded to float32 (fixture value); merely
    rounding the input point to float32 and scaling in float64 gives a different number."""
    kw = dict(octaves=5, lacunarity=2.5, gain=0.6, freq_x=2.0, freq_y=2.0, to_01=True, seed=123)
    expected = 0.5991157701467497  # expressions.json, points_f32_axes at (-0.3, 2.7)
    x32, y32 = np.array([[-0.3]], np.float32), np.array([[2.7]], np.float32)
    got = backend.fbm(x32, y32, **kw)[0, 0]
    scaled_in_f64 = backend.fbm(x32.astype(np.float64), y32.astype(np.float64), **kw)[0, 0]
    assert abs(got - expected) <= 1e-12
    assert abs(scaled_in_f64 - expected) > 1e-9


# --- the OpenSimplex package itself (cross-check; pinned in the test extra) ---------------------------------


@pytest.mark.parametrize("seed", [0, 1, 5, 1145088217, 2**31 - 1, -3, 2**40 + 7])
def test_perm_matches_opensimplex_package(seed: int) -> None:
    """perm_from_seed == opensimplex 0.4.5.1's ``_perm``."""
    opensimplex = _opensimplex_package()
    assert np.array_equal(perm_from_seed(seed), opensimplex.OpenSimplex(seed)._perm)


def test_noise2_bit_exact_with_opensimplex_package() -> None:
    """Vectorised noise2 reproduces the package's scalar ``_noise2`` bit for bit."""
    internals = importlib.import_module("opensimplex.internals")
    rng = np.random.default_rng(1)
    pts = rng.uniform(-300.0, 300.0, size=(3000, 2))
    perm = perm_from_seed(77)
    expected = np.array([internals._noise2(float(a), float(b), perm) for a, b in pts])
    assert np.array_equal(noise_numpy.noise2(pts[:, 0], pts[:, 1], perm), expected)


def test_perm_is_permutation_and_gradient_table_consistent() -> None:
    """Structural checks that hold whatever the seed."""
    for seed in (0, 9, 123456789):
        perm = perm_from_seed(seed)
        assert sorted(perm.tolist()) == list(range(256))
        table = gradient_table(seed)
        a, b = 37, 201
        assert table[(a << 8) | b] == (perm[(perm[a] + b) & 255] & 14) >> 1


def test_vectorised_perms_match_scalar_rule() -> None:
    """perms_for_seeds (vectorised over seeds) == perm_from_seed, including wrap-around seeds."""
    seeds = [0, 1, 5, -1, 2**31 - 1, 2**63 - 1, -(2**63), 2**64 + 5, 2**70 + 3, 1145088217]
    table = perms_for_seeds(seeds)
    for row, seed in zip(table, seeds, strict=True):
        assert np.array_equal(row, perm_from_seed(seed))


def test_fixed_point_batch_falls_back_for_extreme_gain(backend: Backend) -> None:
    """gain=-0.9 leaves no safe fixed-point scale: the batch still equals per-seed fBm."""
    x, y = _axes(9, 7, 0.0, 1.0)
    kw = dict(octaves=4, lacunarity=2.0, gain=-0.9, freq_x=5.0, freq_y=5.0, to_01=False)
    batch = backend.fbm_seed_batch(x, y, seeds=[2, 3], **kw)
    for s, seed in enumerate((2, 3)):
        assert np.max(np.abs(batch[s] - backend.fbm(x, y, seed=seed, **kw))) <= 1e-6


# --- numpy vs numba ---------------------------------------------------------------------------


def _axes(n_w: int, n_h: int, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """Reference-style float32 pixel-centre axes: x (1, W) and y (H, 1), y decreasing."""
    span = np.float32(hi - lo)
    x = (np.arange(n_w, dtype=np.float32) + np.float32(0.5)) * (span / np.float32(n_w)) + lo
    y = (np.arange(n_h, dtype=np.float32) + np.float32(0.5)) * (span / np.float32(n_h)) + lo
    return x[None, :], y[::-1].copy()[:, None]


def _rotated(x: np.ndarray, y: np.ndarray, deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Full (H, W) grids of coordinates rotated like the reference's Rotate (same dtype)."""
    rad = math.radians(deg)
    cos, sin = math.cos(rad), math.sin(rad)
    return cos * x + sin * y, -sin * x + cos * y


FBM_PARAMS = [
    dict(octaves=4, lacunarity=2.0, gain=0.5, freq_x=8.0, freq_y=8.0, to_01=False, seed=3),
    dict(octaves=3, lacunarity=2.7, gain=0.65, freq_x=3.0, freq_y=11.0, to_01=True, seed=91),
    dict(octaves=1, lacunarity=2.0, gain=0.5, freq_x=-5.0, freq_y=40.0, to_01=False, seed=0),
]


@pytest.mark.parametrize("params", FBM_PARAMS)
@pytest.mark.parametrize("rotate", [False, True])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_fbm_numba_matches_numpy(params: dict[str, Any], rotate: bool, dtype: type) -> None:
    nb = _numba()
    x, y = _axes(83, 61, -1.3, 2.2)
    x, y = x.astype(dtype), y.astype(dtype)
    if rotate:
        x, y = _rotated(x, y, 37.0)
    expected = NUMPY.fbm(x, y, **params)
    got = nb.fbm(x, y, **params)
    assert got.shape == expected.shape == (61, 83)
    assert np.max(np.abs(got - expected)) <= 1e-12


@pytest.mark.parametrize("distance", DISTANCES)
@pytest.mark.parametrize("combination", COMBINATIONS)
@pytest.mark.parametrize("rotate", [False, True])
def test_worley_numba_matches_numpy(distance: str, combination: str, rotate: bool) -> None:
    nb = _numba()
    x, y = _axes(57, 45, -0.7, 1.9)
    if rotate:
        x, y = _rotated(x, y, -23.0)
    for to_01 in (False, True):
        kw = dict(
            distance=distance,
            combination=combination,
            freq_x=4.5,
            freq_y=-3.0,
            to_01=to_01,
            seed=12345,
        )
        expected = NUMPY.worley(x, y, **kw)
        got = nb.worley(x, y, **kw)
        assert got.shape == expected.shape == (45, 57)
        assert np.max(np.abs(got - expected)) <= 1e-12


def test_worley_hash_path_for_huge_cell_box() -> None:
    """Beyond the feature-table budget numba hashes per pixel; still equal to numpy."""
    nb = _numba()
    x, y = _axes(64, 64, 0.0, 1.0)
    kw = dict(
        distance="euclidean", combination="F2-F1", freq_x=1.0e4, freq_y=1.0e4, to_01=False, seed=8
    )
    assert np.max(np.abs(nb.worley(x, y, **kw) - NUMPY.worley(x, y, **kw))) <= 1e-12


def test_shapes_and_broadcasting(backend: Backend) -> None:
    """(1,W)x(H,1), 1-D x with (H,1) y, full grids and mixed forms give broadcast shapes."""
    fkw = dict(octaves=2, lacunarity=2.0, gain=0.5, freq_x=3.0, freq_y=3.0, to_01=True, seed=4)
    wkw = dict(distance="manhattan", combination="F1", freq_x=3.0, freq_y=3.0, to_01=True, seed=4)
    x, y = _axes(7, 5, 0.0, 1.0)
    gx, gy = np.broadcast_arrays(x, y)
    for fn, kw in ((backend.fbm, fkw), (backend.worley, wkw)):
        sep = fn(x, y, **kw)
        assert sep.shape == (5, 7)
        assert np.array_equal(fn(x[0], y, **kw), sep)
        # full grids scale each octave in float64 (the reference's per-cell kernel), separable
        # float32 axes in float32: a grid equals the separable result on float64 axes
        wide = fn(x.astype(np.float64), y.astype(np.float64), **kw)
        assert np.array_equal(fn(gx.copy(), gy.copy(), **kw), wide)
        assert np.array_equal(fn(gx.copy(), y, **kw), wide)
        if fn is backend.worley:  # Worley widens first on both layouts
            assert np.array_equal(wide, sep)
        assert fn(np.float32(0.3), np.float32(0.4), **kw).shape == ()
        assert fn(np.zeros((0, 3), np.float32), np.zeros((0, 1), np.float32), **kw).shape == (0, 3)


def test_non_finite_coordinates(backend: Backend) -> None:
    """NaN/inf never crash; fBm gives 0 (every attenuation test fails), Worley F1 inf."""
    x = np.array([[np.nan, np.inf, 0.25]])
    y = np.array([[0.5]])
    f = backend.fbm(
        x, y, octaves=3, lacunarity=2.0, gain=0.5, freq_x=2.0, freq_y=2.0, to_01=False, seed=1
    )
    assert f[0, 0] == 0.0 and f[0, 1] == 0.0 and np.isfinite(f[0, 2])
    w = backend.worley(
        x, y, distance="euclidean", combination="F1", freq_x=2.0, freq_y=2.0, to_01=False, seed=1
    )
    assert np.isinf(w[0, 0]) and np.isinf(w[0, 1]) and np.isfinite(w[0, 2])
    w01 = backend.worley(
        x, y, distance="euclidean", combination="F2-F1", freq_x=2.0, freq_y=2.0, to_01=True, seed=1
    )
    assert np.isnan(w01[0, 0])


def test_invalid_arguments(backend: Backend) -> None:
    x, y = _axes(4, 4, 0.0, 1.0)
    with pytest.raises(ValueError):
        backend.fbm(
            x, y, octaves=0, lacunarity=2.0, gain=0.5, freq_x=1.0, freq_y=1.0, to_01=False, seed=1
        )
    with pytest.raises(ValueError):
        backend.worley(
            x, y, distance="cosine", combination="F1", freq_x=1.0, freq_y=1.0, to_01=False, seed=1
        )
    with pytest.raises(ValueError):
        backend.worley(
            x,
            y,
            distance="euclidean",
            combination="F3",
            freq_x=1.0,
            freq_y=1.0,
            to_01=False,
            seed=1,
        )


# --- seed batches -----------------------------------------------------------------------------


@pytest.mark.parametrize("rotate", [False, True])
@pytest.mark.parametrize("to_01", [False, True])
def test_fbm_seed_batch_matches_per_seed(backend: Backend, rotate: bool, to_01: bool) -> None:
    x, y = _axes(40, 33, 0.0, 2.0)
    if rotate:
        x, y = _rotated(x, y, 15.0)
    seeds = [0, 1, 891377204, 2**31 - 1, 77]
    kw = dict(octaves=4, lacunarity=2.0, gain=0.5, freq_x=30.0, freq_y=30.0, to_01=to_01)
    batch = backend.fbm_seed_batch(x, y, seeds=seeds, **kw)
    assert batch.shape == (5, 33, 40) and batch.dtype == np.float32
    for s, seed in enumerate(seeds):
        assert np.max(np.abs(batch[s] - backend.fbm(x, y, seed=seed, **kw))) <= 1e-6


@pytest.mark.parametrize("distance", DISTANCES)
@pytest.mark.parametrize("rotate", [False, True])
def test_worley_seed_batch_matches_per_seed(backend: Backend, distance: str, rotate: bool) -> None:
    x, y = _axes(36, 29, -0.5, 1.5)
    if rotate:
        x, y = _rotated(x, y, 60.0)
    seeds = [3, 4, 1007923142]
    for combination in COMBINATIONS:
        kw = dict(
            distance=distance,
            combination=combination,
            freq_x=5.0,
            freq_y=6.0,
            to_01=combination == "F2",
        )
        batch = backend.worley_seed_batch(x, y, seeds=seeds, **kw)
        assert batch.shape == (3, 29, 36) and batch.dtype == np.float32
        for s, seed in enumerate(seeds):
            expected = backend.worley(x, y, seed=seed, **kw).astype(np.float32)
            assert np.array_equal(batch[s], expected)


def test_numba_batch_matches_numpy_batch() -> None:
    nb = _numba()
    x, y = _axes(48, 48, 0.0, 2.0)
    kw = dict(
        octaves=5,
        lacunarity=2.0,
        gain=0.5,
        freq_x=35.0,
        freq_y=35.0,
        to_01=True,
        seeds=list(range(20)),
    )
    diff = nb.fbm_seed_batch(x, y, **kw) - NUMPY.fbm_seed_batch(x, y, **kw)
    assert np.max(np.abs(diff)) <= 1e-6


# --- numba cache fallback ---------------------------------------------------------------------

_NO_CACHE_SCRIPT = """
import numpy as np
from numba.core import caching
caching.CacheImpl._locator_classes = []  # as if no cache directory were writable
from matloom.engine.backends import get_backend
from matloom.engine.kernels import noise_numba
assert type(noise_numba._fbm_separable_kernel._cache).__name__ == "NullCache"  # fell back
x = np.linspace(0, 1, 9, dtype=np.float32)[None, :]
y = np.linspace(0, 1, 7, dtype=np.float32)[:, None]
kw = dict(octaves=2, lacunarity=2.0, gain=0.5, freq_x=3.0, freq_y=3.0, to_01=False, seed=2)
assert np.array_equal(get_backend("numba").fbm(x, y, **kw), get_backend("numpy").fbm(x, y, **kw))
print("ok")
"""


def test_numba_works_without_writable_cache() -> None:
    """numba raises at decoration when no cache locator works; we fall back to no caching."""
    _numba()
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    result = subprocess.run(
        [sys.executable, "-c", _NO_CACHE_SCRIPT],
        capture_output=True,
        text=True,
        env=env,
        cwd=ROOT,
        timeout=600,
        check=False,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.strip().endswith("ok")


def test_warm_up_runs() -> None:
    """The CLI warm-up entry point compiles/loads every kernel without error."""
    _numba()
    from matloom.engine.kernels import noise_numba

    noise_numba.warm_up(include_batch=True)
