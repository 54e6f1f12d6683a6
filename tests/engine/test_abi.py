"""ABI hashes of the numba kernels (matloom.engine.kernels.abi) and the proof that a stale numba
cache is rebuilt, never used: a kernel whose callee in another file was edited is recompiled."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from matloom.engine.kernels import abi

ROOT = Path(__file__).resolve().parents[2]
KERNELS = abi.KERNELS


def test_closures_follow_imports_into_other_files() -> None:
    def names(module: str) -> set[str]:
        return {p.name for p in abi.closure(KERNELS / module)}

    assert {"register_numba.py", "register_ops.py", "jit.py"} <= names("composite_numba.py")
    assert {"noise_numba_core.py", "opensimplex.py", "noise_numba_worley.py"} <= names(
        "noise_numba.py"
    )
    assert "composite_numba.py" not in names("noise_numba.py")
    modules = {p.name for p in abi.kernel_modules()}
    assert {"composite_numba.py", "noise_numba.py", "register_numba.py"} <= modules
    assert not {"noise_numpy.py", "noise_c.py", "warmup.py", "abi.py"} & modules


@pytest.mark.numba
def test_every_kernel_is_stamped_with_its_abi_hash() -> None:
    pytest.importorskip("numba")
    from numba.core import caching

    from matloom.engine.kernels import jit, noise_numba, register_numba

    assert caching.CacheImpl._locator_classes[0] is jit.AbiLocator
    for module, kernel in (
        (noise_numba, noise_numba._fbm_separable_kernel),
        (register_numba, register_numba.run_code),
    ):
        impl = getattr(kernel._cache, "_impl", None)
        if impl is None:  # NullCache: no writable cache directory here
            pytest.skip("numba caching is off")
        assert isinstance(impl.locator, jit.AbiLocator)
        assert impl.locator.get_source_stamp()[2] == abi.file_hash(module.__file__)


def test_kernels_hash_is_part_of_the_warmup_stamp(monkeypatch: pytest.MonkeyPatch) -> None:
    from matloom.runtime import warmup

    key = warmup.stamp_key()
    monkeypatch.setattr(abi, "kernels_hash", lambda: "an edited kernel")
    assert warmup.stamp_key() != key


_CALLEE = """
from matloom.engine.kernels.jit import jit

SCALE = {scale}


@jit(inline=True)
def scaled_inline(x):
    return x * SCALE


@jit()
def scaled_call(x):
    return x * SCALE
"""
_CALLER = """
from matloom.engine.kernels.jit import jit
from matloom.engine.kernels.probe_callee import scaled_call, scaled_inline


@jit()
def probe(x):
    return scaled_inline(x) + scaled_call(x)
"""
_RUN = """
import json, sys
if sys.argv[1] == "plain":  # numba's own locators only: the behaviour being fixed
    from numba.core import caching
    import matloom.engine.kernels.jit as jit
    caching.CacheImpl._locator_classes.remove(jit.AbiLocator)
from matloom.engine.kernels.probe_caller import probe
value = probe(1.0)
stats = probe.stats
print(json.dumps({"value": value, "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values())}))
"""


def _run(package: Path, cache: Path, mode: str) -> dict[str, float]:
    env = {**os.environ, "PYTHONPATH": str(package), "NUMBA_CACHE_DIR": str(cache)}
    done = subprocess.run(
        [sys.executable, "-c", _RUN, mode],
        env=env,
        cwd=package,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.numba
def test_editing_a_callee_in_another_file_recompiles_the_cached_caller(tmp_path: Path) -> None:
    """A copy of the package with a kernel (``probe``) calling an inlined and a compiled
    function of another file: after that file's constant is edited, numba alone would load the
    cached ``probe`` with the old value; with the ABI hash it recompiles and computes the new."""
    pytest.importorskip("numba")
    package = tmp_path / "pkg"
    shutil.copytree(
        ROOT / "matloom", package / "matloom", ignore=shutil.ignore_patterns("__pycache__")
    )
    kernels = package / "matloom" / "engine" / "kernels"
    (kernels / "probe_caller.py").write_text(_CALLER, encoding="utf-8")

    def edit(scale: float) -> None:
        (kernels / "probe_callee.py").write_text(_CALLEE.format(scale=scale), encoding="utf-8")

    edit(2.0)
    plain = tmp_path / "plain-cache"
    assert _run(package, plain, "plain") == {"value": 4.0, "hits": 0, "misses": 1}
    edit(3.0)
    stale = _run(package, plain, "plain")  # numba alone: the stale kernel is loaded
    assert stale == {"value": 4.0, "hits": 1, "misses": 0}, "numba now keys callees: re-check"

    edit(2.0)
    cache = tmp_path / "cache"
    assert _run(package, cache, "abi") == {"value": 4.0, "hits": 0, "misses": 1}
    assert _run(package, cache, "abi") == {"value": 4.0, "hits": 1, "misses": 0}  # reused
    edit(3.0)
    assert _run(package, cache, "abi") == {"value": 6.0, "hits": 0, "misses": 1}  # rebuilt
    assert _run(package, cache, "abi") == {"value": 6.0, "hits": 1, "misses": 0}
