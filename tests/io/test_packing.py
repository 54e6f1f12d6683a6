"""Packed textures hold the maps their :class:`~matloom.vocab.packing.Packing` names (the
layout ``matloom blender`` splits them by)."""

from __future__ import annotations

import numpy as np
import pytest

from matloom.blender.packed import PACKINGS
from matloom.io import png
from matloom.vocab.packing import MASK_MAP, ORM


@pytest.mark.parametrize("preset", ["gltf", "godot", "mtlx", "unity", "unreal", "usd"])
def test_packed_textures_hold_the_maps_their_packing_names(render_presets, preset: str) -> None:
    maps, result = render_presets("full", presets=[preset])
    packing = MASK_MAP if preset == "unity" else ORM
    assert dict(PACKINGS).get(preset, packing) is packing
    item = result.manifest["presets"][preset]["files"][packing.role]
    assert item["channels"] == packing.description
    pixels = png.read_png(result.out_dir / preset / item["file"]).astype(int)
    for packed in packing.maps:
        values = getattr(maps, packed.map)
        want = png.quantize_unit8(1 - values if packed.inverted else values).astype(int)
        np.testing.assert_array_equal(pixels[..., "RGBA".index(packed.channel)], want)
