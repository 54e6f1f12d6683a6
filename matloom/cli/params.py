"""Click parameter types shared by the commands, so each range is declared once.

A bad value is a usage error (exit 2) whose one ``Error:`` line names the option and the allowed
range, never a traceback: sizes are 1 to the engine's maximum resolution, counts have bounds,
and real numbers must be finite.
"""

from __future__ import annotations

import math

import click

from matloom.engine.limits import DEFAULT_LIMITS

MAX_SIDE = DEFAULT_LIMITS.max_resolution
"""Largest image side in pixels (the engine's documented limit, docs/limits.md)."""

SIZE = click.IntRange(1, MAX_SIDE)
"""An image side in pixels."""

STATS_GRID = click.IntRange(2, MAX_SIDE)
"""The statistics grid: slopes need at least two samples per axis."""

GALLERY_SIZE = click.IntRange(2, MAX_SIDE)
"""Gallery previews: the 2x2 tiled preview is rendered at half the size."""

VARIANTS = click.IntRange(0, 10_000)
"""Seed variants K of ``seeds``/``sweep`` (0 keeps only the original)."""

TOP = click.IntRange(1, 256)
"""Candidates kept for the sweep's contact sheet and previews."""

JOBS = click.IntRange(0, 256)
"""Worker threads (0 = one per core)."""

TILE = click.IntRange(1, 8)
"""Repetitions per axis of a tiled preview."""

COLUMNS = click.IntRange(1, 64)
"""Contact-sheet columns."""

COUNT = click.IntRange(1, 10_000)
"""Programs printed by ``random``."""

LAYERS = click.IntRange(1, 64)
"""Layers of a random program."""

DEFINES = click.IntRange(0, 64)
"""Defines of a random program."""

BACKEND = click.Choice(("auto", "numba", "numpy"))
"""Kernel backends (``auto`` picks per request)."""


def _describe_range(lo: float | None, hi: float | None) -> str:
    if lo is not None and hi is not None:
        return f"{lo:g}<=x<={hi:g}"
    return f"x>={lo:g}" if lo is not None else f"x<={hi:g}"


class FiniteFloat(click.ParamType):
    """A finite real number (``nan``/``inf`` are refused) within optional closed bounds."""

    name = "number"

    def __init__(self, lo: float | None = None, hi: float | None = None) -> None:
        self.lo, self.hi = lo, hi

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> float:
        if isinstance(value, bool):
            self.fail(f"{value!r} is not a number", param, ctx)
        try:
            number = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number", param, ctx)
        in_range = (self.lo is None or number >= self.lo) and (self.hi is None or number <= self.hi)
        if not math.isfinite(number) or not in_range:
            self.fail(f"{value} is not {self.describe()}", param, ctx)
        return number

    def describe(self) -> str:
        if self.lo is None and self.hi is None:
            return "a finite number"
        return f"a finite number in the range {_describe_range(self.lo, self.hi)}"


NON_NEGATIVE = FiniteFloat(lo=0.0)
"""A finite real number >= 0 (radii in coordinate units)."""


class PositiveFloat(FiniteFloat):
    """A finite real number > 0 (a physical scale)."""

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> float:
        number = super().convert(value, param, ctx)
        if number <= 0:
            self.fail(f"{value} is not a finite number > 0", param, ctx)
        return number

    def describe(self) -> str:
        return "a finite number > 0"


POSITIVE = PositiveFloat(lo=0.0)
"""A finite real number > 0 (metres per coordinate unit)."""


class MaterialName(click.ParamType):
    """A material name for file names: letters, digits, ``_`` and ``-`` (others become ``_``),
    1 to 64 characters."""

    name = "name"

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> str:
        import re

        text = re.sub(r"[^A-Za-z0-9_-]+", "_", str(value)).strip("_")[:64]
        if not text:
            self.fail(f"{value!r} has no letter or digit to name files with", param, ctx)
        return text


NAME = MaterialName()
"""A material name used in preset file names."""


class LightAngles(click.ParamType):
    """``AZIMUTH,ELEVATION`` in degrees: a finite azimuth and an elevation in [-90, 90]."""

    name = "AZIMUTH,ELEVATION"
    _EXAMPLE = "e.g. 45,55"

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> tuple[float, float]:
        if isinstance(value, tuple):
            return value  # type: ignore[return-value]
        parts = str(value).split(",")
        if len(parts) != 2:
            self.fail(f"{value!r} is not AZIMUTH,ELEVATION in degrees, {self._EXAMPLE}", param, ctx)
        azimuth = FiniteFloat().convert(parts[0].strip(), param, ctx)
        elevation = FiniteFloat(-90.0, 90.0).convert(parts[1].strip(), param, ctx)
        return azimuth, elevation


LIGHT = LightAngles()
