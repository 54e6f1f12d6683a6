"""Kernel backends: one table of primitive kernels per backend (``numpy`` always, ``numba`` when
installed). The evaluator only talks to a :class:`Backend`, so a GPU array backend can be added
here without touching the AST or the evaluator.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache, partial
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
    )


def _numba_backend() -> Backend:
    from matloom.engine.kernels import noise_numba, noise_numba_batch, patterns, shapes, threshold

    return Backend(
        "numba",
        fbm=noise_numba.fbm,
        worley=noise_numba.worley,
        fbm_seed_batch=noise_numba_batch.fbm_seed_batch,
        bricks=patterns.bricks,
        weave=patterns.weave,
        threshold=threshold.threshold,
        fill=partial(shapes.fill, backend="numba"),
        stroke=partial(shapes.stroke, backend="numba"),
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


@lru_cache(maxsize=None)
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
