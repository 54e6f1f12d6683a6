"""The tile pass: the View side at which the adapted program tiles, and the placed View.

When the View a request asks for does not tile (a noise frequency or a pattern count is not a
whole number of periods across it) the pass looks for the nearest side that does, among small
fractions of the entry's own side; failing that the entry's own side wins over the size word.
:func:`place` then gives the program that side, puts the wrap edge where the entry says
(:func:`matloom.library.adapt.place_origin`) and records the physical size ``unit_m``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace

from matloom.lang import ast as A
from matloom.lang.diagnostics import Diagnostic
from matloom.lang.tileable import make_tileable, tileable_warnings
from matloom.library.adapt import VIEW_RANGE, place_origin, resize_view
from matloom.library.entry import Entry


@dataclass(frozen=True)
class Tiling:
    """The View side chosen, whether the program tiles at it, and why (notes)."""

    side: float
    tileable: bool
    notes: tuple[str, ...] = ()

    def unit_m(self, entry: Entry) -> float:
        """Metres per View unit: the entry's physical size over the side."""
        return round(entry.size_m / self.side, 6)


def tile(program: A.Program, side: float, entry: Entry, view0: float, wanted: bool) -> Tiling:
    """The side (``side`` asked, ``view0`` the entry's own) at which ``program`` tiles, when
    tiling is ``wanted``."""
    if not wanted:
        return Tiling(side, False)
    warnings = _warnings_at(program, side)
    if not warnings:
        return Tiling(side, True)
    if entry.tileable and abs(side / view0 - 1) > 1e-6:
        snapped = tileable_side(program, side, view0)
        if snapped is not None:
            return Tiling(snapped, True, (f"View {side:g} -> {snapped:g} so that it tiles",))
        if not _warnings_at(program, view0):
            # no tileable size near the asked one: tiling wins over a size word
            why = f"View kept at {view0:g}: the entry tiles only at sizes far from {side:g}"
            return Tiling(view0, True, (why,))
    return Tiling(side, False, ("not tileable: " + warnings[0].message.removeprefix("tileable: "),))


def place(program: A.Program, tiling: Tiling, entry: Entry, own: A.Program) -> A.Program:
    """``program`` with the View of ``tiling`` (its wrap edge where the entry, whose own parsed
    program is ``own``, puts it), the tileable flag and ``unit_m``."""
    program = resize_view(program, tiling.side)
    if tiling.tileable:
        program = place_origin(program, entry, own.view_tuple)
    view = replace(program.view, tileable=tiling.tileable, unit_m=tiling.unit_m(entry))
    return replace(program, view=view)


def _warnings_at(program: A.Program, side: float) -> list[Diagnostic]:
    return tileable_warnings(make_tileable(resize_view(program, side)))


def _nearest_tiling(
    options: Iterable[float],
    target: float,
    tolerance: float,
    tries: int,
    tiles: Callable[[float], bool],
) -> float | None:
    """The option nearest ``target`` (within ``tolerance``, relative; at most ``tries`` tried,
    nearest first) for which ``tiles(option)`` holds, else None."""
    ranked = sorted(
        (o for o in options if abs(o / target - 1) <= tolerance),
        key=lambda o: (abs(o / target - 1), o),
    )
    return next((o for o in ranked[:tries] if tiles(o)), None)


def tileable_side(program: A.Program, target: float, view0: float) -> float | None:
    """The View side nearest ``target`` at which ``program`` tiles (None if none close)."""
    candidates = {round(view0 * k / m, 6) for k in range(1, 17) for m in range(1, 9)}
    lo, hi = view0 * VIEW_RANGE[0], view0 * VIEW_RANGE[1]
    return _nearest_tiling(
        (c for c in candidates if lo <= c <= hi),
        target,
        0.35,
        10,
        lambda side: not _warnings_at(program, side),
    )


def tileable_scale(
    program: A.Program, put: Callable[[A.Program, float], A.Program], scale: float
) -> float:
    """The overlay size factor nearest ``scale`` (within 40 %) at which ``put(program, s)``
    still tiles (noise frequencies stay whole numbers of periods), else ``scale`` itself."""
    options = {round(k / n, 4) for n in range(1, 5) for k in range(1, 13)} | {scale}
    found = _nearest_tiling(
        (s for s in options if s != 1.0),
        scale,
        0.4,
        6,
        lambda s: not tileable_warnings(put(program, s)),
    )
    return scale if found is None else found
