"""The fBm loops of the optional compiled kernel ``_cnoise`` (bit-identical to ``noise_numpy``).

The extension is built by setup.py when a C compiler is present (``optional=True``: installs
without one still succeed).  It exists for cold-start speed: importing it costs microseconds,
where numba costs ~0.4 s, so a one-shot ``matloom render`` on the numpy backend gets a fast
fBm.  The numpy backend runs :data:`FBM_LOOPS` when :func:`available` and the environment
variable ``MATLOOM_PURE_NUMPY`` is not ``"1"`` (the choice is made in
:mod:`matloom.engine.backends`).

Everything that rounds in the coordinate dtype stays in Python/numpy, in the shared plan of
:mod:`matloom.engine.kernels.noise`: separable axes are scaled per octave with ``scale_coords``;
for full grids the C code widens each coordinate to float64 and multiplies it by the float64
per-octave frequency (``scale_grid``).  Importing this module never imports numba.
"""

from __future__ import annotations

import functools
import os
from types import ModuleType

import numpy as np

from matloom.engine.kernels.noise import FbmLoops, FbmPlan
from matloom.engine.kernels.noise_numpy import fbm_tiled
from matloom.engine.kernels.opensimplex import perm_from_seed
from matloom.engine.kernels.threads import run_split

_cnoise: ModuleType | None
try:
    from matloom.engine.kernels import _cnoise
except ImportError:  # not built (no C compiler at install time): pure numpy is used instead
    _cnoise = None

__all__ = ["FBM_LOOPS", "available"]

#: Texels per thread below which the kernel runs on the calling thread only.
MIN_TEXELS_PER_THREAD = 32768


def _threads(texels: int, rows: int) -> int:
    """Threads for a kernel call: the CPU count, fewer for small images."""
    return max(1, min(os.cpu_count() or 1, texels // MIN_TEXELS_PER_THREAD, rows))


@functools.cache
def _numpy_cast_values() -> tuple[int, int, int] | None:
    """numpy's int64 for (NaN, +overflow, -overflow) floats on this platform, or None.

    ``noise_numpy`` converts floored coordinates with ``astype(np.int64)``; for NaN, +-inf and
    |v| >= 2**63 the result is platform-defined (x86-64: INT64_MIN; aarch64 saturates, NaN -> 0).
    The C kernel reproduces whatever numpy gives here.  None if a class is not one value.
    """
    groups = [np.nan] * 8, [np.inf, 1e19, 2.0**63, 1e300] * 2, [-np.inf, -1e19, -1e300] * 3
    probe = np.array([v for group in groups for v in group], dtype=np.float64)
    with np.errstate(invalid="ignore"):
        cast = probe.astype(np.int64).tolist()
    values, start = [], 0
    for group in groups:
        chunk = set(cast[start : start + len(group)])
        start += len(group)
        if len(chunk) != 1:
            return None
        values.append(chunk.pop())
    return values[0], values[1], values[2]


def available() -> bool:
    """True when the compiled kernel is importable and can reproduce numpy on this platform."""
    return _cnoise is not None and _numpy_cast_values() is not None


def _cast_values() -> tuple[int, int, int]:
    """:func:`_numpy_cast_values`; RuntimeError when the extension is not :func:`available`."""
    cast_values = _numpy_cast_values()
    if _cnoise is None or cast_values is None:
        raise RuntimeError(
            "matloom's C extension _cnoise is not available; reinstall matloom with a C "
            "compiler present, or use the numpy loops (MATLOOM_PURE_NUMPY=1)"
        )
    return cast_values


def _fbm_separable(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The separable fBm into ``out`` (H, W): row slices on threads."""
    args = (plan.amps, perm_from_seed(seed), _cast_values(), plan.norm, plan.to_01)
    xs, ys = plan.xs, plan.ys

    def rows(start: int, stop: int) -> None:
        part_ys = np.ascontiguousarray(ys[:, start:stop])
        _cnoise.fbm_separable(out[start:stop], xs, part_ys, *args)  # type: ignore[union-attr]

    run_split(_threads(out.size, out.shape[0]), rows, out.shape[0])


def _fbm_grid(
    plan: FbmPlan, seed: int, out: np.ndarray, mask: np.ndarray | None, fill: float
) -> None:
    """The flat-grid fBm into ``out`` (N,): spans on threads."""
    args = (plan.fxs, plan.fys, plan.amps, perm_from_seed(seed), _cast_values())
    xg, yg = plan.layout.x_grid, plan.layout.y_grid
    norm, to_01 = plan.norm, plan.to_01

    def span(start: int, stop: int) -> None:
        part = (out[start:stop], xg[start:stop], yg[start:stop])
        _cnoise.fbm_grid(*part, *args, norm, to_01)  # type: ignore[union-attr]

    run_split(_threads(out.size, out.size), span, out.size)


#: The C extension's fBm loops (raise RuntimeError when it is not :func:`available`).
FBM_LOOPS = FbmLoops("c", separable=_fbm_separable, grid=_fbm_grid, tiled=fbm_tiled)
