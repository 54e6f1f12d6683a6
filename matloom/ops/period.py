"""Period rules: how an op keeps, wraps, scales or breaks the View's periods (``Op.period``).

A tileable View repeats every (W, H). An expression is evaluated in a *frame* (the coordinates
the transforms above it made); the frame's periods are the View's periods in those coordinates,
or a reason it has none (a rotation, a domain warp). Each op's :class:`Period` says what it does
with them, so that the checker (:mod:`matloom.lang.tileable`, :mod:`matloom.lang.affine`) and
the engine (the interpreter's frames, the field rules) read one statement per function:

* :attr:`Repeats.KEEP`: the operands are evaluated in the op's own frame, and the op repeats
  where they do (element-wise math, masks, constants, geometry).
* :attr:`Repeats.AXIS`: a coordinate (X(), Y(): ``axis`` is its coefficient vector). It breaks
  the periods unless a periodic wrapper accounts for it (the checker's W010).
* :attr:`Repeats.STEP`: Floor, Ceil: a coordinate term passes through when the argument steps by
  whole numbers per period (else the steps do not repeat).
* :attr:`Repeats.WRAP`: a periodic wrapper: each argument with a cycle (``ParamSpec.cycle`` in
  the registry) repeats where it advances by whole cycles per period; ``unit`` names what a
  cycle is ("cycles" of a phase: W010 when not whole; "cells" of Hash: W009).
* :attr:`Repeats.FRAME`: a coordinate transform: ``frame(name, param, periods)`` gives the
  operand's periods for static parameters (Translate keeps them, Scale scales them, Rotate keeps
  them for a multiple of half its angle's cycle and breaks them otherwise); a domain warp (field
  parameters) breaks them unless ``warp_keeps`` (Translate's periodic offsets).
* :attr:`Repeats.OWN`: a primitive with a period of its own (noise lattices, pattern cells,
  Tile's cells, shapes' images): ``misfit(name, param, periods)`` says, from its static
  parameters, why it cannot repeat with the periods (the checker's W009 message and hint; None
  when it does). The engine makes it repeat in its field rule (lattice wraps, images).

``framed``: the op needs a frame with the View's periods (axis-aligned): under a rotation or a
Scale/Rotate warp it cannot repeat (W009). ``param(name)`` gives a static parameter's value as
the evaluator uses it (its default when not written), as in the work rules (:mod:`.work`).

Pure Python: the checker reads these rules without importing numpy or the engine.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = [
    "KEEP",
    "STEP",
    "Frame",
    "Period",
    "Repeats",
    "axis",
    "own",
    "rotated",
    "scaled",
    "transform",
    "translated",
    "whole",
    "wrap",
]

Param = Callable[[str], Any]
#: A frame's View periods (Px, Py).
Periods = tuple[float, float]
#: A frame's View periods, or the name of what made them unknown ("Rotate", "a Scale warp").
Frame = Periods | str
#: The coordinate coefficients (a, b) of ``a X() + b Y()``.
Coeffs = tuple[float, float]
#: ``frame(name, param, periods)``: the operand's frame of a transform with static parameters.
FrameRule = Callable[[str, Param, Periods], Frame]
#: ``misfit(name, param, periods)``: (W009 message, hint) when the op's own period does not fit
#: ``periods``, None when it does.
MisfitRule = Callable[[str, Param, Periods], "tuple[str, str | None] | None"]

#: How far (in cycles or cells per period) from a whole number still counts as whole for the
#: checker: a thousandth of a cycle is a phase error no one sees (programs print pi as 3.1416).
#: (The engine's lattice wraps use :func:`matloom.ops.periodic.whole`, relative 1e-6.)
WHOLE_TOLERANCE = 1e-3


def whole(value: float) -> int | None:
    """``value`` as a whole number when it is one (within :data:`WHOLE_TOLERANCE`)."""
    if not math.isfinite(value):
        return None
    n = round(value)
    return int(n) if abs(value - n) <= WHOLE_TOLERANCE else None


class Repeats(enum.Enum):
    """What an op does with the periods of its frame (see the module docstring)."""

    KEEP = "keep"
    AXIS = "axis"
    STEP = "step"
    WRAP = "wrap"
    FRAME = "frame"
    OWN = "own"


@dataclass(frozen=True)
class Period:
    """One op's period rule (see the module docstring)."""

    repeats: Repeats = Repeats.KEEP
    #: AXIS: the coefficients of the coordinate, (1, 0) for X(), (0, 1) for Y().
    axis: Coeffs | None = None
    #: FRAME: the operand's frame for static parameters.
    frame: FrameRule | None = None
    #: FRAME: a domain warp (a field parameter) keeps the periods (it adds periodic offsets).
    warp_keeps: bool = False
    #: Needs an axis-aligned frame with the View's periods (W009 under a Rotate or a warp).
    framed: bool = False
    #: WRAP: what one cycle of its arguments is: "cycles" (a phase, W010) or "cells" (W009).
    unit: str = "cycles"
    #: OWN: why its own period does not fit a frame's periods (None: it always repeats).
    misfit: MisfitRule | None = None


#: Element-wise ops, masks, constants and geometry: they repeat where their operands do.
KEEP = Period()
#: Floor, Ceil.
STEP = Period(Repeats.STEP)


def axis(a: float, b: float) -> Period:
    """A coordinate ``a X() + b Y()`` (X(): (1, 0), Y(): (0, 1))."""
    return Period(Repeats.AXIS, axis=(a, b))


def wrap(unit: str = "cycles", framed: bool = False) -> Period:
    """A periodic wrapper of its arguments with a ``ParamSpec.cycle``."""
    return Period(Repeats.WRAP, unit=unit, framed=framed)


def transform(frame: FrameRule, warp_keeps: bool = False) -> Period:
    """A coordinate transform whose operand is evaluated in the frame ``frame`` gives."""
    return Period(Repeats.FRAME, frame=frame, warp_keeps=warp_keeps)


def own(misfit: MisfitRule | None = None) -> Period:
    """A primitive with a period of its own, evaluated in a frame with the View's periods."""
    return Period(Repeats.OWN, framed=True, misfit=misfit)


# ------------------------------------------------------------------ transforms' frame rules
def translated(name: str, param: Param, periods: Periods) -> Frame:
    """A translation keeps the periods."""
    return periods


def scaled(sx: str, sy: str) -> FrameRule:
    """A scale by ``param(sx)``, ``param(sy)``: the periods divided by the factors' sizes (none
    past the float range)."""

    def rule(name: str, param: Param, periods: Periods) -> Frame:
        out = (_quotient(periods[0], abs(param(sx))), _quotient(periods[1], abs(param(sy))))
        return out if valid(out) else f"a {name} past the float range"

    return rule


def rotated(angle: str, cycle: float) -> FrameRule:
    """A rotation by ``param(angle)`` (``cycle``: a full turn): it keeps the periods for a
    multiple of half a turn (the axes map to axes), else it breaks them."""

    def rule(name: str, param: Param, periods: Periods) -> Frame:
        return periods if whole(float(param(angle)) / (cycle / 2)) is not None else name

    return rule


def valid(periods: Periods) -> bool:
    """Finite, positive periods."""
    return all(math.isfinite(p) and p > 0 for p in periods)


def _quotient(a: float, b: float) -> float:
    """a / b, inf when b is 0."""
    return a / b if b else math.inf
