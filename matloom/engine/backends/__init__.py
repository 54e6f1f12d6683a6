"""Kernel backends: one table of primitive kernels per backend (``numpy`` always, ``numba`` when
installed). The evaluator only talks to a :class:`Backend`, so a GPU array backend can be added
here without touching the AST or the evaluator.

This is the one place where kernels are chosen. The noise primitives are one dispatch each
(:mod:`matloom.engine.kernels.noise`: a shared plan, then a backend's inner loops); a backend
names its loops here (:func:`noise_kernels`). The numpy backend's fBm runs the C extension's
loops when they are built, else pure numpy (the same numbers); ``get_backend("numpy",
pure_numpy=True)`` always runs pure numpy (a session with ``MATLOOM_PURE_NUMPY=1``).

Both backends produce bit-identical maps (tests/engine/test_fast_paths.py checks this), so the
choice is purely about speed. Which backend ``auto`` means for a request is a policy of the
runtime :class:`~matloom.engine.session.Session` (:meth:`~matloom.engine.session.Session.
choose_backend`), not of this module.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, partial
from typing import TYPE_CHECKING, Any

Kernel = Callable[..., Any]
if TYPE_CHECKING:
    from matloom.engine.kernels.noise import FbmLoops, WorleyLoops
    from matloom.engine.session import Session


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
    """The numpy backend's fBm loops: the C extension's when it is built and usable here, else
    pure numpy's (the same numbers)."""
    from matloom.engine.kernels import noise_c, noise_numpy

    return noise_c.FBM_LOOPS if noise_c.available() else noise_numpy.FBM_LOOPS


def pure_numpy_fbm_loops() -> FbmLoops:
    """The pure-numpy fBm loops (what ``get_backend("numpy", pure_numpy=True)`` runs)."""
    from matloom.engine.kernels import noise_numpy

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


def _numpy_backend(pure_numpy: bool = False) -> Backend:
    from matloom.engine.kernels import noise_numpy, patterns, tile

    loops = pure_numpy_fbm_loops if pure_numpy else numpy_fbm_loops
    noise = noise_kernels(loops, noise_numpy.WORLEY_LOOPS)
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


@cache
def get_backend(name: str = "auto", *, pure_numpy: bool = False) -> Backend:
    """The backend ``name`` (``auto``: numba if installed, else numpy); ``pure_numpy``: the
    numpy backend's fBm on the pure-numpy loops, never the C extension's (the same numbers).
    The backend a request should use is the session's choice (:func:`session_backend`)."""
    if name == "auto":
        try:
            return _FACTORIES["numba"]()
        except ImportError:
            return _numpy_backend(pure_numpy)
    if name not in _FACTORIES:
        raise ValueError(f"unknown backend {name!r}; available: {', '.join(_FACTORIES)}")
    return _numpy_backend(pure_numpy) if name == "numpy" else _FACTORIES[name]()


def session_backend(
    session: Session, name: str = "auto", texels: int = 0, work: int = 0
) -> Backend:
    """The backend ``session`` picks for a request of ``texels`` texels and ``work`` element
    operations (``name``: ``auto``, ``numpy`` or ``numba``; see
    :meth:`~matloom.engine.session.Session.choose_backend`), with the session's settings (its
    ``pure_numpy``)."""
    return get_backend(session.choose_backend(name, texels, work), pure_numpy=session.pure_numpy)
