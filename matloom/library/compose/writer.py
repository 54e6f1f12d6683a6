"""The program writer the composer's builders share: named Defines with comments, explicit seeds,
and the conversions from metres to program units (frequencies whole per View, so that every
noise and pattern repeats with it).

One :class:`Writer` is made per :func:`~matloom.library.compose.build.compose` call; builders
add Defines to it and refer to them by name. Nothing here is module state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from statistics import NormalDist

from matloom.lang.printer import fmt_num

#: features per View at most (about 4 texels per feature at 512 px) and at least
MAX_PER_VIEW = 128
MIN_PER_VIEW = 1
#: spread of ``fBm(octaves=3, to_01=True)`` around 0.5 (measured), for share thresholds
FBM3_SD = 0.144
TAU = 2 * math.pi


def num(v: float, digits: int = 4) -> str:
    """A number as the program writes it: rounded to ``digits`` significant digits."""
    if v == 0:
        return "0"
    r = round(v, max(0, digits - 1 - int(math.floor(math.log10(abs(v))))))
    return fmt_num(float(r))


@dataclass
class Writer:
    """Defines in order (each with an optional comment line before it), seeds and units.

    ``unit_m``: metres per program unit; ``side``: the View's side in units; ``seed0``: the
    first seed (each noise takes the next one)."""

    unit_m: float
    side: float
    seed0: int
    lines: list[str] = field(default_factory=list)
    names: list[str] = field(default_factory=list)
    _next: int = 0

    def seed(self) -> int:
        """The next explicit seed."""
        self._next += 1
        return self.seed0 + self._next

    def section(self, comment: str) -> None:
        """A comment line before the next Define."""
        self.lines.append(f"# {comment}")

    def define(self, name: str, expr: str | float, comment: str | None = None) -> str:
        """``Define(name, expr)`` (a trailing comment when given); returns ``name``."""
        if name in self.names:
            raise ValueError(f"Define {name!r} written twice")
        text = num(expr) if isinstance(expr, (int, float)) else expr
        line = f"Define({name}, {text})"
        self.lines.append(f"{line}  # {comment}" if comment else line)
        self.names.append(name)
        return name

    def units(self, metres: float) -> float:
        """``metres`` in program units (4 significant digits)."""
        return float(num(metres / self.unit_m))

    def per_view(self, feature_m: float, hi: int = MAX_PER_VIEW) -> int:
        """Whole features per View for a feature of ``feature_m`` metres (clamped)."""
        n = round(self.side * self.unit_m / feature_m)
        return max(MIN_PER_VIEW, min(hi, n))

    def freq(self, feature_m: float, hi: int = MAX_PER_VIEW) -> str:
        """Features per unit for a feature of ``feature_m`` metres: a whole number per View."""
        return self.cycles(self.per_view(feature_m, hi))

    def cycles(self, per_view: int, scale: float = 1.0) -> str:
        """The factor of a coordinate that gives ``per_view`` cycles per View (times ``scale``,
        e.g. 2 pi for a ``Sin``), to 10 digits: whole to the checker's and the engine's
        tolerance."""
        return num(per_view * scale / self.side, 10)

    def fbm(
        self,
        octaves: int,
        feature_m: float,
        *,
        stretch: tuple[float, float] | None = None,
        to_01: bool = True,
        hi: int = MAX_PER_VIEW,
    ) -> str:
        """An ``fBm`` call with its own seed; ``stretch`` (along x, along y): feature sizes in
        metres per axis instead of one."""
        if stretch is None:
            freq = f"base_freq={self.freq(feature_m, hi)}"
        else:
            fx, fy = stretch
            freq = f"base_freq_x={self.freq(fx, hi)}, base_freq_y={self.freq(fy, hi)}"
        flag = ", to_01=True" if to_01 else ""
        return f"fBm(octaves={octaves}, {freq}{flag}, seed={self.seed()})"

    def worley(self, feature_m: float, extra: str = "", hi: int = 64) -> str:
        """A ``Worley`` call (``extra``: more keyword arguments) with its own seed."""
        more = f", {extra}" if extra else ""
        return f"Worley(base_freq={self.freq(feature_m, hi)}{more}, seed={self.seed()})"


def share_threshold(share: float) -> float:
    """The value of ``fBm(octaves=3, to_01=True)`` above which about ``share`` of the texels
    lie (a normal approximation of its measured spread)."""
    share = min(0.95, max(0.005, share))
    return round(0.5 + FBM3_SD * NormalDist().inv_cdf(1 - share), 3)


@dataclass(frozen=True)
class Axes:
    """Coordinates of a directional structure: ``along`` the grain and ``across`` it (X() and
    Y() for a horizontal grain, swapped for an upright one)."""

    vertical: bool = False

    @property
    def along(self) -> str:
        return "Y()" if self.vertical else "X()"

    @property
    def across(self) -> str:
        return "X()" if self.vertical else "Y()"

    def stretch(self, along_m: float, across_m: float) -> tuple[float, float]:
        """(x, y) feature sizes of a structure stretched ``along_m`` along the grain."""
        return (across_m, along_m) if self.vertical else (along_m, across_m)
