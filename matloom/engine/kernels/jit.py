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
(it must be set before OpenMP starts, i.e. before the first parallel kernel runs).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

import numba
from numba.core import config as numba_config

#: Environment variable that turns the 512-bit vector preference off ("0").
WIDE_VECTORS_ENV = "MATLOOM_NUMBA_WIDE_VECTORS"


def wide_vector_features() -> str | None:
    """The host feature string with "-prefer-256-bit" added, or None where it does not apply
    (no AVX-512, switched off, the user's own NUMBA_CPU_FEATURES, or LLVM cannot tell)."""
    if os.environ.get(WIDE_VECTORS_ENV, "1") == "0" or os.environ.get("NUMBA_CPU_FEATURES"):
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
