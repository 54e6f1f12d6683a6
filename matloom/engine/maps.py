"""The evaluated material: float32 maps on one sampling grid (row 0 = top, +y up)."""

from __future__ import annotations

from dataclasses import dataclass, field, fields, make_dataclass

import numpy as np

from matloom.vocab.layout import LAYOUT

#: Field names of :class:`MaterialMaps` that hold arrays, in export order (from the layout).
ARRAY_FIELDS: tuple[str, ...] = LAYOUT.map_fields

#: The blended scalar channels clamped to [0, 1] (metallic .. anisotropy).
SCALAR_CHANNELS: tuple[str, ...] = tuple(c.field for c in LAYOUT.unit_scalars)

#: Array fields that arrays written for language 1 (the reference's parity fixtures) lack:
#: the maps of newer channels (``anisotropy_angle``).
NEWER_FIELDS: tuple[str, ...] = LAYOUT.fields_newer_than(1)

#: Of those, the ones :meth:`MaterialMaps.from_arrays` may fill in: a program that cannot
#: write the channel composites it to exactly 0 everywhere.
_ZERO_WHEN_ABSENT: frozenset[str] = frozenset(
    name
    for name in NEWER_FIELDS
    if (channel := LAYOUT.channel_of_field(name)) is not None and channel.default_map_is_zero
)


@dataclass(frozen=True)
class View:
    """Sampling window: (x1, y1) bottom-left, (x2, y2) top-right, in coordinate units."""

    x1: float = 0.0
    y1: float = 0.0
    x2: float = 1.0
    y2: float = 1.0
    #: The maps repeat seamlessly with the window's width and height (docs/tileable.md).
    tileable: bool = False
    #: Metres per coordinate unit (``View(..., unit_m=...)``), when the program states it.
    unit_m: float | None = None

    def as_tuple(self) -> tuple[float, float, float, float]:
        return (self.x1, self.y1, self.x2, self.y2)

    @property
    def periods(self) -> tuple[float, float] | None:
        """(width, height) of the window when the output is tileable, else None."""
        if not self.tileable:
            return None
        return abs(float(self.x2) - float(self.x1)), abs(float(self.y2) - float(self.y1))

    def texel_size(self, width: int, height: int) -> tuple[float, float]:
        """Texel spacing (dx, dy) in coordinate units, as the reference computes it."""
        return abs(self.x2 - self.x1) / width, abs(self.y2 - self.y1) / height


class _Maps:
    """Composited float32 maps of one material at one resolution.

    Array fields: :data:`ARRAY_FIELDS`, one per channel of the registry (via
    :mod:`matloom.vocab.layout`) plus the derived ``normal`` and ``ao``. Shapes: (H, W) for
    scalars, (H, W, 3) for colours and the normal. ``basecolor_linear`` and ``emissive_linear``
    are linear light; ``alpha`` is total coverage; ``height`` is in coordinate units
    (unclamped); ``normal`` is a unit tangent-space normal in the OpenGL convention (+x right,
    +y up toward row 0, +z out); ``ao`` is 1 where unoccluded. ``view`` is the sampling window
    and ``n_layers`` the number of layers composited (0 for an empty material).
    """

    # Fields the methods below read (the dataclass :data:`MaterialMaps` defines them all).
    alpha: np.ndarray
    view: View
    n_layers: int

    @property
    def width(self) -> int:
        return int(self.alpha.shape[1])

    @property
    def height_px(self) -> int:
        return int(self.alpha.shape[0])

    def arrays(self) -> dict[str, np.ndarray]:
        """Name -> array for every map, in export order."""
        return {name: getattr(self, name) for name in ARRAY_FIELDS}

    @classmethod
    def from_arrays(
        cls, arrays: dict[str, np.ndarray], view: View | None = None, n_layers: int = 1
    ) -> MaterialMaps:
        """Build from a mapping with the fixture names (e.g. a parity ``.npz``).

        A map of a channel newer than language 1 (:data:`NEWER_FIELDS`, e.g.
        ``anisotropy_angle``) may be missing: arrays made before the channel existed hold what
        such a program composites to, exactly 0 everywhere. Any other missing map raises
        KeyError.
        """
        kwargs = {
            name: np.asarray(arrays[name], dtype=np.float32)
            for name in ARRAY_FIELDS
            if name in arrays or name not in _ZERO_WHEN_ABSENT
        }
        if any(name not in kwargs for name in ARRAY_FIELDS):
            shape = np.shape(kwargs[LAYOUT.coverage.field])
            for name in ARRAY_FIELDS:
                if name not in kwargs:
                    components = LAYOUT.components(name)
                    kwargs[name] = np.zeros(shape + ((3,) if components == 3 else ()), np.float32)
        return cls(**kwargs, view=view or View(), n_layers=n_layers)

    def nonfinite_counts(self) -> dict[str, int]:
        """Per map, how many texel values are NaN or +-inf (only non-zero entries)."""
        out: dict[str, int] = {}
        for f in fields(self):
            if f.name in ARRAY_FIELDS:
                n = int(np.count_nonzero(~np.isfinite(getattr(self, f.name))))
                if n:
                    out[f.name] = n
        return out


#: The maps of a material: a dataclass whose array fields come from the channel layout.
MaterialMaps = make_dataclass(
    "MaterialMaps",
    [
        *((name, np.ndarray) for name in ARRAY_FIELDS),
        ("view", View, field(default_factory=View)),
        ("n_layers", int, field(default=1)),
    ],
    bases=(_Maps,),
    namespace={"__doc__": _Maps.__doc__, "__module__": __name__},
)
