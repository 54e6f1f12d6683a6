"""Whole-program parity with the reference implementation's fixture arrays (tests/data/parity)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends
from matloom.engine.evaluate import evaluate
from matloom.engine.maps import ARRAY_FIELDS, NEWER_FIELDS

DATA = Path(__file__).resolve().parents[1] / "data" / "parity"
MANIFEST = json.loads((DATA / "manifest.json").read_text())["programs"]
PROGRAMS = sorted(MANIFEST)
SIZES = [(64, 64), (48, 32)]
BACKENDS = available_backends()

# Tolerances from the fixtures README: 1e-5 absolute on 0..1 channels, 1e-5 relative on height and
# ior, 1e-4 on normal/AO; NaN/inf at the same texels.
ABS_TOL = {"normal": 1e-4, "ao": 1e-4}
REL_TOL = {"height": 1e-5, "ior": 1e-5, "emissive_linear": 1e-5}


def _source(name: str) -> str:
    baked = DATA / f"{name}.baked.mat"
    return (baked if baked.exists() else DATA / f"{name}.mat").read_text()


def _compare(name: str, key: str, ours: np.ndarray, ref: np.ndarray) -> None:
    assert ours.shape == ref.shape, f"{name}.{key}: shape {ours.shape} != {ref.shape}"
    assert ours.dtype == np.float32
    np.testing.assert_array_equal(np.isnan(ours), np.isnan(ref), err_msg=f"{name}.{key} NaN mask")
    inf = np.isinf(ref) | np.isinf(ours)
    np.testing.assert_array_equal(ours[inf], ref[inf], err_msg=f"{name}.{key} inf texels")
    fin = np.isfinite(ref) & np.isfinite(ours)
    a, r = ours[fin].astype(np.float64), ref[fin].astype(np.float64)
    if key in REL_TOL:
        tol = REL_TOL[key] * np.maximum(np.abs(r), 1.0)
    else:
        tol = ABS_TOL.get(key, 1e-5)
    bad = np.abs(a - r) > tol
    assert not bad.any(), (
        f"{name}.{key}: {bad.sum()} texel(s) differ; max |diff| {np.abs(a - r).max():.3g}"
    )


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("name", PROGRAMS)
def test_program_channels_match_reference(name, size, backend):
    w, h = size
    ref = np.load(DATA / f"{name}_{w}x{h}.npz")
    maps = evaluate(_source(name), w, h, backend=backend)
    assert set(ref.files) <= set(ARRAY_FIELDS), f"{name}: unknown arrays in the fixture"
    # The fixtures predate the language-2 channels: they hold every other map.
    assert set(ARRAY_FIELDS) - set(ref.files) == set(NEWER_FIELDS)
    for key in NEWER_FIELDS:  # no language-1 program writes them: their default, 0
        assert np.all(getattr(maps, key) == 0), f"{name}.{key}"
    for key in ref.files:
        _compare(name, key, getattr(maps, key), ref[key])


def _expr_program(expr: str) -> str:
    return f"Material(\n  Layer(1)\n    .height({expr})\n)"


EXPRESSIONS = json.loads((DATA / "expressions.json").read_text())


def _value(v: object) -> float:
    return float(v) if not isinstance(v, str) else float(v.replace("inf", "inf"))


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("entry", EXPRESSIONS, ids=lambda e: e["expr"][:60])
def test_expression_point_samples(entry, backend):
    """Each expression evaluated through the evaluator at the fixture's points (float64 axes)."""
    from matloom.engine.backends import get_backend
    from matloom.engine.evaluate import Evaluator, prepare

    program = prepare(_expr_program(entry["expr"]))
    expr = program.layers[0].channel("height").args[0]
    for x, y, expected in entry["points"]:
        ev = Evaluator(
            program,
            np.array([[x]], dtype=np.float64),
            np.array([[y]], dtype=np.float64),
            get_backend(backend),
        )
        got = float(np.broadcast_to(ev.field(expr), (1, 1))[0, 0])
        want = _value(expected)
        if math.isnan(want):
            assert math.isnan(got), f"{entry['expr']} at ({x}, {y}): {got} != nan"
        elif math.isinf(want):
            assert got == want
        else:
            assert got == pytest.approx(want, rel=1e-9, abs=1e-12), f"{entry['expr']} at ({x}, {y})"


def test_canonical_reference_programs_print_identically():
    for name in PROGRAMS:
        if name == "seedless":
            continue
        canonical = (DATA / f"{name}.canonical.mat").read_text()
        assert matloom.format(matloom.parse(canonical)) == canonical
