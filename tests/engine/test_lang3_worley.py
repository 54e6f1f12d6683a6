"""Language 3 of Worley: ``smoothness=s``, the smooth minimum of the feature-point distances in
place of F1, against the direct formula (every feature point of the 5 x 5 block, numpy's exp and
log), on every backend with the same bits; s = 0 is today's output bit for bit; no crease at
the cell borders; tileable output repeats."""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.kernels.noise_numpy import worley_hash
from matloom.engine.kernels.opensimplex import worley_seed_term

BACKENDS = [b for b in ("numpy", "numba") if b in available_backends()]
METRICS = ("euclidean", "manhattan", "chebyshev")


def _worley(backend: str, x: np.ndarray, y: np.ndarray, **kw: object) -> np.ndarray:
    args = dict(distance="euclidean", combination="F1", freq_x=3.0, freq_y=3.0, to_01=False)
    return get_backend(backend).worley(x, y, seed=5, **{**args, **kw})


def _direct(u: np.ndarray, v: np.ndarray, s: float, distance: str) -> tuple[np.ndarray, ...]:
    """(F1, smooth F1, F2) at flat cell coordinates from the 25 points around each sample."""
    term = worley_seed_term(5)
    cu, cv = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
    ds = []
    for ox in range(-2, 3):
        for oy in range(-2, 3):
            cx, cy = cu + ox, cv + oy
            du = u - (cx + worley_hash(cx, cy, term, 0))
            dv = v - (cy + worley_hash(cx, cy, term, 1))
            if distance == "euclidean":
                ds.append(np.hypot(du, dv))
            elif distance == "manhattan":
                ds.append(np.abs(du) + np.abs(dv))
            else:
                ds.append(np.maximum(np.abs(du), np.abs(dv)))
    d = np.sort(np.array(ds), axis=0)
    f1 = d[0]
    smooth = f1 - s * np.log(np.exp(-(d - f1) / s).sum(axis=0))
    return f1, smooth, d[1]


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distance", METRICS)
def test_smooth_f1_matches_the_formula(backend: str, distance: str) -> None:
    x = np.linspace(-1.1, 2.3, 97)[None, :]
    y = np.linspace(-0.7, 1.9, 61)[:, None]
    s = 0.12
    f1, smooth, f2 = _direct(*(a.ravel() for a in np.broadcast_arrays(x * 3, y * 3)), s, distance)
    for combination, want in (("F1", smooth), ("F2-F1", f2 - smooth), ("F2+F1", f2 + smooth)):
        got = _worley(backend, x, y, distance=distance, combination=combination, smoothness=s)
        np.testing.assert_allclose(got.ravel(), np.maximum(want, 0.0), rtol=1e-12, atol=1e-12)
    assert (smooth <= f1).all() and (smooth >= f1 - s * np.log(25)).all()
    got_f2 = _worley(backend, x, y, distance=distance, combination="F2", smoothness=s)
    np.testing.assert_array_equal(
        got_f2, _worley(backend, x, y, distance=distance, combination="F2")
    )


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize(
    "kw",
    [{}, dict(combination="F2-F1", to_01=True), dict(output="cell_value"), dict(output="edge")],
)
def test_zero_smoothness_is_todays_worley(backend: str, kw: dict) -> None:
    x = np.linspace(-2, 2, 50, dtype=np.float32)[None, :]
    y = np.linspace(-1, 3, 40, dtype=np.float32)[:, None]
    base = _worley(backend, x, y, **kw)
    assert np.array_equal(base, _worley(backend, x, y, smoothness=0.0, **kw))
    if kw.get("output"):  # the other outputs ignore smoothness
        assert np.array_equal(base, _worley(backend, x, y, smoothness=0.2, **kw))


@pytest.mark.parametrize("backend", BACKENDS)
def test_no_crease_at_the_cell_borders(backend: str) -> None:
    """Along a line, F1's slope jumps at each border (a second difference of about the jump
    per step); the smooth F1's stay bounded by its curvature."""
    h = 1e-3
    x = np.arange(0.0, 3.0, h)[None, :]
    y = np.array([[0.37]])
    exact = _worley(backend, x, y)[0]
    smooth = _worley(backend, x, y, smoothness=0.1)[0]
    second = lambda f: np.abs(np.diff(f, 2)) / h  # noqa: E731 - slope change per step
    assert second(exact).max() > 2.0  # a kink: the slope turns within one step
    assert second(smooth).max() < 0.2  # curvature ~ freq^2 / s, times the step


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
@pytest.mark.parametrize("distance", METRICS)
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_backends_agree(distance: str, dtype: type) -> None:
    rng = np.random.default_rng(3)
    x = rng.uniform(-40, 40, (23, 31)).astype(dtype)
    y = rng.uniform(-40, 40, (23, 31)).astype(dtype)
    x[0, 0], y[1, 1] = np.nan, np.inf
    for kw in (
        dict(smoothness=0.05),
        dict(smoothness=0.3, combination="F2-F1", to_01=True),
        dict(smoothness=0.2, period=(1.0, 2.0)),
    ):
        a = _worley("numpy", x, y, distance=distance, **kw)
        b = _worley("numba", x, y, distance=distance, **kw)
        assert np.array_equal(a, b, equal_nan=True), kw
        sep_a = _worley("numpy", x[:1], y[:, :1], distance=distance, **kw)
        sep_b = _worley("numba", x[:1], y[:, :1], distance=distance, **kw)
        assert np.array_equal(sep_a, sep_b, equal_nan=True), kw


@pytest.mark.parametrize("backend", BACKENDS)
def test_smooth_worley_repeats_with_the_view(backend: str) -> None:
    src = "View(0, 0, 1, 1, tileable=True)\nMaterial(Layer(1).height(Worley(base_freq=3.2, seed=4, smoothness=0.2)))"
    assert not [d for d in matloom.check(src) if d.severity.name == "ERROR"]
    maps = matloom.evaluate(src, 64, 64, backend=backend)
    h = np.asarray(maps.height, np.float64)
    # the left and right (bottom and top) edges continue each other: compare the seam's jump
    # with the typical step between neighbouring texels
    step = np.abs(np.diff(h, axis=1)).max()
    assert np.abs(h[:, 0] - h[:, -1]).max() <= 1.5 * step
    assert np.abs(h[0] - h[-1]).max() <= 1.5 * np.abs(np.diff(h, axis=0)).max()


def test_canonical_text() -> None:
    plain = matloom.format("Material(Layer(1).height(Worley(base_freq=3, seed=1, smoothness=0)))")
    assert "Worley(base_freq=3, seed=1))" in plain
    kept = matloom.format("Material(Layer(1).height(Worley(base_freq=3, seed=1, smoothness=0.2)))")
    assert "smoothness=0.2" in kept
    bad = matloom.check("Material(Layer(1).height(Worley(seed=1, smoothness=0.9)))")
    assert any(d.severity.name == "ERROR" for d in bad)
