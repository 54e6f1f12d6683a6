"""What a base's structure builder returns, and the helpers the builders share."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from matloom.library.compose.bases import BaseSpec
from matloom.library.compose.writer import Axes, Writer, num


@dataclass(frozen=True)
class Structure:
    """Expressions (usually Define names) of a base's structure.

    ``tone``: 0..1, the base colour (0) to the secondary colour (1); ``bump``: height in
    program units (the relief multiplier is applied by the composer); ``accent``: 0..1 coverage
    of the accent colour (None: the base shows no accent); ``rough``: added to the roughness;
    ``metal``: multiplies the metalness."""

    tone: str
    bump: str
    accent: str | None = None
    rough: str | None = None
    metal: str | None = None


@dataclass(frozen=True)
class Ctx:
    """A builder's inputs: the writer, the base, the grain axes, a suffix for its Define names
    (a directional base is written twice under upright planks) and a per-cell random value
    (``"0"`` without cells) that shifts the structure from cell to cell."""

    w: Writer
    base: BaseSpec
    axes: Axes
    sfx: str = ""
    phase: str = "0"

    def d(self, name: str, expr: str, comment: str | None = None) -> str:
        """Define ``name`` + suffix; returns the full name."""
        return self.w.define(f"{name}{self.sfx}", expr, comment)

    @property
    def amp(self) -> str:
        """The base's relief amplitude in program units."""
        return num(self.w.units(self.base.relief_m))

    def specks(self, name: str, feature_m: float, share: float | None = None) -> str | None:
        """Grains of ``feature_m`` covering ``share`` (default: the base's accent share) of the
        surface: Worley cells whose uniform cell value is above 1 - share. None for no share."""
        share = self.base.accent_share if share is None else share
        if share <= 0:
            return None
        t = 1 - share
        cells = self.w.worley(feature_m, 'output="cell_value"', hi=128)
        return self.d(name, f"Smoothstep({num(t - 0.004)}, {num(t + 0.004)}, {cells})")


Builder = Callable[[Ctx], Structure]
