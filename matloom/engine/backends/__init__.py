"""Kernel backends: one table of primitive kernels per backend (``numpy`` always, ``numba`` when
installed). The evaluator only talks to a :class:`Backend`, so a GPU array backend can be added
here without touching the AST or the evaluator.

Both backends produce bit-identical maps (tests/engine/test_fast_paths.py checks this), so the
choice is purely about speed. ``auto`` (:func:`choose_backend`) weighs numba's one-off start-up
cost (importing numba and loading the cached kernels: about 1 s of CPU) against its speed: a
process that evaluates one small image (e.g. ``matloom render --size 256``) is faster on numpy.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, partial
from typing import Any

Kernel = Callable[..., Any]


@dataclass(frozen=True)
class Backend:
    """The primitive kernels the evaluator needs. All take/return numpy-compatible arrays."""

    name: str
    fbm: Kernel
    worley: Kernel
    fbm_seed_batch: Kernel
    bricks: Kernel
    weave: Kernel
    threshold: Kernel
    fill: Kernel
    stroke: Kernel
    worley_seed_batch: Kernel
    #: Evaluate through the fused numba compositing path (identical results, less memory).
    fused: bool = False
    #: ``fbm`` at the texels of a boolean mask only (coverage culling, see engine.cull).
    fbm_masked: Kernel | None = None


def _numpy_backend() -> Backend:
    from matloom.engine.kernels import noise_numpy, patterns, shapes, threshold

    return Backend(
        "numpy",
        fbm=noise_numpy.fbm,
        worley=noise_numpy.worley,
        fbm_seed_batch=noise_numpy.fbm_seed_batch,
        bricks=patterns.bricks,
        weave=patterns.weave,
        threshold=threshold.threshold,
        fill=partial(shapes.fill, backend="numpy"),
        stroke=partial(shapes.stroke, backend="numpy"),
        worley_seed_batch=noise_numpy.worley_seed_batch,
    )


def _numba_backend() -> Backend:
    from matloom.engine.kernels import (
        noise_numba,
        noise_numba_batch,
        patterns,
        patterns_numba,
        shapes,
        threshold,
    )

    return Backend(
        "numba",
        fbm=noise_numba.fbm,
        worley=noise_numba.worley,
        fbm_seed_batch=noise_numba_batch.fbm_seed_batch,
        bricks=patterns_numba.bricks,
        weave=patterns.weave,
        threshold=threshold.threshold,
        fill=partial(shapes.fill, backend="numba"),
        stroke=partial(shapes.stroke, backend="numba"),
        worley_seed_batch=noise_numba.worley_seed_batch,
        fused=True,
        fbm_masked=noise_numba.fbm_masked,
    )


_FACTORIES: dict[str, Callable[[], Backend]] = {"numpy": _numpy_backend, "numba": _numba_backend}


def available_backends() -> list[str]:
    """Names of the backends that can be loaded here."""
    out = []
    for name in _FACTORIES:
        try:
            get_backend(name)
            out.append(name)
        except ImportError:
            pass
    return out


#: ``auto`` picks numba for requests of at least this many texels (numba's start-up cost is
#: then small next to what it saves) ...
AUTO_NUMBA_MIN_TEXELS = 512 * 512
#: ... and for every request once this many evaluations ran in the process, or numba is loaded.
AUTO_NUMBA_AFTER_CALLS = 2
_auto_calls = [0]


def choose_backend(name: str = "auto", texels: int = 0) -> Backend:
    """The backend for a request of ``texels`` texels; ``auto`` as in the module docstring
    ($MATLOOM_BACKEND overrides it). Any other name is passed to :func:`get_backend`."""
    if name != "auto" or os.environ.get("MATLOOM_BACKEND", "auto") != "auto":
        return get_backend(name)
    _auto_calls[0] += 1
    warm = "numba" in sys.modules or _auto_calls[0] > AUTO_NUMBA_AFTER_CALLS
    if warm or texels >= AUTO_NUMBA_MIN_TEXELS:
        return get_backend("auto")
    return get_backend("numpy")


@cache
def get_backend(name: str = "auto") -> Backend:
    """The backend ``name`` (``auto``: $MATLOOM_BACKEND, else numba if installed, else numpy)."""
    if name == "auto":
        name = os.environ.get("MATLOOM_BACKEND", "auto")
    if name == "auto":
        try:
            return _FACTORIES["numba"]()
        except ImportError:
            return _FACTORIES["numpy"]()
    if name not in _FACTORIES:
        raise ValueError(f"unknown backend {name!r}; available: {', '.join(_FACTORIES)}")
    return _FACTORIES[name]()
