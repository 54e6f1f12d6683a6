"""The evaluated material: float32 maps on one sampling grid (row 0 = top, +y up)."""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

#: Field names of :class:`MaterialMaps` that hold arrays, in export order.
ARRAY_FIELDS: tuple[str, ...] = (
    "basecolor_linear",
    "alpha",
    "metallic",
    "roughness",
    "sheen",
    "coat",
    "transmission",
    "subsurface",
    "anisotropy",
    "ior",
    "emissive_linear",
    "height",
    "normal",
    "ao",
)

#: The seven blended scalar channels in [0, 1].
SCALAR_CHANNELS: tuple[str, ...] = (
    "metallic",
    "roughness",
    "sheen",
    "coat",
    "transmission",
    "subsurface",
    "anisotropy",
)


@dataclass(frozen=True)
class View:
    """Sampling window: (x1, y1) bottom-left, (x2, y2) top-right, in coordinate units."""

    x1: float = 0.0
    y1: float = 0.0
    x2: float = 1.0
    y2: float = 1.0

    def as_tuple(self) -> tuple[float, float, float, float]:
        return (self.x1, self.y1, self.x2, self.y2)

    def texel_size(self, width: int, height: int) -> tuple[float, float]:
        """Texel spacing (dx, dy) in coordinate units, as the reference computes it."""
        return abs(self.x2 - self.x1) / width, abs(self.y2 - self.y1) / height


@dataclass
class MaterialMaps:
    """Composited float32 maps of one material at one resolution.

    Shapes: (H, W) for scalars, (H, W, 3) for colours and the normal. ``basecolor_linear`` and
    ``emissive_linear`` are linear light; ``alpha`` is total coverage; ``height`` is in
    coordinate units (unclamped); ``normal`` is a unit tangent-space normal in the OpenGL
    convention (+x right, +y up toward row 0, +z out); ``ao`` is 1 where unoccluded.
    """

    basecolor_linear: np.ndarray
    alpha: np.ndarray
    metallic: np.ndarray
    roughness: np.ndarray
    sheen: np.ndarray
    coat: np.ndarray
    transmission: np.ndarray
    subsurface: np.ndarray
    anisotropy: np.ndarray
    ior: np.ndarray
    emissive_linear: np.ndarray
    height: np.ndarray
    normal: np.ndarray
    ao: np.ndarray
    view: View = field(default_factory=View)
    #: Number of layers composited (0 for an empty material).
    n_layers: int = 1

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
        """Build from a mapping with the fixture names (e.g. a parity ``.npz``)."""
        kwargs = {name: np.asarray(arrays[name], dtype=np.float32) for name in ARRAY_FIELDS}
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
