"""The channel layout is derived from the registry: today's orders, and a new channel for free."""

from __future__ import annotations

import dataclasses

import pytest

from matloom.vocab import CHANNELS, ChannelSpec
from matloom.vocab.layout import EXPORT_RULES, LAYOUT, ExportRule, Group, build_layout
from matloom.vocab.spec import Blend, ValueKind

# The engine's tables, written out once here to prove the derivation keeps them (the language-2
# channel anisotropy_angle took the next "other scalar" slot and plane after ior).
SLOTS = {
    "alpha": (0,),
    "basecolor": (1, 2, 3),
    "metallic": (4,),
    "roughness": (5,),
    "sheen": (6,),
    "coat": (7,),
    "transmission": (8,),
    "subsurface": (9,),
    "anisotropy": (10,),
    "ior": (11,),
    "anisotropy_angle": (12,),
    "emissive": (13, 14, 15, 16),
    "height": (17,),
}
PLANES = {
    "alpha": (0,),
    "metallic": (1,),
    "roughness": (2,),
    "sheen": (3,),
    "coat": (4,),
    "transmission": (5,),
    "subsurface": (6,),
    "anisotropy": (7,),
    "ior": (8,),
    "anisotropy_angle": (9,),
    "height": (10,),
    "basecolor": (11, 12, 13),
    "emissive": (14, 15, 16),
}
UNIT = ("metallic", "roughness", "sheen", "coat", "transmission", "subsurface", "anisotropy")
MAP_FIELDS = (
    "basecolor_linear",
    "alpha",
    *UNIT,
    "ior",
    "anisotropy_angle",
    "emissive_linear",
    "height",
    "normal",
    "ao",
)
LINEAR = "linear (non-color)"
EXPORT_ROWS = [
    (
        "basecolor",
        "basecolor.png",
        "png8-rgba",
        "sRGB (RGB); alpha is linear coverage",
        ("basecolor_linear", "alpha"),
        "base colour (value_range: the linear colour before encoding); A = total coverage",
    ),
    ("metallic", "metallic.png", "png8-grey", LINEAR, ("metallic",), "metalness 0..1"),
    ("roughness", "roughness.png", "png8-grey", LINEAR, ("roughness",), "roughness 0..1"),
    ("sheen", "sheen.png", "png8-grey", LINEAR, ("sheen",), "sheen weight 0..1"),
    ("coat", "coat.png", "png8-grey", LINEAR, ("coat",), "clear-coat weight 0..1"),
    (
        "transmission",
        "transmission.png",
        "png8-grey",
        LINEAR,
        ("transmission",),
        "transmission weight 0..1",
    ),
    (
        "subsurface",
        "subsurface.png",
        "png8-grey",
        LINEAR,
        ("subsurface",),
        "subsurface weight 0..1",
    ),
    (
        "anisotropy",
        "anisotropy.png",
        "png8-grey",
        LINEAR,
        ("anisotropy",),
        "anisotropy magnitude 0..1 (brush lines along tangent/X rotated by anisotropy_angle; "
        "the highlight stretches across them)",
    ),
    ("ior", "ior.exr", "exr-float32", LINEAR, ("ior",), "index of refraction"),
    (
        "anisotropy_angle",
        "anisotropy_angle.png",
        "png8-grey",
        LINEAR,
        ("anisotropy_angle",),
        "brushing direction (the brush lines run along it; the highlight stretches across it, "
        "at angle + 90), degrees counter-clockwise from +x (tangent/X) toward +y (up); axial, so angle and angle + 180 are the same; layers blend the angle "
        "linearly (value_range: the blended degrees)",
    ),
    (
        "emissive",
        "emissive.exr",
        "exr-float32",
        "linear RGB (scene-referred, unclipped)",
        ("emissive_linear",),
        "emitted radiance = linear colour x strength",
    ),
    (
        "height",
        "height.exr",
        "exr-float32",
        LINEAR,
        ("height",),
        "height in coordinate units (may be negative)",
    ),
    (
        "normal",
        "normal_gl.png",
        "png8-rgb",
        LINEAR,
        ("normal",),
        "tangent-space normal, OpenGL convention (+Y up), encoded n * 0.5 + 0.5",
    ),
    ("ao", "ao.png", "png8-grey", LINEAR, ("ao",), "ambient occlusion, 1 = unoccluded"),
]
BLENDED = (
    "basecolor",
    "metallic",
    "roughness",
    "sheen",
    "coat",
    "transmission",
    "ior",
    "subsurface",
    "anisotropy",
    "anisotropy_angle",
    "emissive",
)


def _rows(layout: object) -> list[tuple[object, ...]]:
    return [
        (m.name, m.file_name, m.encoding, m.colour_space, m.sources, m.meaning)
        for m in layout.maps  # type: ignore[attr-defined]
    ]


def test_layout_keeps_the_engine_tables() -> None:
    assert {c.name: c.slots for c in LAYOUT.channels} == SLOTS
    assert {c.name: c.planes for c in LAYOUT.channels} == PLANES
    assert (LAYOUT.n_slots, LAYOUT.n_planes, LAYOUT.n_map_planes) == (18, 17, 11)
    assert LAYOUT.map_fields == MAP_FIELDS
    assert LAYOUT.plane_fields == ("alpha", *UNIT, "ior", "anisotropy_angle", "height")
    assert tuple(c.name for c in LAYOUT.unit_scalars) == UNIT
    assert _rows(LAYOUT) == EXPORT_ROWS
    assert LAYOUT.blended == BLENDED
    assert LAYOUT.outputs == ("alpha", *BLENDED, "height", "normal", "ao")


def test_every_registry_channel_has_a_place() -> None:
    assert tuple(c.name for c in LAYOUT.channels) == tuple(CHANNELS)
    for channel in LAYOUT.channels:
        assert len(channel.slots) == channel.spec.arity
        assert channel.default == (
            channel.spec.defaults[0] if channel.arity == 1 else channel.spec.defaults
        )
    slots = sorted(s for c in LAYOUT.channels for s in c.slots)
    planes = sorted(p for c in LAYOUT.channels for p in c.planes)
    assert slots == list(range(LAYOUT.n_slots)) and planes == list(range(LAYOUT.n_planes))
    assert LAYOUT["alpha"].group is Group.COVERAGE and LAYOUT["height"].group is Group.MAX
    assert LAYOUT["ior"].group is Group.SCALAR and LAYOUT["emissive"].kind is (
        ValueKind.COLOUR_STRENGTH
    )


def _extended(*extra: ChannelSpec) -> list[ChannelSpec]:
    """A copy of the registry with channels inserted before height (as a new entry would be)."""
    specs = list(CHANNELS.values())
    return specs[:-1] + list(extra) + specs[-1:]


def test_a_new_scalar_channel_needs_only_its_registry_entry() -> None:
    gloss = ChannelSpec(
        "gloss", ("value",), (0.25,), "0..1", "specular gloss", ".gloss(0.5)", map_doc="gloss 0..1"
    )
    layout = build_layout(_extended(gloss))
    new = layout["gloss"]
    assert new.group is Group.UNIT and new.field == "gloss" and new.default == 0.25
    # the next [0, 1] slot and plane; the later ones move up by one
    assert new.slots == (11,) and new.planes == (8,)
    assert layout["ior"].slots == (12,) and layout["emissive"].slots == (14, 15, 16, 17)
    assert layout["height"].slots == (18,) and layout.n_slots == 19
    assert layout["ior"].planes == (9,) and layout["height"].planes == (11,)
    assert layout["basecolor"].planes == (12, 13, 14) and layout.n_planes == 18
    assert layout.n_map_planes == 12 and "gloss" in layout.plane_fields
    assert layout.map_fields == (*MAP_FIELDS[:9], "gloss", *MAP_FIELDS[9:])
    assert tuple(c.name for c in layout.scalars) == (*UNIT, "gloss", "ior", "anisotropy_angle")
    rows = _rows(layout)
    assert rows[8] == ("gloss", "gloss.png", "png8-grey", LINEAR, ("gloss",), "gloss 0..1")
    assert rows[:8] + rows[9:] == EXPORT_ROWS  # nothing else changes
    assert layout.blended == (*BLENDED, "gloss")
    assert layout.outputs[-4:] == ("gloss", "height", "normal", "ao")
    assert layout.fingerprint != LAYOUT.fingerprint


def test_new_channels_of_other_kinds_get_their_kinds_defaults() -> None:
    depth = ChannelSpec(
        "depth", ("value",), (0.0,), "units", "unclamped depth", ".depth(1)", clamp_lo=None,
        clamp_hi=None,
    )  # fmt: skip
    tint = ChannelSpec(
        "tint", ("r", "g", "b"), (255.0, 255.0, 255.0), "sRGB", "sheen tint", ".tint(1, 2, 3)",
        clamp_hi=255, colour_args=(0, 1, 2),
    )  # fmt: skip
    layout = build_layout(_extended(depth, tint))
    # colours come after basecolor, other scalars after ior (registry order within a group)
    assert layout["tint"].group is Group.COLOUR and layout["tint"].field == "tint_linear"
    assert layout["tint"].slots == (4, 5, 6) and layout["metallic"].slots == (7,)
    assert layout["depth"].group is Group.SCALAR and layout["depth"].slots == (16,)
    assert layout["depth"].planes == (10,) and layout["height"].planes == (11,)
    assert layout["tint"].planes == (15, 16, 17) and layout["emissive"].planes == (18, 19, 20)
    by_name = {m.name: m for m in layout.maps}
    assert (by_name["depth"].file_name, by_name["depth"].encoding) == ("depth.exr", "exr-float32")
    assert by_name["depth"].meaning == "unclamped depth"  # map_doc defaults to the doc
    assert (by_name["tint"].encoding, by_name["tint"].writer) == ("png8-rgb", "srgb8")
    assert layout.components("tint_linear") == 3 and layout.components("depth") == 1


def test_registries_the_engine_cannot_composite_are_refused() -> None:
    alpha = CHANNELS["alpha"]
    with pytest.raises(ValueError, match="exactly one coverage"):
        build_layout(_extended(dataclasses.replace(alpha, name="alpha2")))
    loose = [dataclasses.replace(alpha, clamp_hi=2.0), *list(CHANNELS.values())[1:]]
    with pytest.raises(ValueError, match="coverage is clamped"):
        build_layout(loose)


def test_max_channels_are_unclamped_scalars() -> None:
    clamped = dataclasses.replace(CHANNELS["height"], name="bump", clamp_lo=0.0, clamp_hi=1.0)
    with pytest.raises(ValueError, match="unclamped"):
        build_layout(_extended(clamped))
    assert CHANNELS["height"].blend is Blend.MAX


def test_periodic_export_rule_with_a_float_copy() -> None:
    """anisotropy_angle: an 8-bit PNG of (angle mod 180) / 180 plus the degrees as EXR."""
    by_name = {m.name: m for m in LAYOUT.maps}
    angle = by_name["anisotropy_angle"]
    assert (angle.writer, angle.period, angle.float_file) == (
        "periodic8",
        180.0,
        "anisotropy_angle.exr",
    )
    assert angle.file_names == ("anisotropy_angle.png", "anisotropy_angle.exr")
    described = angle.describe()
    assert described["float_file"] == "anisotropy_angle.exr"
    assert described["float_encoding"] == "exr-float32" and "180" in described["decode"]
    assert "decode" not in by_name["roughness"].describe()
    assert by_name["roughness"].file_names == ("roughness.png",)
    # the same rule on a new channel of a registry copy
    spin = ChannelSpec(
        "spin", ("degrees",), (0.0,), "degrees", "spin", ".spin(1)", clamp_lo=None, clamp_hi=None
    )
    rules = {
        **EXPORT_RULES,
        "spin": ExportRule(encoding="png8-grey", period=360.0, float_copy=True),
    }
    new = {m.name: m for m in build_layout(_extended(spin), rules).maps}["spin"]
    assert (new.file_name, new.writer, new.period, new.float_file) == (
        "spin.png",
        "periodic8",
        360.0,
        "spin.exr",
    )


def test_export_rules_the_exporter_cannot_write_are_refused() -> None:
    with pytest.raises(ValueError, match="periodic"):
        build_layout(CHANNELS, {**EXPORT_RULES, "emissive": ExportRule(period=1.0)})
    with pytest.raises(ValueError, match="already a float EXR"):
        build_layout(CHANNELS, {**EXPORT_RULES, "ior": ExportRule(float_copy=True)})
