"""Layer channels (methods) in the reference's fixed order (reference-engine.md §1.2, §3.1).

Each entry is the whole description of a channel: :mod:`matloom.vocab.layout` derives from these
specs the kernel slots, the ``MaterialMaps`` fields, the export rows and the dependency classes.
"""

from __future__ import annotations

from matloom.vocab.spec import Blend, ChannelSpec

C = ChannelSpec

#: ``anisotropy_angle`` is the brushing direction an artist writes (the brush lines run along
#: it). Real grooves spread the normals across themselves, so the highlight stretches across the
#: lines. Every consumer's anisotropy direction (glTF KHR_materials_anisotropy, Blender's
#: tangent, OpenPBR's tangent, the lit preview's GGX tangent) is the direction of the *larger*
#: roughness, i.e. of the stretch: each gets ``anisotropy_angle + ANISOTROPY_STRETCH_OFFSET_DEG``.
ANISOTROPY_STRETCH_OFFSET_DEG = 90.0

CHANNELS: dict[str, ChannelSpec] = {
    c.name: c
    for c in (
        C(
            "alpha",
            ("alpha",),
            (1.0,),
            "coverage 0..1",
            "coverage of the layer; overrides the Layer(...) argument",
            ".alpha(0.5)",
            blend=Blend.COVERAGE,
            search=(0, 1),
        ),
        C(
            "basecolor",
            ("r", "g", "b"),
            (0.0, 0.0, 0.0),
            "sRGB 0..255",
            "base colour; each component may be an expression",
            ".basecolor(200, 120, 80)",
            map_doc="base colour (value_range: the linear colour before encoding); A = total coverage",
            clamp_lo=0,
            clamp_hi=255,
            search=(0, 255),
            colour_args=(0, 1, 2),
        ),
        C(
            "metallic",
            ("value",),
            (0.0,),
            "0..1",
            "metalness (1 = metal)",
            ".metallic(1)",
            map_doc="metalness 0..1",
            search=(0, 1),
        ),
        C(
            "roughness",
            ("value",),
            (0.0,),
            "0..1",
            "micro-surface roughness (0 = mirror, the default; 1 = fully matte)",
            ".roughness(0.6)",
            map_doc="roughness 0..1",
            search=(0, 1),
        ),
        C(
            "sheen",
            ("value",),
            (0.0,),
            "0..1",
            "cloth-like grazing sheen",
            ".sheen(0.4)",
            map_doc="sheen weight 0..1",
            search=(0, 1),
        ),
        C(
            "coat",
            ("value",),
            (0.0,),
            "0..1",
            "clear-coat layer weight",
            ".coat(0.9)",
            map_doc="clear-coat weight 0..1",
            search=(0, 1),
        ),
        C(
            "transmission",
            ("value",),
            (0.0,),
            "0..1",
            "see-through transmission (glass, ice)",
            ".transmission(0.9)",
            map_doc="transmission weight 0..1",
            search=(0, 1),
        ),
        C(
            "ior",
            ("value",),
            (1.5,),
            ">= 1",
            "index of refraction (no upper clamp)",
            ".ior(1.45)",
            map_doc="index of refraction",
            clamp_lo=1.0,
            clamp_hi=None,
            search=(1, 3),
        ),
        C(
            "subsurface",
            ("value",),
            (0.0,),
            "0..1",
            "subsurface scattering weight (scatter colour = base colour)",
            ".subsurface(0.3)",
            map_doc="subsurface weight 0..1",
            search=(0, 1),
        ),
        C(
            "anisotropy",
            ("value",),
            (0.0,),
            "0..1",
            "anisotropic highlight of brushed metal: brush lines along x, or along "
            ".anisotropy_angle; the highlight stretches across the lines, as on real grooves",
            ".anisotropy(0.6)",
            map_doc=(
                "anisotropy magnitude 0..1 (brush lines along tangent/X rotated by "
                "anisotropy_angle; the highlight stretches across them)"
            ),
            search=(0, 1),
        ),
        C(
            "anisotropy_angle",
            ("degrees",),
            (0.0,),
            "degrees counter-clockwise from +x (unclamped; 180 is the same direction as 0)",
            "brushing direction (the direction the brush lines or grooves run); the highlight "
            "stretches across it, at angle + 90, as on real grooves; layers blend the angle "
            "linearly",
            ".anisotropy_angle(45)",
            map_doc=(
                "brushing direction (the brush lines run along it; the highlight stretches "
                "across it, at angle + 90), degrees counter-clockwise from +x (tangent/X) toward "
                "+y (up); axial, so angle and angle + 180 are the same; layers blend the angle "
                "linearly (value_range: the blended degrees)"
            ),
            clamp_lo=None,
            clamp_hi=None,
            search=(0, 180),
            since=2,
        ),
        C(
            "emissive",
            ("r", "g", "b", "strength"),
            (0.0, 0.0, 0.0, 0.0),
            "sRGB 0..255 and strength >= 0",
            "emitted light colour and strength",
            ".emissive(255, 180, 60, 2)",
            map_doc="emitted radiance = linear colour x strength",
            clamp_lo=0,
            clamp_hi=255,
            search=(0, 255),
            colour_args=(0, 1, 2),
        ),
        C(
            "height",
            ("value",),
            (0.0,),
            "coordinate units (unclamped, may be negative)",
            "surface relief; the composite is the max over covered layers",
            ".height(0.01)",
            blend=Blend.MAX,
            map_doc="height in coordinate units (may be negative)",
            clamp_lo=None,
            clamp_hi=None,
            search=(-0.5, 0.5),
        ),
    )
}
"""Name -> channel spec, in evaluation (and seed-drawing) order; alpha first."""

PRINT_ORDER: tuple[str, ...] = tuple(n for n in CHANNELS if n != "alpha")
"""Canonical order of the chained methods (alpha is printed as the Layer argument)."""
