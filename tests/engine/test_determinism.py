"""Determinism and controlled edits (paper §3.3 and the formal dependency statement)."""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.engine.evaluate import evaluate
from matloom.engine.maps import ARRAY_FIELDS
from matloom.lang.inline import inline_defines
from matloom.lang.printer import format_program

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "parity"
TILE = (DATA / "tile.mat").read_text()
BRICK = (DATA / "brick.mat").read_text()


def digest(maps) -> dict[str, str]:  # noqa: ANN001
    return {
        k: hashlib.sha256(np.ascontiguousarray(getattr(maps, k)).tobytes()).hexdigest()
        for k in ARRAY_FIELDS
    }


@pytest.mark.parametrize("src", [TILE, BRICK], ids=["tile", "brick"])
def test_repeated_evaluation_is_byte_identical(src):
    assert digest(evaluate(src, 96, 80)) == digest(evaluate(src, 96, 80))


def test_evaluation_is_byte_identical_across_processes():
    code = (
        "import hashlib, numpy as np, matloom, sys;"
        "m = matloom.evaluate(open(sys.argv[1]).read(), 96, 80);"
        "print(hashlib.sha256(b''.join(np.ascontiguousarray(a).tobytes() "
        "for a in m.arrays().values())).hexdigest())"
    )
    env_path = {"PYTHONPATH": str(ROOT)}
    import os

    env = {**os.environ, **env_path}
    outs = {
        subprocess.run(
            [sys.executable, "-c", code, str(DATA / "tile.mat")],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        for _ in range(2)
    }
    here = hashlib.sha256(
        b"".join(
            np.ascontiguousarray(a).tobytes() for a in evaluate(TILE, 96, 80).arrays().values()
        )
    ).hexdigest()
    assert outs == {here}


def test_tile_roughness_edit_changes_only_roughness():
    edited = TILE.replace(
        ".roughness((0.04 + (glazeGrain * 0.05)))", ".roughness((0.09 + (glazeGrain * 0.05)))"
    )
    assert edited != TILE
    a, b = digest(evaluate(TILE, 128, 128)), digest(evaluate(edited, 128, 128))
    for key in ("basecolor_linear", "alpha", "height", "normal", "ao", "metallic", "ior"):
        assert a[key] == b[key], key
    assert a["roughness"] != b["roughness"]


def test_tile_mortar_edit_changes_coverage_and_relief_together():
    edited = TILE.replace("mortar=0.02", "mortar=0.05")
    a, b = digest(evaluate(TILE, 128, 128)), digest(evaluate(edited, 128, 128))
    # total coverage stays 1 (opaque grout base), but the tile layer's visible coverage moves,
    # so every blended channel and the relief change together
    for key in ("height", "normal", "ao", "basecolor_linear", "roughness", "coat"):
        assert a[key] != b[key], key


@pytest.mark.parametrize("src", [TILE, BRICK], ids=["tile", "brick"])
def test_inlined_and_named_forms_export_identical_maps(src):
    inlined = format_program(inline_defines(matloom.parse(src)))
    assert "Define(" not in inlined
    assert digest(evaluate(src, 80, 64)) == digest(evaluate(inlined, 80, 64))


def test_inlined_random_programs_evaluate_identically():
    from matloom.lang.random_program import random_program

    for seed in range(100):
        text = random_program(seed)
        inlined = format_program(inline_defines(matloom.parse(text)))
        a, b = evaluate(text, 24, 20), evaluate(inlined, 24, 20)
        for key in ARRAY_FIELDS:
            np.testing.assert_array_equal(getattr(a, key), getattr(b, key), err_msg=f"{seed}:{key}")


# ------------------------------------------------------------------ the same maps on every CPU
#: numpy's run-time dispatch groups turned off, one setting after the other: none (the CPU's
#: best), the AVX-512 groups (an AVX2 machine), and AVX2 as well (an x86-64-v2 machine).
CPU_SETTINGS: tuple[tuple[str, ...], ...] = (
    (),
    ("X86_V4", "AVX512_ICL", "AVX512_SPR"),
    ("X86_V4", "AVX512_ICL", "AVX512_SPR", "X86_V3"),
)
#: Evaluates every program of the job (JSON on stdin) on every backend it names and prints the
#: SHA-256 of every map, with the dispatch groups numpy runs with.
_HASH_WORKER = r"""
import hashlib, json, sys, warnings
import numpy as np
try:
    from numpy._core import _multiarray_umath as umath
except ImportError:  # numpy < 2
    from numpy.core import _multiarray_umath as umath
from matloom.engine.evaluate import evaluate
from matloom.engine.maps import ARRAY_FIELDS
job = json.load(sys.stdin)
warnings.simplefilter("ignore")  # division-by-zero and NaN warnings of random programs
hashes = {}
for backend in job["backends"]:
    for name, text in job["programs"].items():
        maps = evaluate(text, job["width"], job["height"], backend=backend)
        for key in ARRAY_FIELDS:
            array = np.ascontiguousarray(getattr(maps, key))
            digest = hashlib.sha256(f"{array.dtype}{array.shape}".encode() + array.tobytes())
            hashes[f"{backend}:{name}:{key}"] = digest.hexdigest()
active = sorted(k for k in umath.__cpu_dispatch__ if umath.__cpu_features__.get(k))
json.dump({"active": active, "hashes": hashes}, sys.stdout)
"""


def _dispatch_groups() -> set[str]:
    """The dispatch groups this numpy build has and this CPU runs (naming another one in
    NPY_DISABLE_CPU_FEATURES is ignored or, for a baseline group, an import error)."""
    try:
        from numpy._core import _multiarray_umath as umath
    except ImportError:  # numpy < 2
        from numpy.core import _multiarray_umath as umath
    return {k for k in umath.__cpu_dispatch__ if umath.__cpu_features__.get(k)}


def determinism_programs() -> dict[str, str]:
    """All docs examples, 30 library entries (every 16th of the sorted list) and 50 random
    programs (25 of language 1, 25 of language 2)."""
    from matloom.lang.random_program import RandomConfig, random_program
    from matloom.library.index import library

    programs = {
        f"{p.parent.parent.name}/{p.name}": p.read_text()
        for folder in (ROOT / "docs" / "examples", ROOT / "matloom" / "examples")
        for p in sorted(folder.glob("*.mat"))
    }
    entries = sorted(library().entries.values(), key=lambda e: e.name)
    step = max(1, len(entries) // 30)
    programs |= {f"library/{e.name}": e.program for e in entries[::step][:30]}
    for language in (1, 2):
        config = RandomConfig(language=language)
        for seed in range(25):
            programs[f"random{language}/{seed}"] = random_program(seed, config=config)
    return programs


def test_maps_are_identical_on_every_cpu_dispatch():
    """Every map of every program is bit-identical whichever SIMD code numpy dispatches to
    (AVX-512, AVX2, baseline) and with numba compiling for a generic CPU, on both backends:
    the transcendental functions are portable (ops.portable_math), not the CPU's."""
    import os

    from matloom.engine.backends import available_backends

    programs = determinism_programs()
    assert len(programs) >= 13 + 30 + 50
    here = _dispatch_groups()
    job = json.dumps(
        {"programs": programs, "backends": available_backends(), "width": 48, "height": 40}
    )
    runs = []
    for setting in CPU_SETTINGS:
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        env.pop("NPY_DISABLE_CPU_FEATURES", None)
        disabled = [g for g in setting if g in here]
        if setting:
            env["NPY_DISABLE_CPU_FEATURES"] = " ".join(disabled)
            env["NUMBA_CPU_NAME"] = "generic"
        # one after the other: the second generic-CPU run reuses the kernels the first cached
        proc = subprocess.run(
            [sys.executable, "-c", _HASH_WORKER],
            env=env,
            input=job,
            capture_output=True,
            text=True,
            timeout=600,
        )
        runs.append((setting, disabled, proc))
    results = []
    for setting, disabled, proc in runs:
        assert proc.returncode == 0, f"{setting}: {proc.stderr[-2000:]}"
        result = json.loads(proc.stdout)
        assert not set(disabled) & set(result["active"]), f"{setting} still dispatched"
        results.append((setting, result["hashes"]))
    reference = results[0][1]
    assert len(reference) == len(programs) * len(available_backends()) * len(ARRAY_FIELDS)
    for setting, hashes in results[1:]:
        differing = sorted(k for k in reference if hashes[k] != reference[k])
        assert not differing, f"NPY_DISABLE_CPU_FEATURES={' '.join(setting)}: {differing[:20]}"
