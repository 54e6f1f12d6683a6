"""Fast paths vs the numpy reference path: fused numba evaluation, relief kernels, seed sweep.

The fused path (``backend="numba"``) must give maps bit-identical to the numpy path, which
itself matches the reference fixtures (tests/engine/test_parity.py checks both backends against
the fixture arrays with the project's tolerances). Sweep previews may differ from
``matloom.preview`` by one 8-bit level.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("numba")

import matloom  # noqa: E402
from matloom.engine import relief  # noqa: E402
from matloom.engine.backends import get_backend, session_backend  # noqa: E402
from matloom.engine.evaluate import evaluate  # noqa: E402
from matloom.engine.kernels import composite_numba, relief_numba  # noqa: E402
from matloom.engine.maps import ARRAY_FIELDS, NEWER_FIELDS  # noqa: E402
from matloom.engine.schedules import banded as fused  # noqa: E402
from matloom.engine.schedules import sweep  # noqa: E402
from matloom.engine.schedules.sweep import variant_program  # noqa: E402
from matloom.lang.random_program import random_program  # noqa: E402
from matloom.render.preview import ShadeParams  # noqa: E402

DATA = Path(__file__).resolve().parents[1] / "data" / "parity"
PROGRAMS = sorted(json.loads((DATA / "manifest.json").read_text())["programs"])
SWEEP_PROGRAMS = ["tile", "brick", "reptile_scales", "terrain_thresholds", "denim_twill"]


def run_sweep(text: str, **kwargs: object) -> sweep.SweepResult:
    """The engine's seed sweep with the reference's light."""
    return sweep.run_sweep(text, shading=ShadeParams.of(), **kwargs)  # type: ignore[arg-type]


def _source(name: str) -> str:
    baked = DATA / f"{name}.baked.mat"
    return (baked if baked.exists() else DATA / f"{name}.mat").read_text()


def _assert_bit_identical(text: str, width: int, height: int, label: str) -> None:
    """Every map of the fused path equals the numpy path bit for bit (NaN payloads too)."""
    ref = evaluate(text, width, height, backend="numpy")
    ours = evaluate(text, width, height, backend="numba")
    for key in ARRAY_FIELDS:
        a, b = getattr(ours, key), getattr(ref, key)
        assert a.shape == b.shape and a.dtype == b.dtype == np.float32, f"{label}.{key}"
        differ = a.view(np.uint32) != b.view(np.uint32)
        assert not differ.any(), f"{label}.{key}: {differ.sum()} texel(s) differ"


@pytest.mark.parametrize(
    "size", [(64, 64), (48, 32), (1, 1), (2, 3), (7, 1)], ids=lambda s: f"{s[0]}x{s[1]}"
)
@pytest.mark.parametrize("name", PROGRAMS)
def test_fused_path_is_bit_identical_to_numpy(name: str, size: tuple[int, int]) -> None:
    _assert_bit_identical(_source(name), *size, label=name)


@pytest.mark.parametrize("name", PROGRAMS)
def test_fused_path_matches_reference_fixture(name: str) -> None:
    """Direct check against the reference arrays at 64x64 (README tolerances)."""
    ref = np.load(DATA / f"{name}_64x64.npz")
    ours = evaluate(_source(name), 64, 64, backend="numba")
    assert set(ref.files) <= set(ARRAY_FIELDS), f"{name}: unknown arrays in the fixture"
    # The fixtures predate the language-2 channels: they hold every other map.
    assert set(ARRAY_FIELDS) - set(ref.files) == set(NEWER_FIELDS)
    for key in NEWER_FIELDS:  # no language-1 program writes them: their default, 0
        assert np.all(getattr(ours, key) == 0), f"{name}.{key}"
    for key in ref.files:
        a, r = getattr(ours, key).astype(np.float64), ref[key].astype(np.float64)
        np.testing.assert_array_equal(np.isnan(a), np.isnan(r), err_msg=f"{name}.{key}")
        fin = np.isfinite(a) & np.isfinite(r)
        np.testing.assert_array_equal(a[~fin & ~np.isnan(a)], r[~fin & ~np.isnan(r)])
        tol = {"normal": 1e-4, "ao": 1e-4}.get(key, 1e-5)
        if key in ("height", "ior", "emissive_linear"):
            tol = 1e-5 * np.maximum(np.abs(r[fin]), 1.0)
        assert np.all(np.abs(a[fin] - r[fin]) <= tol), f"{name}.{key}"


@pytest.mark.parametrize("name", ["tile", "nan_inf_fields", "all_channels", "trig_ripples"])
def test_many_bands_and_row_splits(monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    """Band-wise evaluation (tiny bands, uneven last band) changes nothing."""
    monkeypatch.setattr(fused, "BAND_TEXELS", 3 * 50)
    monkeypatch.setattr("matloom.engine.kernels.threads.MIN_TEXELS_PER_THREAD", 64)
    _assert_bit_identical(_source(name), 50, 37, name)


@pytest.mark.parametrize("name", ["tile", "all_channels", "nan_inf_fields", "log_scales"])
def test_uncertain_decode_texels_are_recomposited(
    monkeypatch: pytest.MonkeyPatch, name: str
) -> None:
    """With a huge certainty margin nearly every colour texel is flagged and redone by numpy."""
    monkeypatch.setattr(composite_numba, "DECODE_MARGIN", 1e-3)
    _assert_bit_identical(_source(name), 40, 24, name)


_COVER = "Bricks(brick_width=0.5, brick_height=0.25, mortar=0.04, feather=0.01)"
_HIDDEN_NOISE = "fBm(octaves=3, base_freq=6, to_01=True, seed=4)"


@pytest.mark.parametrize(
    "bottom",
    [
        f"basecolor(40 + {_HIDDEN_NOISE} * 90, 30, 20)",  # finite: decoded where visible only
        f"basecolor(Sqrt({_HIDDEN_NOISE} - 0.5) * 255, 30, 20)",  # NaN under the top layer
        f"emissive(255, 128, 0, {_HIDDEN_NOISE} * 1e308 * 10)",  # inf strength where hidden
        f"emissive(255, 128, 0, 2 - {_HIDDEN_NOISE})",  # finite emission
        "basecolor(10, 20, 30).emissive(200, 100, 50, 3)",  # constant colours
    ],
)
def test_hidden_layer_colours_are_skipped_only_when_exact(bottom: str) -> None:
    """A layer visible on under half of a row decodes its colours only where visible, unless
    a hidden colour is NaN/inf (then 0 x colour is not 0): maps equal the numpy path's."""
    text = (
        f"View(0, 0, 2, 2)\nMaterial(\n  Layer(1).{bottom},\n"
        f"  Layer({_COVER}).basecolor(200, 200, 190).roughness(0.3)\n)"
    )
    _assert_bit_identical(text, 64, 40, bottom)


_WILD = "Log(fBm(octaves=2, base_freq=3, seed=8), base=10)"  # NaN below 0, -inf at 0


@pytest.mark.parametrize(
    "expr",
    [
        f"{_WILD} * 3 + 0.25",
        f"0.25 + 3 * {_WILD}",
        f"{_WILD} * -2 - 0.5",
        f"0.5 - {_WILD} * 2",  # not fused: c - x * k
        f"({_WILD} * 0) + 0",  # 0 * inf = NaN, -0 + 0
        f"{_WILD} * 1e308 + 1e308",  # overflow to inf
    ],
)
def test_fused_multiply_add_rows_equal_numpy(expr: str) -> None:
    """``x * c1 + c2`` runs as one register row with two roundings: bit-identical maps, NaN and
    infinities included."""
    text = (
        "View(0, 0, 2, 2)\nMaterial(Layer(1)"
        f".basecolor({expr} * 40 + 100, 50, 50).roughness({expr}).height({expr} * 0.01))"
    )
    _assert_bit_identical(text, 40, 30, expr)


@pytest.mark.parametrize("name", ["tile", "brick", "nan_inf_fields"])
def test_flagged_texels_of_many_bands_are_recomposited_together(
    monkeypatch: pytest.MonkeyPatch, name: str
) -> None:
    """Small bands (several per image) with most colour texels flagged: one joint numpy pass."""
    monkeypatch.setattr(composite_numba, "DECODE_MARGIN", 1e-3)
    monkeypatch.setattr(fused, "BAND_TEXELS", 40 * 5)
    assert len(fused._band_slices(27, 40)) > 3
    _assert_bit_identical(_source(name), 40, 27, name)


def test_decode_table_is_within_its_margin() -> None:
    """The cubic sRGB table is far more accurate than the 2**-44 certainty margin."""
    rng = np.random.default_rng(5)
    authored = np.concatenate([rng.random(200_000), np.linspace(0.0404, 1.0, 50_001)]) * 255.0
    lin = np.empty_like(authored)
    composite_numba.decode_row(authored, fused.decode_luts()[0], lin, np.empty_like(lin))
    s = authored / 255.0
    x = (s + 0.055) / 1.055  # the float64 power base the reference forms
    exact = np.where(s <= 0.04045, s / 12.92, np.power(x.astype(np.longdouble), 2.4))
    rel = np.abs(lin - exact) / exact
    # numpy's own pow is within ~1.2 ulp (3e-16) of exact; keep a 16x safety factor
    assert float(rel.max()) < composite_numba.DECODE_MARGIN / 16


@pytest.mark.parametrize("limit", ["MAX_REGISTERS", "leaves"])
def test_unsupported_programs_fall_back(monkeypatch: pytest.MonkeyPatch, limit: str) -> None:
    if limit == "MAX_REGISTERS":
        monkeypatch.setattr(fused, "MAX_REGISTERS", 2)
    else:
        monkeypatch.setattr(composite_numba, "MAX_LEAVES64", 0)
    _assert_bit_identical(_source("tile"), 32, 32, f"tile/{limit}")


@pytest.mark.parametrize("seed", range(40))
def test_random_programs_are_bit_identical(seed: int) -> None:
    _assert_bit_identical(random_program(seed), 24, 20, f"random{seed}")


@pytest.mark.parametrize("radius", [(8.0, 8.0), (2.5, 0.0), (0.0, 3.0), (1.75, 4.25)])
@pytest.mark.parametrize("shape", [(37, 53), (1, 9), (9, 1), (2, 2), (1, 1)])
def test_relief_kernels_are_bit_identical(
    shape: tuple[int, int], radius: tuple[float, float]
) -> None:
    rng = np.random.default_rng(shape[0] * 100 + shape[1])
    height = (rng.random(shape) * 0.05 - 0.01).astype(np.float32)
    dx, dy = 2.0 / shape[1], 1.5 / shape[0]
    np.testing.assert_array_equal(
        relief_numba.normals(height, dx, dy), relief.normals(height, dx, dy)
    )
    np.testing.assert_array_equal(
        relief_numba.ambient_occlusion(height, dx, *radius),
        relief.ambient_occlusion(height, dx, *radius),
    )


def test_auto_backend_is_numba_for_large_requests() -> None:
    from matloom.engine.session import Session

    session = Session()
    assert session_backend(session, "auto", 4096 * 4096).name == get_backend("auto").name
    assert session_backend(session, "numpy", 4096 * 4096).name == "numpy"


# --------------------------------------------------------------------------------------------
# Seed sweep


@pytest.mark.parametrize("name", SWEEP_PROGRAMS + ["nan_inf_fields", "all_channels"])
def test_sweep_candidate_zero_matches_preview(name: str) -> None:
    text = _source(name)
    result = run_sweep(text, variants=2, size=64, jobs=2, keep=3)
    original = dict(result.top_images)[0]
    preview = matloom.preview(text, 64)
    diff = np.abs(original.astype(np.int16) - preview.astype(np.int16))
    assert diff.max() <= 1, f"{name}: candidate 0 differs by {diff.max()} levels"
    assert np.count_nonzero(diff) <= diff.size // 100


def test_sweep_variants_match_their_previews() -> None:
    """Candidate k of a chunk is the preview of variant k's text (within one level)."""
    text = _source("brick")
    result = run_sweep(text, variants=3, size=48, jobs=1, keep=4)
    canonical = matloom.format(text)
    for index, image in result.top_images:
        preview = matloom.preview(variant_program(canonical, index, 3), 48)
        assert np.abs(image.astype(np.int16) - preview.astype(np.int16)).max() <= 1


def test_sweep_buffers_stay_clean_after_nan_coverage() -> None:
    """One shading thread reuses its buffers without re-zeroing the channels no layer writes:
    a candidate whose coverage is NaN somewhere touches them (NaN x 0), but only where its
    coverage is NaN, where 0 is written; the next candidate must match its exact preview."""
    text = (
        "View(0, 0, 1, 1)\nMaterial(\n  Layer(1).basecolor(40, 40, 200).roughness(0.6),\n"
        "  Layer(Sqrt(fBm(octaves=1, base_freq=0.6, to_01=True, seed=3) - 0.5))"
        ".basecolor(220, 30, 30)\n)"
    )
    canonical = matloom.format(text)
    variants = [variant_program(canonical, k, 12) for k in range(13)]
    nan_coverage = [bool(np.isnan(evaluate(v, 24, 24).alpha).any()) for v in variants]
    assert any(nan_coverage) and not all(nan_coverage)  # both kinds, in sequence
    result = run_sweep(text, variants=12, size=24, jobs=1, keep=13)
    for index, image in result.top_images:
        preview = matloom.preview(variants[index], 24)
        assert np.abs(image.astype(np.int16) - preview.astype(np.int16)).max() <= 1, index


class MeanRedScorer:
    """Deterministic test scorer: mean red level of each image."""

    name = "test-mean-red"

    def score(self, images: list[np.ndarray], text: str) -> np.ndarray:
        del text
        return np.array([float(img[..., 0].mean()) for img in images])


def _scorers() -> list[object]:
    scorers: list[object] = [MeanRedScorer()]
    try:
        from matloom.author.scorers.lookup import get_scorer

        scorers.append(get_scorer("test-brightness"))
    except (ImportError, KeyError, RuntimeError):
        pass
    return scorers


@pytest.mark.parametrize("scorer", _scorers(), ids=lambda s: s.name)
def test_sweep_is_reproducible(scorer: object) -> None:
    text = _source("tile")
    first = run_sweep(text, variants=12, size=32, scorer=scorer, prompt="red", seed=7, jobs=2)
    again = run_sweep(text, variants=12, size=32, scorer=scorer, prompt="red", seed=7, jobs=1)
    assert first.best_index == again.best_index
    assert first.best_program == again.best_program
    assert [c.score for c in first.candidates] == [c.score for c in again.candidates]
    other = run_sweep(text, variants=12, size=32, scorer=scorer, prompt="red", seed=8, jobs=2)
    assert [c.score for c in other.candidates][1:] != [c.score for c in first.candidates][1:]
    scores = [c.score for c in first.candidates]
    assert first.best_index == max(range(len(scores)), key=lambda i: (scores[i], -i))


def test_seed_free_program_sweeps_as_one_candidate() -> None:
    result = run_sweep(_source("bricks"), variants=50, size=32)
    assert result.n_candidates == 1 and result.seed_free
    assert "single candidate" in result.message


def test_program_whose_seeds_feed_no_output_sweeps_as_one_candidate() -> None:
    text = (
        "View(0, 0, 2, 2)\nDefine(unused, fBm(octaves=3, base_freq=4, seed=77))\n"
        "Material(Layer(1).basecolor(200, 30, 30).roughness(0.4))"
    )
    result = run_sweep(text, variants=20, size=32)
    assert result.n_candidates == 1 and result.seed_free
    assert "single candidate" in result.message
    used = text.replace("roughness(0.4)", "roughness(unused)")
    assert run_sweep(used, variants=20, size=32).n_candidates == 21


def test_sweep_falls_back_for_unsupported_programs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(fused, "MAX_REGISTERS", 2)
    text = _source("tile")
    result = run_sweep(text, variants=1, size=32, keep=2)
    preview = matloom.preview(text, 32)
    assert np.array_equal(dict(result.top_images)[0], preview)


def test_sweep_honours_its_backend() -> None:
    """``numpy`` previews every variant with the exact numpy engine; ``numba`` and ``auto`` use
    the kernels (the same previews here); an unknown name is refused before any work."""
    text = _source("brick")
    exact = run_sweep(text, variants=2, size=32, jobs=1, keep=3, backend="numpy")
    canonical = matloom.format(text)
    for index, image in exact.top_images:
        preview = matloom.preview(variant_program(canonical, index, 2), 32, backend="numpy")
        assert np.array_equal(image, preview), index
    kernels = run_sweep(text, variants=2, size=32, jobs=1, keep=3, backend="numba")
    auto = run_sweep(text, variants=2, size=32, jobs=1, keep=3)
    for (i, a), (j, b) in zip(kernels.top_images, auto.top_images, strict=True):
        assert i == j and np.array_equal(a, b)
    with pytest.raises(ValueError, match="unknown sweep backend"):
        run_sweep(text, variants=2, size=32, backend="cuda")


def test_sweep_and_evaluate_work_without_numba() -> None:
    """numba is optional: the sweep then previews each variant with the numpy engine."""
    import os
    import subprocess
    import sys

    code = (
        "import sys; sys.modules['numba'] = None\n"
        "import numpy as np, matloom\n"
        "from matloom.engine.schedules.sweep import run_sweep\n"
        "from matloom.render.preview import ShadeParams\n"
        f"text = open({str(DATA / 'tile.mat')!r}).read()\n"
        "r = run_sweep(text, variants=2, shading=ShadeParams.of(), size=24, keep=3)\n"
        "assert r.n_candidates == 3\n"
        "assert np.array_equal(dict(r.top_images)[0], matloom.preview(text, 24))\n"
        "print('ok')\n"
    )
    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root)}
    env.pop("MATLOOM_BACKEND", None)
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert result.stdout.strip() == "ok"
