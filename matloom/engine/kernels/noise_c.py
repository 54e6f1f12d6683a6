"""Wrapper of the optional compiled fBm kernel ``_cnoise`` (bit-identical to ``noise_numpy``).

The extension is built by setup.py when a C compiler is present (``optional=True``: installs
without one still succeed).  It exists for cold-start speed: importing it costs microseconds,
where numba costs ~0.4 s, so a one-shot ``matloom render`` on the numpy backend gets a fast
fBm.  ``noise_numpy.fbm`` calls :func:`fbm` here when :func:`available` and the environment
variable ``MATLOOM_PURE_NUMPY`` is not ``"1"``.

Everything that rounds in the coordinate dtype stays in Python/numpy exactly as in
``noise_numpy.fbm``: separable axes are scaled per octave with ``scale_coords``; for full grids
the per-octave frequencies are rounded to the grid dtype (``freq_in_dtype``) and the C code
multiplies in that dtype before widening, as numpy does.  Importing this module never imports
numba.
"""

from __future__ import annotations

import functools
import os
from types import ModuleType

import numpy as np

from matloom.engine.kernels.opensimplex import (
    coord_layout,
    freq_in_dtype,
    octave_axes,
    octave_schedule,
    perm_from_seed,
)
from matloom.engine.kernels.threads import run_split

_cnoise: ModuleType | None
try:
    from matloom.engine.kernels import _cnoise
except ImportError:  # not built (no C compiler at install time): pure numpy is used instead
    _cnoise = None

__all__ = ["fbm", "available"]

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


def fbm(
    x: np.ndarray,
    y: np.ndarray,
    *,
    octaves: int,
    lacunarity: float,
    gain: float,
    freq_x: float,
    freq_y: float,
    to_01: bool,
    seed: int,
) -> np.ndarray:
    """fBm of OpenSimplex noise on the broadcast of x and y (float64); see ``noise_numpy.fbm``.

    Raises RuntimeError when the extension is not available (check :func:`available`).
    """
    cast_values = _numpy_cast_values()
    if _cnoise is None or cast_values is None:
        raise RuntimeError(
            "matloom's C extension _cnoise is not available; reinstall matloom with a C "
            "compiler present, or use noise_numpy.fbm_numpy"
        )
    sched = octave_schedule(octaves, lacunarity, gain, freq_x, freq_y)
    perm = perm_from_seed(seed)
    amps = np.array(sched.amps, dtype=np.float64)
    lay = coord_layout(x, y)
    if lay.separable:
        xs, ys = octave_axes(lay.x_axis, lay.y_axis, sched.freqs_x, sched.freqs_y)
        out = np.empty((lay.y_axis.size, lay.x_axis.size), dtype=np.float64)

        def rows(start: int, stop: int) -> None:
            part_ys = np.ascontiguousarray(ys[:, start:stop])
            args = (amps, perm, cast_values, sched.norm, bool(to_01))
            _cnoise.fbm_separable(out[start:stop], xs, part_ys, *args)  # type: ignore[union-attr]

        run_split(_threads(out.size, out.shape[0]), rows, out.shape[0])
        return out.reshape(lay.shape)
    with np.errstate(over="ignore"):  # numpy's own scalar conversion overflows the same way
        fxs = freq_in_dtype(sched.freqs_x, lay.x_grid.dtype)
        fys = freq_in_dtype(sched.freqs_y, lay.y_grid.dtype)
    flat = np.empty(lay.x_grid.size, dtype=np.float64)
    xg, yg = lay.x_grid, lay.y_grid

    def span(start: int, stop: int) -> None:
        args = (fxs, fys, amps, perm, cast_values, sched.norm, bool(to_01))
        _cnoise.fbm_grid(flat[start:stop], xg[start:stop], yg[start:stop], *args)  # type: ignore[union-attr]

    run_split(_threads(flat.size, flat.size), span, flat.size)
    return flat.reshape(lay.shape)
