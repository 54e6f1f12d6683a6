"""The engine reads the channel layout: RawLayer, MaterialMaps and the compositing kernel's slots.

The kernel freezes the layout's slot and plane numbers when numba compiles it; these tests check
the compiled constants and route every registry channel through the kernel on its own.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from matloom.engine import composite
from matloom.engine.composite import RawLayer
from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps
from matloom.vocab import CHANNELS
from matloom.vocab.layout import LAYOUT, Group


def test_raw_layer_fields_and_defaults_are_the_registry_channels() -> None:
    layer = RawLayer()
    assert [f.name for f in dataclasses.fields(RawLayer)] == list(CHANNELS)
    for name, spec in CHANNELS.items():
        expected = spec.defaults[0] if spec.arity == 1 else spec.defaults
        assert getattr(layer, name) == expected, name
    with pytest.raises(TypeError):
        RawLayer(1.0)  # keyword-only: the field order is not an interface
    layer.set("emissive", [1.0, 2.0, 3.0, 4.0])
    layer.set("roughness", [0.5])
    assert layer.emissive == (1.0, 2.0, 3.0, 4.0) and layer.roughness == 0.5
    assert len(layer.blended_values()) == sum(
        c.arity for c in LAYOUT.channels if c.group not in (Group.COVERAGE, Group.MAX)
    )


def test_material_maps_fields_are_the_layout_fields() -> None:
    names = [f.name for f in dataclasses.fields(MaterialMaps)]
    assert names == [*LAYOUT.map_fields, "view", "n_layers"]
    assert ARRAY_FIELDS == LAYOUT.map_fields


# --------------------------------------------------------------------------------------------
# The compiled kernel

numba = pytest.importorskip("numba")

from matloom.engine.kernels import composite_numba as K  # noqa: E402
from matloom.engine.schedules import banded as fused  # noqa: E402


def test_compiled_kernel_constants_follow_the_layout() -> None:
    """What the compiled (possibly cached) kernels see equals the layout's tables."""
    scalars, colours, maxed = LAYOUT.scalars, LAYOUT.colours, LAYOUT.maxed
    (strength,) = [c.slots[3] for c in colours if c.group is Group.COLOUR_STRENGTH]
    expected = (
        LAYOUT.n_slots,
        LAYOUT.n_planes,
        LAYOUT.n_map_planes,
        LAYOUT.coverage.slots[0],
        strength,
        tuple(c.slots[0] for c in scalars),
        tuple(c.planes[0] for c in scalars),
        tuple(s for c in colours for s in c.slots[:3]),
        tuple(p for c in colours for p in c.planes),
        tuple(c.slots[0] for c in maxed),
        tuple(c.planes[0] for c in maxed),
    )
    assert K.frozen_layout() == expected
    # every slot is read by exactly one kernel table
    read = {K.CH_ALPHA, K.CH_STRENGTH, *K.SCALAR_SLOTS, *K.COLOUR_SLOTS, *K.MAX_SLOTS}
    assert sorted(read) == list(range(K.N_CHANNELS))
    # and every plane written once, the 2-D ones first
    written = [0, *K.SCALAR_PLANES, *K.MAX_PLANES, *K.COLOUR_PLANES]
    assert sorted(written) == list(range(K.N_PLANES))
    assert max(0, *K.SCALAR_PLANES, *K.MAX_PLANES) == K.N_MAP_PLANES - 1
    ior = K.SCALAR_SLOTS.index(LAYOUT.slot("ior"))
    assert K.SCALAR_LO[ior] == 1.0 and K.SCALAR_HI[ior] == np.inf  # ior: below at 1
    angle = K.SCALAR_SLOTS.index(LAYOUT.slot("anisotropy_angle"))
    assert K.SCALAR_LO[angle] == -np.inf and K.SCALAR_HI[angle] == np.inf  # unclamped


H, W = 5, 7


def _varying(channel_name: str, arg: int) -> np.ndarray:
    """A distinct float64 field per channel argument, spanning the channel's search range."""
    lo, hi = CHANNELS[channel_name].search or (0.0, 1.0)
    ramp = (np.arange(H * W, dtype=np.float64).reshape(H, W) * (0.37 + 0.11 * arg)) % 1.0
    return lo + (hi - lo) * ramp


def _layers(name: str | None) -> list[RawLayer]:
    """Two partly covering layers; the top one writes ``name`` (if any)."""
    top: dict[str, object] = {"alpha": 0.25 + 0.5 * _varying("alpha", 3)}
    if name is not None:
        values = tuple(_varying(name, k) for k in range(CHANNELS[name].arity))
        top[name] = values[0] if len(values) == 1 else values
    return [RawLayer(alpha=0.5, basecolor=(120.0, 90.0, 60.0), height=0.01), RawLayer(**top)]


def _kernel_maps(layers: list[RawLayer]) -> dict[str, np.ndarray]:
    prog = fused.compile_layers(layers, (H, W))
    maps = fused.allocate_maps(W, H)
    flags = np.zeros((H, W), np.uint8)
    fused.run_kernel(prog, maps, 0, flags)
    found = fused._flagged(layers, flags, 0)
    fused._recomposite(maps, [found] if found is not None else [])
    return maps


def _bits(array: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(array, np.float32).view(np.uint32)


@pytest.mark.parametrize("name", list(CHANNELS))
def test_each_channel_reaches_its_own_map_through_the_kernel(name: str) -> None:
    """A layer writing one channel (varying values, RAW slots) changes that channel's map and
    no other one, and the kernel's maps equal the numpy compositing's bit for bit."""
    with np.errstate(all="ignore"):
        ours, without = _kernel_maps(_layers(name)), _kernel_maps(_layers(None))
        reference = composite.allocate_maps(W, H)
        composite.composite_band(_layers(name), reference, slice(0, H))
    for field_name in reference:
        assert np.array_equal(_bits(ours[field_name]), _bits(reference[field_name])), field_name
    own = LAYOUT[name].field
    assert not np.array_equal(ours[own], without[own])
    if LAYOUT[name].group is not Group.COVERAGE:
        for field_name in reference:
            if field_name != own:
                assert np.array_equal(_bits(ours[field_name]), _bits(without[field_name])), (
                    field_name
                )
