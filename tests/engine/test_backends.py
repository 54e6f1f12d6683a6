"""The Backend table (matloom.engine.backends) and the noise dispatch it binds
(matloom.engine.kernels.noise): one plan, then a backend's loops."""

from __future__ import annotations

import math
from dataclasses import fields, replace
from typing import Any

import numpy as np
import pytest

from matloom.engine.backends import (
    Backend,
    available_backends,
    get_backend,
    noise_kernels,
    session_backend,
)
from matloom.engine.kernels import noise, noise_c, noise_numpy
from matloom.engine.session import Session

FBM: dict[str, Any] = dict(octaves=3, lacunarity=2.0, gain=0.5, freq_x=5.0, freq_y=4.0)
WORLEY: dict[str, Any] = dict(distance="manhattan", combination="F2-F1", freq_x=3.0, freq_y=2.0)


def _axes(dtype: type = np.float32) -> tuple[np.ndarray, np.ndarray]:
    x = np.linspace(-1.0, 2.0, 13, dtype=dtype)[None, :]
    y = np.linspace(1.5, -0.5, 7, dtype=dtype)[:, None]
    return x, y


def _rotated(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    c, s = x.dtype.type(math.cos(0.5)), x.dtype.type(math.sin(0.5))
    return c * x + s * y, c * y - s * x


def test_every_backend_fills_every_kernel() -> None:
    names = available_backends()
    assert "numpy" in names
    for name in names:
        backend = get_backend(name)
        assert backend.name == name
        for f in fields(Backend):
            value = getattr(backend, f.name)
            if f.name not in ("name", "fused", "fbm_masked"):
                assert callable(value), (name, f.name)
        assert backend.fbm_loops is not None
        assert (backend.fbm_masked is not None) == backend.fbm_loops().masks


def test_numpy_backend_runs_the_c_loops_where_built(monkeypatch: pytest.MonkeyPatch) -> None:
    """MATLOOM_PURE_NUMPY=1 is read when a session is made: that session's numpy backend runs
    the pure-numpy loops."""
    monkeypatch.delenv("MATLOOM_PURE_NUMPY", raising=False)
    loops = session_backend(Session.from_env(), "numpy").fbm_loops
    assert loops is not None and loops is get_backend("numpy").fbm_loops
    assert loops().name == ("c" if noise_c.available() else "numpy")
    monkeypatch.setenv("MATLOOM_PURE_NUMPY", "1")
    assert loops().name == ("c" if noise_c.available() else "numpy")  # a made session keeps it
    pure = session_backend(Session.from_env(), "numpy").fbm_loops
    assert pure is not None and pure() is noise_numpy.FBM_LOOPS
    assert get_backend("numpy", pure_numpy=True).fbm_loops is pure


class _Recorder:
    """fBm loops that record which loop ran and fill a constant."""

    def __init__(self, batch: bool = False) -> None:
        self.calls: list[tuple[str, Any]] = []
        self.batch = batch

    def loop(self, kind: str) -> noise.FbmLoop:
        def run(plan: noise.FbmPlan, seed: int, out: np.ndarray, mask: Any, fill: float) -> None:
            self.calls.append((kind, seed))
            out[...] = seed

        return run

    def seed_batch(self, plan: noise.FbmPlan, seeds: list[int], mask: Any) -> Any:
        self.calls.append(("batch", tuple(seeds)))
        if not self.batch:
            return None  # declined: per-seed calls
        _, _, h, w = plan.octave_coords()
        return np.zeros((len(seeds), h, w), np.float32)

    def loops(self) -> noise.FbmLoops:
        return noise.FbmLoops(
            "recorder",
            separable=self.loop("separable"),
            grid=self.loop("grid"),
            seed_batch=self.seed_batch,
        )


def test_fbm_dispatch_runs_the_loops_of_the_layout() -> None:
    rec = _Recorder()
    loops = rec.loops()
    x, y = _axes()
    assert noise.fbm(x, y, loops=loops, to_01=True, seed=3, **FBM).shape == (7, 13)
    gx, gy = _rotated(x, y)
    out = noise.fbm(gx, gy, loops=loops, to_01=True, seed=4, **FBM)
    assert out.shape == (7, 13) and np.all(out == 4)
    assert rec.calls == [("separable", 3), ("grid", 4)]
    with pytest.raises(ValueError, match="no coverage mask"):
        noise.fbm(x, y, loops=loops, to_01=True, seed=3, mask=np.ones((7, 13), bool), **FBM)


def test_seed_batch_falls_back_to_one_loop_call_per_seed() -> None:
    rec = _Recorder(batch=False)
    x, y = _axes()
    out = noise.fbm_seed_batch(x, y, loops=rec.loops(), to_01=False, seeds=[5, 6], **FBM)
    assert out.dtype == np.float32 and out.shape == (2, 7, 13)
    assert [float(out[k, 0, 0]) for k in range(2)] == [5.0, 6.0]
    assert rec.calls == [("batch", (5, 6)), ("separable", 5), ("separable", 6)]
    rec = _Recorder(batch=True)
    noise.fbm_seed_batch(*_rotated(x, y), loops=rec.loops(), to_01=False, seeds=[1], **FBM)
    assert rec.calls == [("batch", (1,))]


def test_plan_scales_octaves_in_the_coordinate_dtype() -> None:
    x, y = _axes(np.float32)
    plan = noise.plan_fbm(x, y, to_01=True, **FBM)
    assert plan.layout.separable and plan.xs is not None and plan.xs.dtype == np.float64
    expected = (x[0] * np.float32(FBM["freq_x"] * FBM["lacunarity"])).astype(np.float64)
    assert np.array_equal(plan.xs[1], expected)
    grid = noise.plan_fbm(*_rotated(x, y), to_01=True, **FBM)
    # full grids: float64 frequencies, the float32 grid widened before the product
    assert grid.xs is None and grid.fxs is not None and grid.fxs.dtype == np.float64


@pytest.mark.parametrize("rotate", [False, True])
def test_all_fbm_loops_agree(rotate: bool) -> None:
    """numpy and C loops bit for bit; numba (where installed) to 1e-12; seed batches too."""
    x, y = _axes(np.float32)
    if rotate:
        x, y = _rotated(x, y)
    pure = replace(
        get_backend("numpy"),
        **noise_kernels(lambda: noise_numpy.FBM_LOOPS, noise_numpy.WORLEY_LOOPS),
    )
    expected = pure.fbm(x, y, to_01=False, seed=9, **FBM)
    assert np.array_equal(get_backend("numpy").fbm(x, y, to_01=False, seed=9, **FBM), expected)
    batch = pure.fbm_seed_batch(x, y, to_01=False, seeds=[9, 10], **FBM)
    assert np.array_equal(batch[0], expected.astype(np.float32))
    worley = pure.worley(x, y, to_01=True, seed=2, **WORLEY)
    if "numba" in available_backends():
        numba = get_backend("numba")
        assert np.max(np.abs(numba.fbm(x, y, to_01=False, seed=9, **FBM) - expected)) <= 1e-12
        assert np.max(np.abs(numba.worley(x, y, to_01=True, seed=2, **WORLEY) - worley)) <= 1e-12
        nb_batch = numba.fbm_seed_batch(x, y, to_01=False, seeds=[9, 10], **FBM)
        assert np.max(np.abs(nb_batch - batch)) <= 1e-6
