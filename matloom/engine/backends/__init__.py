"""Kernel backends: one table of primitive kernels per backend (``numpy`` always, ``numba`` when
installed). The evaluator only talks to a :class:`Backend`, so a GPU array backend can be added
here without touching the AST or the evaluator.

This is the one place where kernels are chosen. The noise primitives are one dispatch each
(:mod:`matloom.engine.kernels.noise`: a shared plan, then a backend's inner loops); a backend
names its loops here (:func:`noise_kernels`). The numpy backend's fBm runs the C extension's
loops when they are built and ``$MATLOOM_PURE_NUMPY`` is not ``"1"`` (:func:`numpy_fbm_loops`,
read at every call), else pure numpy: the same numbers.

Both backends produce bit-identical maps (tests/engine/test_fast_paths.py checks this), so the
choice is purely about speed. ``auto`` (:func:`choose_backend`) weighs numba's one-off start-up
cost (importing numba and loading the cached kernels: about 1 s of CPU) against its speed: a
process that evaluates one small image (e.g. ``matloom render --size 256``) is faster on numpy.

Before the kernels are compiled at all (a fresh install or numba cache) numba's start-up cost is
10-25 s of compilation instead. Under the ``background`` cold-start policy, which the CLI sets
(:func:`set_cold_start`), ``auto`` then starts the background compiler of
:mod:`matloom.engine.kernels.warmup` and evaluates on numpy until it has finished. The library
default (``compile``) keeps compiling on first use.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, partial
from typing import TYPE_CHECKING, Any

Kernel = Callable[..., Any]
if TYPE_CHECKING:
    from matloom.engine.kernels.noise import FbmLoops, WorleyLoops

#: Set to "1" to run the numpy backend's fBm on the pure-numpy loops even where the C extension
#: is built (read at every call).
PURE_NUMPY_ENV = "MATLOOM_PURE_NUMPY"


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
    #: ``tile(x, y, params, dr, dc)``: Tile's instance frame of one neighbour cell
    #: (local x, local y, keep); see :mod:`matloom.engine.kernels.tile`.
    tile: Kernel
    #: Evaluate through the fused numba compositing path (identical results, less memory).
    fused: bool = False
    #: ``fbm`` at the texels of a boolean mask only (coverage culling, see engine.cull).
    fbm_masked: Kernel | None = None
    #: The fBm loops ``fbm`` runs now (what the noise kernels are bound to; for reports/tests).
    fbm_loops: Callable[[], FbmLoops] | None = None


def numpy_fbm_loops() -> FbmLoops:
    """The numpy backend's fBm loops, chosen at every call: the C extension's when it is built
    and usable here and ``$MATLOOM_PURE_NUMPY`` is not "1", else pure numpy's (same numbers)."""
    from matloom.engine.kernels import noise_c, noise_numpy

    if os.environ.get(PURE_NUMPY_ENV) != "1" and noise_c.available():
        return noise_c.FBM_LOOPS
    return noise_numpy.FBM_LOOPS


def noise_kernels(fbm_loops: Callable[[], FbmLoops], worley_loops: WorleyLoops) -> dict[str, Any]:
    """The noise fields of a :class:`Backend`: the dispatch of :mod:`matloom.engine.kernels.noise`
    bound to a backend's loops (``fbm_loops()`` is asked at every call)."""
    from matloom.engine.kernels import noise

    def fbm(x: Any, y: Any, **kw: Any) -> Any:
        return noise.fbm(x, y, loops=fbm_loops(), **kw)

    def fbm_masked(x: Any, y: Any, mask: Any, **kw: Any) -> Any:
        return noise.fbm(x, y, loops=fbm_loops(), mask=mask, **kw)

    def fbm_seed_batch(x: Any, y: Any, **kw: Any) -> Any:
        return noise.fbm_seed_batch(x, y, loops=fbm_loops(), **kw)

    return dict(
        fbm=fbm,
        fbm_masked=fbm_masked if fbm_loops().masks else None,
        fbm_seed_batch=fbm_seed_batch,
        fbm_loops=fbm_loops,
        worley=partial(noise.worley, loops=worley_loops),
        worley_seed_batch=partial(noise.worley_seed_batch, loops=worley_loops),
    )


def _shared_kernels(name: str) -> dict[str, Any]:
    """The kernels every backend takes from the same modules (paths by backend name)."""
    from matloom.engine.kernels import patterns, shapes, threshold

    return dict(
        weave=patterns.weave,
        threshold=threshold.threshold,
        fill=partial(shapes.fill, backend=name),
        stroke=partial(shapes.stroke, backend=name),
    )


def _numpy_backend() -> Backend:
    from matloom.engine.kernels import noise_numpy, patterns, tile

    noise = noise_kernels(numpy_fbm_loops, noise_numpy.WORLEY_LOOPS)
    shared = _shared_kernels("numpy")
    return Backend("numpy", bricks=patterns.bricks, tile=tile.instance, **shared, **noise)


def _numba_backend() -> Backend:
    from matloom.engine.kernels import noise_numba, patterns_numba, patterns_weave_numba, tile_numba

    noise = noise_kernels(lambda: noise_numba.FBM_LOOPS, noise_numba.WORLEY_LOOPS)
    shared = {**_shared_kernels("numba"), "weave": patterns_weave_numba.weave}
    kernels = dict(bricks=patterns_numba.bricks, tile=tile_numba.instance)
    return Backend("numba", fused=True, **kernels, **shared, **noise)


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
    if (warm or texels >= AUTO_NUMBA_MIN_TEXELS) and _kernels_ready():
        return get_backend("auto")
    return get_backend("numpy")


COLD_START_POLICIES = ("compile", "background")
_cold_start = ["compile"]
_ready = [False]


def set_cold_start(policy: str) -> str:
    """What ``auto`` does while the numba kernels are not compiled; returns the previous policy.

    ``compile`` (the default): pick numba anyway, the kernels compile on first use.
    ``background`` (the CLI's): start the background compiler and pick numpy until it is done
    (the same maps); where it cannot help (no numba, no writable cache, switched off with
    $MATLOOM_BACKGROUND_COMPILE=0, or it failed) numba compiles on first use as before.
    """
    if policy not in COLD_START_POLICIES:
        raise ValueError(f"unknown cold-start policy {policy!r}: {', '.join(COLD_START_POLICIES)}")
    previous, _cold_start[0] = _cold_start[0], policy
    return previous


def _kernels_ready() -> bool:
    """False while ``auto`` should stay on numpy under the ``background`` policy."""
    if _cold_start[0] != "background" or _ready[0]:
        return True
    from importlib.util import find_spec

    if find_spec("numba") is None:
        return True  # get_backend("auto") falls back to numpy by itself
    from matloom.engine.kernels import compile_report, warmup

    current = warmup.ensure_background()
    if not current.running:  # ready; or it cannot run or failed: numba compiles on first use
        _ready[0] = True
        return True
    reporter = compile_report.get_reporter()
    if reporter is not None:
        reporter.background_compiling(current.done, current.total)
    return False


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
