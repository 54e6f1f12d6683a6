"""The language-2 channel ``.anisotropy_angle(degrees)``: registry entry, language front end,
evaluation on every backend (bit-identical), linear blending between layers, default 0."""

from __future__ import annotations

import re

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends
from matloom.engine.composite import RawLayer, composite
from matloom.engine.evaluate import evaluate
from matloom.engine.maps import ARRAY_FIELDS, NEWER_FIELDS, MaterialMaps, View
from matloom.lang.random_program import RandomConfig, random_program
from matloom.vocab import CHANNELS
from matloom.vocab.layout import LAYOUT, Group
from matloom.vocab.spec import ValueKind

BACKENDS = available_backends()

#: Two layers: an opaque base at 30 degrees and a half-covering top whose angle varies over
#: the swatch, unclamped (-90 .. 630 degrees).
VARYING = """Material(
  Layer(1)
    .anisotropy(0.7)
    .anisotropy_angle(30),
  Layer(0.5 + 0.4 * Sin(X() * 9))
    .anisotropy(0.4)
    .anisotropy_angle(X() * 720 - 90 + Y() * 3)
)"""


def _bits(array: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(array, np.float32).view(np.uint32)


def test_registry_entry() -> None:
    spec = CHANNELS["anisotropy_angle"]
    assert spec.since == 2 and spec.arg_names == ("degrees",) and spec.defaults == (0.0,)
    assert (spec.clamp_lo, spec.clamp_hi) == (None, None)  # unclamped: blended linearly
    assert spec.kind is ValueKind.SCALAR and spec.search == (0, 180)
    channel = LAYOUT["anisotropy_angle"]
    assert channel.group is Group.SCALAR and channel.field == "anisotropy_angle"
    assert NEWER_FIELDS == ("anisotropy_angle",)
    assert "anisotropy_angle" in ARRAY_FIELDS and "anisotropy_angle" in LAYOUT.blended


def test_parses_checks_and_formats() -> None:
    src = "Material(Layer(1).anisotropy_angle(45).anisotropy(0.6))"
    assert not [d for d in matloom.check(src) if d.is_error]
    text = matloom.format(matloom.parse(src))
    # canonical order: right after .anisotropy
    assert text == "Material(\n  Layer(1)\n    .anisotropy(0.6)\n    .anisotropy_angle(45)\n)"
    assert matloom.format(matloom.parse(text)) == text
    assert not [d for d in matloom.check(VARYING) if d.is_error]
    wrong = matloom.check("Material(Layer(1).anisotropy_angle(3, 4))")
    assert any(d.is_error and "anisotropy_angle" in d.format() for d in wrong)
    typo = matloom.check("Material(Layer(1).anisotropy_angel(3))")
    assert any("did you mean `anisotropy_angle`" in d.format() for d in typo)


def test_only_language_2_random_programs_draw_it() -> None:
    assert not any(
        "anisotropy_angle" in random_program(s, config=RandomConfig(language=1)) for s in range(20)
    )
    assert any("anisotropy_angle" in random_program(s) for s in range(20))


@pytest.mark.parametrize("backend", BACKENDS)
def test_varying_angle_evaluates_and_changes_no_other_map(backend: str) -> None:
    with_angle = evaluate(VARYING, 40, 24, backend=backend)
    plain = re.sub(r"\n\s*\.anisotropy_angle\([^\n]*\)(,?)$", r"\1", VARYING, flags=re.M)
    assert "anisotropy_angle" not in plain
    without = evaluate(plain, 40, 24, backend=backend)
    angle = with_angle.anisotropy_angle
    assert angle.dtype == np.float32 and angle.shape == (24, 40)
    assert angle.min() < 0 and angle.max() > 360  # unclamped
    for name in ARRAY_FIELDS:
        if name != "anisotropy_angle":
            assert np.array_equal(_bits(getattr(with_angle, name)), _bits(getattr(without, name)))


def test_backends_are_bit_identical(monkeypatch: pytest.MonkeyPatch) -> None:
    if len(BACKENDS) < 2:
        pytest.skip("one backend only")
    compiled: list[object] = []
    if "numba" in BACKENDS:  # the fused compositing kernel takes the program (no fallback)
        from matloom.engine.schedules import banded

        original = banded.compile_layers

        def spy(*args: object, **kwargs: object) -> object:
            compiled.append(original(*args, **kwargs))
            return compiled[-1]

        monkeypatch.setattr(banded, "compile_layers", spy)
    results = [evaluate(VARYING, 37, 29, backend=b) for b in BACKENDS]
    assert compiled or "numba" not in BACKENDS
    for other in results[1:]:
        for name in ARRAY_FIELDS:
            a, b = getattr(results[0], name), getattr(other, name)
            assert np.array_equal(_bits(a), _bits(b)), name


@pytest.mark.parametrize("backend", BACKENDS)
def test_layers_blend_the_angle_linearly(backend: str) -> None:
    """Over rule, like every blended scalar: sum(V_i * angle_i) / A, no wrap-around."""
    src = "Material(\n  Layer(1).anisotropy_angle(170),\n  Layer(0.25).anisotropy_angle(10)\n)"
    maps = evaluate(src, 4, 3, backend=backend)
    # V_top = 0.25, V_bottom = 0.75: 0.75 * 170 + 0.25 * 10 = 130 (not the axial mean 175)
    assert np.all(maps.anisotropy_angle == np.float32(130.0))
    half = "Material(\n  Layer(0.5).anisotropy_angle(-400),\n  Layer(0)\n)"
    # a lone half-covering layer: its own value, unclamped and unreduced
    assert np.all(evaluate(half, 3, 2, backend=backend).anisotropy_angle == np.float32(-400.0))


def test_numpy_compositing_formula() -> None:
    """The numpy compositing against the over rule written out in float32."""
    rng = np.random.default_rng(5)
    a_top = rng.random((6, 5)).astype(np.float32)
    angles = (rng.random((2, 6, 5)) * 720 - 360).astype(np.float32)
    layers = [
        RawLayer(alpha=1.0, anisotropy_angle=angles[0]),
        RawLayer(alpha=a_top, anisotropy_angle=angles[1]),
    ]
    maps = composite(layers, 5, 6, View())
    v_top = a_top * np.float32(1)
    v_bottom = np.float32(1) * (np.float32(1) - a_top)
    expected = (v_bottom * angles[0] + v_top * angles[1]) / np.float32(1)
    assert np.array_equal(_bits(maps.anisotropy_angle), _bits(expected))


@pytest.mark.parametrize("backend", BACKENDS)
def test_default_is_zero_everywhere_when_unused(backend: str) -> None:
    src = "Material(\n  Layer(X()).anisotropy(0.8).metallic(1),\n  Layer(Sqrt(Y() - 0.5))\n)"
    with np.errstate(all="ignore"):
        maps = evaluate(src, 16, 12, backend=backend)
    assert np.isnan(maps.alpha).any()  # a NaN coverage does not leak into the unused map
    assert np.array_equal(_bits(maps.anisotropy_angle), np.zeros((12, 16), np.uint32))  # +0.0


def test_from_arrays_fills_only_newer_zero_default_maps() -> None:
    arrays = {name: np.ones((2, 3) + ((3,) if LAYOUT.components(name) == 3 else ()), np.float32)
              for name in ARRAY_FIELDS}  # fmt: skip
    del arrays["anisotropy_angle"]
    maps = MaterialMaps.from_arrays(arrays)
    assert maps.anisotropy_angle.shape == (2, 3) and not maps.anisotropy_angle.any()
    del arrays["anisotropy"]  # a language-1 map is never invented
    with pytest.raises(KeyError):
        MaterialMaps.from_arrays(arrays)
