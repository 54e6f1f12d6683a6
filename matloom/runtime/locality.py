"""Locality of an edit, computed not claimed: which maps an edit changed, and where.

:func:`locality` evaluates the program before and after the edit on the same grid (256 x 256
by default, the same seeds: omitted seeds come from ``program_seed`` 0 both times) and compares
every output map texel by texel. A texel of a map *changed* when some component moved by more
than the map's tolerance:

* maps in [0, 1] (colours in linear light, the unit scalars, coverage, AO) and the normal:
  half an 8-bit step, ``0.5 / 255``: a change no 8-bit export would show is no change;
* the other maps (``height`` in coordinate units, ``ior``, ``anisotropy_angle``, ``emissive``):
  the same fraction of the map's own scale, its largest peak-to-peak over before and after
  (at least 1 for all but height, whose relief may be millimetres in any unit).

The report lists, per map, the fraction of texels changed and the largest change; ``changed``
are the maps with any texel changed, and ``leaks`` the maps changed outside the intended
channels on more than :data:`LEAK_FRACTION` of their texels. Intended channels are expanded
the way the dependency analysis reads a program (:mod:`matloom.lang.deps`): ``height`` also
allows ``normal`` and ``ao`` (derived from it), and coverage (``alpha``) allows every map,
because a layer's coverage enters every blended channel.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from matloom.engine.evaluate import evaluate
from matloom.lang.deps import COVERAGE, DERIVED, MAXED, OUTPUTS
from matloom.vocab.layout import LAYOUT

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps
    from matloom.engine.session import Session
    from matloom.lang import ast as A

#: Side of the square grid both programs are evaluated on.
LOCALITY_SIZE = 256
#: A texel changed when a component moved by more than this (times the map's scale).
TOLERANCE = 0.5 / 255
#: A map changed outside the intended channels on more than this fraction of texels leaks.
LEAK_FRACTION = 0.01

#: Maps whose values live in [0, 1] (or [-1, 1] for the normal): scale 1.
_UNIT_MAPS = frozenset(
    {"alpha", "basecolor", "ao", "normal"} | {c.name for c in LAYOUT.unit_scalars}
)


def _field_of(name: str) -> str:
    """The :class:`MaterialMaps` field holding the output map ``name``."""
    for f in LAYOUT.map_fields:
        channel = LAYOUT.channel_of_field(f)
        if (channel.name if channel is not None else f) == name:
            return f
    raise KeyError(name)


def allowed_outputs(intended: Iterable[str]) -> frozenset[str]:
    """The output maps an edit of the ``intended`` channels may change: the channels, the maps
    derived from them (height -> normal, ao) and, for coverage, every map."""
    wanted = set(intended)
    unknown = wanted - set(OUTPUTS)
    if unknown:
        raise ValueError(f"unknown channel(s) {sorted(unknown)}; channels: {', '.join(OUTPUTS)}")
    if COVERAGE in wanted:
        return frozenset(OUTPUTS)
    out = set(wanted)
    for name, source in DERIVED.items():
        if source in wanted:
            out.add(name)
    return frozenset(out)


@dataclass(frozen=True)
class MapChange:
    """How one output map changed: the fraction of texels beyond tolerance, the largest
    change, and the tolerance used (in the map's units)."""

    name: str
    fraction: float
    max_abs: float
    tolerance: float

    def to_json(self) -> dict[str, Any]:
        return {
            "fraction": round(self.fraction, 6),
            "max_abs": float(f"{self.max_abs:.6g}"),
            "tolerance": float(f"{self.tolerance:.6g}"),
        }


@dataclass(frozen=True)
class LocalityReport:
    """The maps an edit changed, against the channels it meant to change."""

    size: int
    intended: tuple[str, ...]
    maps: dict[str, MapChange] = field(default_factory=dict)

    @property
    def allowed(self) -> frozenset[str]:
        return allowed_outputs(self.intended)

    @property
    def changed(self) -> tuple[str, ...]:
        """Maps with any texel changed beyond tolerance, in output order."""
        return tuple(n for n, c in self.maps.items() if c.fraction > 0)

    @property
    def leaks(self) -> tuple[str, ...]:
        """Maps changed outside the intended channels on more than 1 % of their texels."""
        allowed = self.allowed
        return tuple(
            n for n, c in self.maps.items() if n not in allowed and c.fraction > LEAK_FRACTION
        )

    @property
    def ok(self) -> bool:
        return not self.leaks

    def describe(self) -> str:
        """One line per leak, or a line saying the edit stayed local (for messages and the
        model's repair turn)."""
        intended = ", ".join(self.intended) or "none"
        if COVERAGE in self.intended:
            intended = "coverage: every map"
        if not self.leaks:
            changed = ", ".join(self.changed) or "nothing"
            return f"local: changed {changed} (intended {intended})"
        return "; ".join(
            f"{n} changed on {self.maps[n].fraction:.1%} of texels outside the intended "
            f"channels ({intended})"
            for n in self.leaks
        )

    def to_json(self) -> dict[str, Any]:
        return {
            "size": self.size,
            "tolerance": f"{TOLERANCE:.6g} x map scale",
            "leak_fraction": LEAK_FRACTION,
            "intended": list(self.intended),
            "allowed": sorted(self.allowed),
            "changed": list(self.changed),
            "leaks": list(self.leaks),
            "maps": {n: c.to_json() for n, c in self.maps.items()},
        }


def _scale(name: str, a: np.ndarray, b: np.ndarray) -> float:
    if name in _UNIT_MAPS:
        return 1.0
    finite = [x[np.isfinite(x)] for x in (a, b)]
    ptp = max((float(np.ptp(x)) if x.size else 0.0) for x in finite)
    if name in MAXED:  # height: its own scale, whatever the unit
        return ptp if ptp > 0 else 1e-6
    return max(1.0, ptp)


def _change(name: str, a: np.ndarray, b: np.ndarray) -> MapChange:
    tol = TOLERANCE * _scale(name, a, b)
    diff = np.abs(a.astype(np.float64) - b.astype(np.float64))
    diff = np.where(np.isnan(a) & np.isnan(b), 0.0, diff)  # NaN in both: unchanged
    diff = np.where(np.isfinite(diff), diff, np.inf)
    if diff.ndim == 3:
        diff = diff.max(axis=2)
    moved = diff > tol
    finite = diff[np.isfinite(diff)]
    return MapChange(
        name=name,
        fraction=float(np.count_nonzero(moved)) / max(1, moved.size),
        max_abs=float(finite.max()) if finite.size else 0.0,
        tolerance=tol,
    )


def compare_maps(
    before: MaterialMaps, after: MaterialMaps, intended: Iterable[str]
) -> LocalityReport:
    """The locality report of two evaluations on the same grid."""
    if before.alpha.shape != after.alpha.shape:
        raise ValueError(f"maps differ in size: {before.alpha.shape} vs {after.alpha.shape}")
    intended_t = tuple(dict.fromkeys(intended))
    allowed_outputs(intended_t)  # validates the names
    maps = {
        name: _change(name, getattr(before, _field_of(name)), getattr(after, _field_of(name)))
        for name in OUTPUTS
    }
    return LocalityReport(size=int(before.alpha.shape[0]), intended=intended_t, maps=maps)


def locality(
    before: A.Program | str,
    after: A.Program | str,
    intended: Iterable[str],
    *,
    size: int = LOCALITY_SIZE,
    session: Session | None = None,
) -> LocalityReport:
    """Evaluate ``before`` and ``after`` at ``size`` x ``size`` (same seeds) and report which
    maps changed, and which of them leak outside the ``intended`` channels."""
    a = evaluate(before, size, size, session=session)
    b = evaluate(after, size, size, session=session)
    return compare_maps(a, b, intended)


__all__ = [
    "LEAK_FRACTION",
    "LOCALITY_SIZE",
    "TOLERANCE",
    "LocalityReport",
    "MapChange",
    "allowed_outputs",
    "compare_maps",
    "locality",
]
