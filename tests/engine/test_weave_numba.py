"""The numba Weave kernel gives numpy's numbers bit for bit (every kernel output, both dtypes,
separable axes and full grids, non-finite coordinates, hard and feathered edges)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("numba", reason="needs the numba extra (numba is not installed)")

from matloom.engine.kernels import patterns  # noqa: E402
from matloom.engine.kernels import patterns_weave_numba as W  # noqa: E402


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("output", W.KERNEL_OUTPUTS)
def test_weave_kernel_matches_numpy(dtype, output):
    rng = np.random.default_rng(7)
    for trial in range(30):
        x = rng.uniform(-50, 50, (1, 53)).astype(dtype)
        y = rng.uniform(-50, 50, (37, 1)).astype(dtype)
        if trial % 3 == 0:  # full grids with non-finite samples
            x, y = (np.array(a) for a in np.broadcast_arrays(x, y))
            x[0, 0], y[1, 1], x[2, 2] = np.nan, np.inf, -np.inf
        kw = dict(
            over=int(rng.integers(1, 5)),
            under=int(rng.integers(1, 5)),
            shift=int(rng.integers(-3, 4)),
            freq_x=float(rng.uniform(-9, 9)),
            freq_y=float(rng.uniform(-9, 9)),
            warp_width=float(rng.uniform(0.05, 1)),
            feather=float(rng.choice([0.0, rng.uniform(0, 0.5)])),
        )
        if output == "thread_value":  # language 3: a seed, a weft width and wrapped threads
            kw.update(seed=trial, weft_width=0.3, wrap=(trial % 3 * 7, trial % 2 * 5))
        want = patterns.weave(x, y, output=output, **kw)
        got = W.weave(x, y, output=output, **kw)
        assert got.dtype == np.float64
        np.testing.assert_array_equal(got, want, err_msg=str(kw))


def test_other_inputs_go_to_numpy():
    x = np.linspace(0, 3, 9, dtype=np.float32)  # 1-D: not the kernel's layout
    kw = dict(over=2, under=1, shift=1, freq_x=3.0, freq_y=3.0, warp_width=0.7, feather=0.0)
    got = W.weave(x, np.float32(0.4), output="along", **kw)
    np.testing.assert_array_equal(got, patterns.weave(x, np.float32(0.4), output="along", **kw))
