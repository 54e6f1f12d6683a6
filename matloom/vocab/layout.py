"""The channel layout: every fact about the layer channels that the engine needs, derived once
from the registry's :class:`~matloom.vocab.spec.ChannelSpec` entries.

Readers: the numpy compositing (:mod:`matloom.engine.composite`: ``RawLayer`` fields and
defaults, conversions), the compositing and preview kernels (slot and plane indices as
module-level constants), the fused path (:mod:`matloom.engine.schedules.banded`), ``MaterialMaps``
(:mod:`matloom.engine.maps`: its array fields), the preview shading's input checks, the
exporter (:mod:`matloom.io.export`: one row per map) and the dependency analysis
(:mod:`matloom.lang.deps`). Nothing else writes a channel list.

Per channel (:class:`ChannelLayout`): its blend rule (coverage / over / max), value kind
(scalar / colour / colour+strength), clamp, kernel input slots (one per argument), output planes,
``MaterialMaps`` field and export row. Each channel falls in one *group*; the groups' orders
below reproduce the engine's historical orders, so the numba kernels keep their slot meanings:

* kernel input slots (per layer): coverage, colours, [0, 1] scalars, other scalars,
  colour+strength (r, g, b, strength), max -- today 0 alpha, 1-3 basecolor, 4-10 metallic ..
  anisotropy, 11 ior, 12 anisotropy_angle, 13-16 emissive, 17 height (18 slots);
* output planes (the kernel's accumulator rows and the sweep's planar buffer): coverage, [0, 1]
  scalars, other scalars, max, colours, colour+strength -- 0 alpha, 1-7, 8 ior, 9
  anisotropy_angle, 10 height, 11-13 basecolor, 14-16 emissive (17 planes; the first 11 are the
  2-D maps);
* ``MaterialMaps`` fields and export rows: colours, coverage, [0, 1] scalars, other scalars,
  colour+strength, max, then the maps derived from the relief channel (normal, ao).

Within a group, channels keep the registry's order. Adding a channel is a registry entry (plus an
:data:`EXPORT_RULES` entry when the default export of its kind does not fit); a new [0, 1]
scalar, for instance, gets the next [0, 1] slot and plane, a field, a grey PNG and a dependency
class with no other edit. This module imports no numpy, so the registry stays light.
"""

from __future__ import annotations

import enum
import hashlib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from matloom.vocab.channels import CHANNELS
from matloom.vocab.spec import Blend, ChannelSpec, ValueKind


class Group(enum.Enum):
    """The compositing role of a channel (its blend rule, value kind and clamp together)."""

    COVERAGE = "coverage"  # the layer's alpha: clamped to [0, 1], weights every OVER channel
    COLOUR = "colour"  # OVER, sRGB colour decoded to linear
    UNIT = "unit"  # OVER scalar clamped to [0, 1]
    SCALAR = "scalar"  # OVER scalar with another clamp (ior: below at 1) or none
    COLOUR_STRENGTH = "colour+strength"  # OVER, linear colour x max(strength, 0)
    MAX = "max"  # max over the layers with alpha > 0 and a finite value (height)


#: Kernel input slot order of the groups (see the module docstring).
SLOT_ORDER = (
    Group.COVERAGE,
    Group.COLOUR,
    Group.UNIT,
    Group.SCALAR,
    Group.COLOUR_STRENGTH,
    Group.MAX,
)
#: Output plane order of the groups: the 2-D planes first, then the colour components.
PLANE_ORDER = (
    Group.COVERAGE,
    Group.UNIT,
    Group.SCALAR,
    Group.MAX,
    Group.COLOUR,
    Group.COLOUR_STRENGTH,
)
#: ``MaterialMaps`` field and export order of the groups.
FIELD_ORDER = (
    Group.COLOUR,
    Group.COVERAGE,
    Group.UNIT,
    Group.SCALAR,
    Group.COLOUR_STRENGTH,
    Group.MAX,
)
#: The channel that normals and ambient occlusion are derived from.
RELIEF_SOURCE = "height"
#: Colour space of every map that is not a colour.
NON_COLOUR = "linear (non-color)"
#: Encoding of a map's float copy (:attr:`ExportRule.float_copy`).
FLOAT_COPY_ENCODING = "exr-float32"


@dataclass(frozen=True)
class MapSpec:
    """How one exported map is encoded and which ``MaterialMaps`` arrays it is made from.

    ``writer`` names the encoder in :mod:`matloom.io.export` (``grey8``, ``exr``, ``srgb8``,
    ``srgb8-alpha``, ``normal8``, ``periodic8``); it is not part of the manifest. ``period``
    is the period of a ``periodic8`` map (its file holds (value mod period) / period);
    ``decode`` (manifest field when set) says how to read the samples back; ``float_file``
    names a float32 EXR holding the source's raw values, written next to ``file_name``.
    """

    name: str
    file_name: str
    encoding: str
    colour_space: str
    sources: tuple[str, ...]
    meaning: str
    writer: str = "grey8"
    period: float | None = None
    decode: str = ""
    float_file: str | None = None

    @property
    def file_names(self) -> tuple[str, ...]:
        """Every file the map is written to (the float copy last)."""
        return (self.file_name,) + ((self.float_file,) if self.float_file else ())

    def describe(self) -> dict[str, Any]:
        """The manifest fields that do not depend on the data."""
        out: dict[str, Any] = {
            "file": self.file_name,
            "encoding": self.encoding,
            "colour_space": self.colour_space,
            "meaning": self.meaning,
        }
        if self.decode:
            out["decode"] = self.decode
        if self.float_file:
            out["float_file"] = self.float_file
            out["float_encoding"] = FLOAT_COPY_ENCODING
        return out


@dataclass(frozen=True)
class ExportRule:
    """Non-default export of a channel: the fields given replace those of its kind's default;
    ``with_coverage`` appends the coverage map to the sources (written as the PNG's alpha);
    ``skip`` exports no map of its own; ``period`` makes it a ``periodic8`` grey PNG of
    (value mod period) / period (an angle); ``float_copy`` also writes the raw values as a
    float32 EXR (``<name>.exr``); ``decode`` is recorded in the manifest."""

    encoding: str | None = None
    colour_space: str | None = None
    writer: str | None = None
    with_coverage: bool = False
    skip: bool = False
    period: float | None = None
    float_copy: bool = False
    decode: str | None = None


#: Export rules beyond the defaults of :func:`_default_export` (by channel name).
EXPORT_RULES: dict[str, ExportRule] = {
    "alpha": ExportRule(skip=True),  # written as basecolor.png's alpha
    "basecolor": ExportRule(
        encoding="png8-rgba",
        colour_space="sRGB (RGB); alpha is linear coverage",
        writer="srgb8-alpha",
        with_coverage=True,
    ),
    # An axial direction in degrees: the PNG holds (angle mod 180) / 180, the EXR the degrees.
    "anisotropy_angle": ExportRule(
        encoding="png8-grey",
        period=180.0,
        float_copy=True,
        decode=(
            "angle_degrees = value / 255 * 180 (axial: the angle mod 180, 255 = 180 = 0); "
            "float_file holds the blended degrees unreduced"
        ),
    ),
}


@dataclass(frozen=True)
class ChannelLayout:
    """Where one channel lives in the engine (see the module docstring)."""

    spec: ChannelSpec
    group: Group
    #: ``MaterialMaps`` field of the composited map (colours: ``<name>_linear``).
    field: str
    #: Kernel input slot of each argument, in argument order.
    slots: tuple[int, ...]
    #: Output planes (accumulator rows): 1 for scalars, 3 for colours (a strength has none).
    planes: tuple[int, ...]

    @property
    def name(self) -> str:
        return self.spec.name

    @property
    def blend(self) -> Blend:
        return self.spec.blend

    @property
    def kind(self) -> ValueKind:
        return self.spec.kind

    @property
    def arity(self) -> int:
        return self.spec.arity

    @property
    def clamp(self) -> tuple[float | None, float | None]:
        """(lo, hi) of a scalar's value (None: unbounded); colours: the authored 0..255 range."""
        return self.spec.clamp_lo, self.spec.clamp_hi

    @property
    def default(self) -> float | tuple[float, ...]:
        """The value of a layer that does not write the channel (a tuple for colours)."""
        defaults = self.spec.defaults
        return defaults[0] if self.arity == 1 else tuple(defaults)

    @property
    def components(self) -> int:
        """Components of the composited map: 1 (H, W) or 3 (H, W, 3)."""
        return len(self.planes)

    @property
    def since(self) -> int:
        """Language version that introduced the channel."""
        return self.spec.since

    @property
    def default_map_is_zero(self) -> bool:
        """True when a material whose layers never write the channel has an all-zero map
        (every default argument is 0; max-blended maps are 0 where no layer counts)."""
        return all(d == 0 for d in self.spec.defaults)


@dataclass(frozen=True)
class DerivedMap:
    """A map computed from a composited channel after compositing (normal, AO)."""

    name: str
    source: str
    components: int
    export: MapSpec


#: Maps derived from :data:`RELIEF_SOURCE`, in ``MaterialMaps`` and export order.
DERIVED: tuple[DerivedMap, ...] = (
    DerivedMap(
        "normal",
        RELIEF_SOURCE,
        3,
        MapSpec(
            "normal",
            "normal_gl.png",
            "png8-rgb",
            NON_COLOUR,
            ("normal",),
            "tangent-space normal, OpenGL convention (+Y up), encoded n * 0.5 + 0.5",
            writer="normal8",
        ),
    ),
    DerivedMap(
        "ao",
        RELIEF_SOURCE,
        1,
        MapSpec(
            "ao",
            "ao.png",
            "png8-grey",
            NON_COLOUR,
            ("ao",),
            "ambient occlusion, 1 = unoccluded",
        ),
    ),
)


@dataclass(frozen=True)
class Layout:
    """The channel layout derived from a registry (:func:`build_layout`); see the module
    docstring for the orders."""

    #: Every channel in registry order.
    channels: tuple[ChannelLayout, ...]
    derived: tuple[DerivedMap, ...]
    #: Export rows, in export order.
    maps: tuple[MapSpec, ...]
    #: Kernel input slots per layer, and output planes (2-D planes first).
    n_slots: int
    n_planes: int
    n_map_planes: int
    _by_name: dict[str, ChannelLayout] = field(repr=False, compare=False)

    def __getitem__(self, name: str) -> ChannelLayout:
        return self._by_name[name]

    def __contains__(self, name: object) -> bool:
        return name in self._by_name

    def in_group(self, *groups: Group) -> tuple[ChannelLayout, ...]:
        """The channels of ``groups``, in the order the groups are given (registry order
        within a group)."""
        return tuple(c for g in groups for c in self.channels if c.group is g)

    @cached_property
    def coverage(self) -> ChannelLayout:
        """The coverage (alpha) channel."""
        return self.in_group(Group.COVERAGE)[0]

    @cached_property
    def scalars(self) -> tuple[ChannelLayout, ...]:
        """The over-blended scalars in slot order ([0, 1] ones first, then ior)."""
        return self.in_group(Group.UNIT, Group.SCALAR)

    @cached_property
    def unit_scalars(self) -> tuple[ChannelLayout, ...]:
        """The over-blended scalars clamped to [0, 1] (metallic .. anisotropy)."""
        return self.in_group(Group.UNIT)

    @cached_property
    def colours(self) -> tuple[ChannelLayout, ...]:
        """Colour channels in slot order: plain colours, then colour+strength ones."""
        return self.in_group(Group.COLOUR, Group.COLOUR_STRENGTH)

    @cached_property
    def maxed(self) -> tuple[ChannelLayout, ...]:
        """Max-blended channels (height)."""
        return self.in_group(Group.MAX)

    @cached_property
    def in_slot_order(self) -> tuple[ChannelLayout, ...]:
        return self.in_group(*SLOT_ORDER)

    @cached_property
    def blended(self) -> tuple[str, ...]:
        """Names of the coverage-weighted ("over") channels in registry order."""
        return tuple(c.name for c in self.channels if c.blend is Blend.OVER)

    @cached_property
    def blended_in_slot_order(self) -> tuple[ChannelLayout, ...]:
        """The over channels in slot order (the order of ``RawLayer.blended_values``)."""
        return tuple(c for c in self.in_slot_order if c.blend is Blend.OVER)

    @cached_property
    def outputs(self) -> tuple[str, ...]:
        """Output names of the dependency analysis: coverage, over, max, derived maps."""
        return (
            self.coverage.name,
            *self.blended,
            *(c.name for c in self.maxed),
            *(d.name for d in self.derived),
        )

    @cached_property
    def map_fields(self) -> tuple[str, ...]:
        """``MaterialMaps`` array fields in export order (derived maps last)."""
        return (
            *(c.field for c in self.in_group(*FIELD_ORDER)),
            *(d.name for d in self.derived),
        )

    @cached_property
    def plane_fields(self) -> tuple[str, ...]:
        """Fields of the 2-D output planes 0 .. ``n_map_planes - 1`` in plane order."""
        return tuple(c.field for c in self.in_group(*PLANE_ORDER) if c.components == 1)

    def channel_of_field(self, map_field: str) -> ChannelLayout | None:
        """The channel whose composited map is ``map_field`` (None for a derived map)."""
        for c in self.channels:
            if c.field == map_field:
                return c
        return None

    def fields_newer_than(self, language: int) -> tuple[str, ...]:
        """``MaterialMaps`` array fields of the channels newer than ``language`` (maps that
        arrays written for that language version, e.g. the parity fixtures, do not hold)."""
        return tuple(c.field for c in self.in_group(*FIELD_ORDER) if c.since > language)

    def components(self, map_field: str) -> int:
        """1 for an (H, W) map, 3 for an (H, W, 3) one."""
        for c in self.channels:
            if c.field == map_field:
                return c.components
        for d in self.derived:
            if d.name == map_field:
                return d.components
        raise KeyError(map_field)

    def plane(self, name: str) -> int:
        """First output plane of a channel."""
        return self[name].planes[0]

    def slot(self, name: str) -> int:
        """First kernel input slot of a channel."""
        return self[name].slots[0]

    @cached_property
    def fingerprint(self) -> str:
        """Hash of the slot and plane tables (what compiled kernels freeze as constants)."""
        table = [(c.name, c.group.value, c.slots, c.planes, c.clamp) for c in self.in_slot_order]
        text = repr((table, self.n_slots, self.n_planes, self.n_map_planes))
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _group(spec: ChannelSpec) -> Group:
    kind = spec.kind
    if spec.blend is Blend.COVERAGE or spec.blend is Blend.MAX:
        if kind is not ValueKind.SCALAR:
            raise ValueError(f"channel {spec.name!r}: a {spec.blend.value} channel is a scalar")
        if spec.blend is Blend.COVERAGE and (spec.clamp_lo, spec.clamp_hi) != (0.0, 1.0):
            raise ValueError(f"channel {spec.name!r}: coverage is clamped to [0, 1]")
        if spec.blend is Blend.MAX and (spec.clamp_lo, spec.clamp_hi) != (None, None):
            raise ValueError(f"channel {spec.name!r}: a max-blended channel is unclamped")
        return Group.COVERAGE if spec.blend is Blend.COVERAGE else Group.MAX
    if kind is ValueKind.COLOUR:
        return Group.COLOUR
    if kind is ValueKind.COLOUR_STRENGTH:
        return Group.COLOUR_STRENGTH
    if (spec.clamp_lo, spec.clamp_hi) == (0.0, 1.0):
        return Group.UNIT
    return Group.SCALAR


def _default_export(channel: ChannelLayout) -> MapSpec:
    """The export of a channel's kind: [0, 1] scalars as grey PNGs; other scalars as float
    EXR; colours as sRGB PNGs; colour x strength as float linear RGB EXR."""
    spec, group = channel.spec, channel.group
    meaning = spec.map_doc or spec.doc
    sources = (channel.field,)
    if group in (Group.COVERAGE, Group.UNIT):
        return MapSpec(spec.name, f"{spec.name}.png", "png8-grey", NON_COLOUR, sources, meaning)
    if group is Group.COLOUR:
        return MapSpec(
            spec.name, f"{spec.name}.png", "png8-rgb", "sRGB", sources, meaning, writer="srgb8"
        )
    colour_space = (
        "linear RGB (scene-referred, unclipped)" if group is Group.COLOUR_STRENGTH else NON_COLOUR
    )
    return MapSpec(
        spec.name, f"{spec.name}.exr", "exr-float32", colour_space, sources, meaning, "exr"
    )


def _export(
    channel: ChannelLayout, coverage: ChannelLayout, rules: Mapping[str, ExportRule]
) -> MapSpec | None:
    spec = _default_export(channel)
    rule = rules.get(channel.name)
    if rule is None:
        return spec
    if rule.skip:
        return None
    encoding = rule.encoding or spec.encoding
    extension = ".exr" if encoding.startswith("exr") else ".png"
    sources = spec.sources + ((coverage.field,) if rule.with_coverage else ())
    if rule.period is not None and (channel.components != 1 or extension != ".png"):
        raise ValueError(f"channel {channel.name!r}: a periodic map is a scalar 8-bit PNG")
    if rule.float_copy and extension == ".exr":
        raise ValueError(f"channel {channel.name!r}: its map is already a float EXR")
    writer = rule.writer or ("periodic8" if rule.period is not None else spec.writer)
    return MapSpec(
        spec.name,
        f"{spec.name}{extension}",
        encoding,
        rule.colour_space or spec.colour_space,
        sources,
        spec.meaning,
        writer,
        period=rule.period,
        decode=rule.decode or "",
        float_file=f"{spec.name}.exr" if rule.float_copy else None,
    )


def build_layout(
    channels: Mapping[str, ChannelSpec] | Iterable[ChannelSpec],
    rules: Mapping[str, ExportRule] | None = None,
    derived: tuple[DerivedMap, ...] = DERIVED,
) -> Layout:
    """The layout of a registry's channels (``CHANNELS`` or any list of specs, e.g. a copy
    with one more channel). Raises ValueError for a registry the engine cannot composite."""
    specs = list(channels.values() if isinstance(channels, Mapping) else channels)
    rules = EXPORT_RULES if rules is None else rules
    groups = {spec.name: _group(spec) for spec in specs}
    if sum(g is Group.COVERAGE for g in groups.values()) != 1:
        raise ValueError("the registry needs exactly one coverage channel")
    slots: dict[str, tuple[int, ...]] = {}
    planes: dict[str, tuple[int, ...]] = {}
    n_slots = n_planes = 0
    for group in SLOT_ORDER:
        for spec in specs:
            if groups[spec.name] is group:
                slots[spec.name] = tuple(range(n_slots, n_slots + spec.arity))
                n_slots += spec.arity
    for group in PLANE_ORDER:
        for spec in specs:
            if groups[spec.name] is group:
                width = 1 if spec.kind is ValueKind.SCALAR else 3
                planes[spec.name] = tuple(range(n_planes, n_planes + width))
                n_planes += width
    laid = tuple(
        ChannelLayout(
            spec,
            groups[spec.name],
            spec.name if spec.kind is ValueKind.SCALAR else f"{spec.name}_linear",
            slots[spec.name],
            planes[spec.name],
        )
        for spec in specs
    )
    by_name = {c.name: c for c in laid}
    if any(d.source not in by_name or by_name[d.source].group is not Group.MAX for d in derived):
        raise ValueError("derived maps come from a max-blended channel")
    coverage = next(c for c in laid if c.group is Group.COVERAGE)
    rows = [_export(c, coverage, rules) for g in FIELD_ORDER for c in laid if c.group is g]
    maps = tuple(r for r in rows if r is not None) + tuple(d.export for d in derived)
    n_map_planes = sum(1 for c in laid if c.components == 1)
    return Layout(laid, derived, maps, n_slots, n_planes, n_map_planes, by_name)


#: The layout of the language's channels.
LAYOUT: Layout = build_layout(CHANNELS)
