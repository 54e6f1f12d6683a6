"""The one numba entry point of the kernels: code-generation target set-up and ``jit``.

Every numba kernel module decorates through :func:`jit` (importing this module first), so the
target is configured before numba builds its code generator, which it does at the first
decoration in the process.

Target: on CPUs with AVX-512, LLVM's default tuning for those chips ("prefer-256-bit") keeps the
loop vectoriser at 256-bit vectors. The noise and compositing loops are long, branch-free float64
loops that run about 1.3-1.5x faster with 512-bit vectors on the 2-core Cascade Lake machines we
measure on (see ``benchmarks/engine.py``), so :func:`configure_target` drops that preference.
Results do not change: ``fastmath`` stays off in every bit-exact kernel, so the vector width only
changes how many lanes run at once, not the arithmetic. It is skipped when the user sets
``NUMBA_CPU_FEATURES`` (their choice wins), when ``MATLOOM_NUMBA_WIDE_VECTORS=0``, and when the
process already compiled numba code before MatLoom was imported (the generator exists then).

Threads: numba's parallel loops run on OpenMP here, whose workers spin for a while after every
loop by default. MatLoom alternates short parallel loops with its own compositing and shading
threads, and on a 2-core machine the spinning workers take the CPU from them: with
``OMP_WAIT_POLICY=PASSIVE`` a 256x256 evaluation needs ~30 % less CPU and sweeps run faster
(``benchmarks/``). :func:`configure_threads` sets that default unless the variable is already set
(it must be set before OpenMP starts, i.e. before the first parallel kernel runs). The kernels of
the evaluation path are serial ``nogil`` functions run on row ranges from threads
(``threads.parallel_rows``): a ``prange`` kernel costs numba a parfor pipeline and a second,
unsigned-index specialisation of everything it calls, which made the first render compile for
much longer (docs/performance.md, "Cold start"); only the seed-batch kernels of sweeps still use
``prange``.

Compile progress: importing this module installs :mod:`compile_report`'s listener, which tells
a registered reporter (the CLI's) when a kernel compiles; with none registered it is silent.

Stale caches: numba keys a cached kernel on the source of its own file only, so a kernel whose
callee (or a constant it freezes) lives in an edited file would be loaded stale. Importing this
module puts :class:`AbiLocator` first in numba's cache locators: for MatLoom's files it is
numba's own locator (same directory, same file names) with the file's ABI hash
(:func:`matloom.engine.kernels.abi.file_hash`, the source of its whole import closure) added
to the freshness stamp, so such a kernel is recompiled and its cache entry replaced. Where the
user lists the locators (``NUMBA_CACHE_LOCATOR_CLASSES``) numba uses theirs.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba
from numba.core import caching
from numba.core import config as numba_config

from matloom.engine.kernels import abi
from matloom.engine.kernels.compile_report import install_listener

#: Environment variable that turns the 512-bit vector preference off ("0").
WIDE_VECTORS_ENV = "MATLOOM_NUMBA_WIDE_VECTORS"


def wide_vector_features() -> str | None:
    """The host feature string with "-prefer-256-bit" added, or None where it does not apply
    (no AVX-512, switched off, the user's own NUMBA_CPU_FEATURES or NUMBA_CPU_NAME -- e.g.
    ``generic`` for portable cached kernels, which host features would undo --, or LLVM cannot
    tell)."""
    if os.environ.get(WIDE_VECTORS_ENV, "1") == "0":
        return None
    if os.environ.get("NUMBA_CPU_FEATURES") or os.environ.get("NUMBA_CPU_NAME"):
        return None
    try:
        import llvmlite.binding as ll

        features = ll.get_host_cpu_features()
    except (RuntimeError, ImportError):  # pragma: no cover - LLVM without host detection
        return None
    if not features.get("avx512f") or not numba_config.ENABLE_AVX:
        return None
    return features.flatten() + ",-prefer-256-bit"


def configure_target() -> bool:
    """Set numba's CPU features for 512-bit vectors when :func:`wide_vector_features` applies
    and numba has not built its code generator yet; True when the setting was applied."""
    from numba.core import registry

    if "_toplevel_target_context" in vars(registry.cpu_target):  # generator already built
        return False
    features = wide_vector_features()
    if features is None:
        return False
    numba_config.CPU_FEATURES = features
    return True


WIDE_VECTORS = configure_target()


def configure_threads() -> None:
    """Default ``OMP_WAIT_POLICY`` to PASSIVE (see the module docstring); a user's value wins."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


configure_threads()
install_listener()  # compile progress for front ends that ask for it (silent otherwise)

#: Source files under this directory get :class:`AbiLocator`'s stamps.
_OURS = abi.PACKAGE_ROOT / "matloom"


def _cache_impl() -> Any:
    """numba's cache implementation base class (named ``_CacheImpl`` before numba 0.61)."""
    return getattr(caching, "CacheImpl", None) or caching._CacheImpl


class AbiLocator(caching._CacheLocator):  # type: ignore[misc]
    """numba's locator for a MatLoom kernel, with the kernel file's ABI hash in its stamp."""

    def __init__(self, base: Any, abi_hash: str) -> None:
        self._base = base
        self._abi_hash = abi_hash

    def ensure_cache_path(self) -> None:
        self._base.ensure_cache_path()

    def get_cache_path(self) -> str:
        return self._base.get_cache_path()

    def get_source_stamp(self) -> Any:
        return (self._base.get_source_stamp(), "matloom-abi", self._abi_hash)

    def get_disambiguator(self) -> str:
        return self._base.get_disambiguator()

    @classmethod
    def from_function(cls, py_func: Any, py_file: str) -> AbiLocator | None:
        """The first of numba's other locators that takes the function, wrapped; None for
        files outside MatLoom (or when no other locator takes it: no caching then)."""
        path = Path(py_file).resolve()
        if not path.is_file() or not path.is_relative_to(_OURS):
            return None
        for other in list(_cache_impl()._locator_classes):
            base = None if other is cls else other.from_function(py_func, py_file)
            if base is not None:
                return cls(base, abi.file_hash(path))
        return None


def install_abi_locator() -> None:
    """Put :class:`AbiLocator` first in numba's cache locators (idempotent)."""
    classes = _cache_impl()._locator_classes
    if AbiLocator not in classes:
        classes.insert(0, AbiLocator)


install_abi_locator()


def jit(
    parallel: bool = False, inline: bool = False, **options: Any
) -> Callable[[Callable[..., Any]], Any]:
    """``numba.njit(cache=True, parallel=..., **options)``; ``inline=True`` inlines the function
    into its callers at numba IR level. Falls back to uncached compilation when numba finds no
    writable cache location (it raises at decoration time then)."""
    options = dict(options, parallel=parallel)
    if inline:
        options["inline"] = "always"

    def decorate(func: Callable[..., Any]) -> Any:
        try:
            return numba.njit(cache=True, **options)(func)
        except RuntimeError:  # "cannot cache function ...: no locator available for file"
            return numba.njit(cache=False, **options)(func)

    return decorate
