"""numba set-up of the kernels (matloom.engine.kernels.jit): thread policy and vector width."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

pytest.importorskip("numba")

_PROBE = (
    "import os, matloom.engine.kernels.jit as j; "
    "from numba.core import config; "
    "print(os.environ.get('OMP_WAIT_POLICY'), j.WIDE_VECTORS, config.CPU_FEATURES is not None)"
)


def _probe(**env: str) -> list[str]:
    clean = {
        k: v
        for k, v in os.environ.items()
        if k not in ("OMP_WAIT_POLICY", "NUMBA_CPU_FEATURES", "NUMBA_CPU_NAME")
    }
    clean.update(env)
    out = subprocess.run(
        [sys.executable, "-c", _PROBE], env=clean, capture_output=True, text=True, check=True
    )
    return out.stdout.split()


def test_openmp_workers_sleep_by_default_but_a_user_setting_wins() -> None:
    assert _probe()[0] == "PASSIVE"
    assert _probe(OMP_WAIT_POLICY="ACTIVE")[0] == "ACTIVE"


def test_wide_vectors_follow_the_cpu_and_can_be_switched_off(monkeypatch) -> None:
    from matloom.engine.kernels.jit import wide_vector_features

    monkeypatch.delenv("NUMBA_CPU_NAME", raising=False)  # the default host set-up is tested

    policy, wide, configured = _probe()
    assert (wide == "True") == (configured == "True")
    if wide == "True":  # AVX-512 host: the preference for 256-bit vectors is dropped
        assert (wide_vector_features() or "").endswith(",-prefer-256-bit")
    assert _probe(MATLOOM_NUMBA_WIDE_VECTORS="0")[1:] == ["False", "False"]
    user = "+sse2"
    policy, wide, configured = _probe(NUMBA_CPU_FEATURES=user)
    assert wide == "False" and configured == "True"  # the user's features are kept
    policy, wide, configured = _probe(NUMBA_CPU_NAME="generic")
    assert wide == "False"  # a generic CPU stays generic: no host features added
