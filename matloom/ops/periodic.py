"""Periodic lattices: the arithmetic that makes a lattice repeat with the View's periods.

Pure Python, shared by the op table's period rules (:mod:`matloom.ops.period`: what the checker
reports), the noise plans (:mod:`matloom.engine.kernels.noise`), Tile's and Bricks' cell wraps
and the shapes' images, so that the checker and the engine decide alike.

**fBm** (OpenSimplex 2014) samples a triangular lattice: the vertex with stretched indices
(i, j) sits at ``(i + (i + j) SQUISH, j + (i + j) SQUISH)``. No lattice vector is parallel to
an axis, so a View's periods cannot be matched by snapping the frequency alone. For each
octave the noise instead samples ``p = M (x, y)``, where M maps the View's period vectors
``(Px, 0)`` and ``(0, Py)`` onto the two lattice vectors ``L1``, ``L2`` nearest to where the
octave's frequency would put them (``(f_x Px, 0)`` and ``(0, f_y Py)``): an affine map within
about half a lattice cell per period of the plain ``(f_x x, f_y y)`` (a slight stretch and
shear, largest for octaves with few cells per View). Shifting (x, y) by a period then shifts p
by a lattice vector, and the vertex hash takes the vertex's index modulo the sublattice that
``L1``, ``L2`` span (its Hermite normal form ``(p, q), (0, r)``: index ``i' r + j'`` of the
canonical representative, its low 16 bits replacing the 8 + 8 bits of the unbounded noise), so
the field repeats exactly. The reductions use float64 ``floor((n + 0.5) / p)``, exact for every
index below 2**51, so numpy and numba compute the same integers
(:func:`matloom.engine.kernels.noise.simplex_tiling` stacks the octaves' maps).

**Worley** and the cell values use a square lattice: the frequency is snapped so that each
period holds a whole number of cells, and cell indices are wrapped modulo those counts.

**Shapes** (Fill, Stroke) repeat as the maximum over their images one period apart:
:func:`image_shifts` lists the images that can reach a grid of samples.
"""

from __future__ import annotations

import itertools
import math

#: OpenSimplex 2-D lattice constants (opensimplex 0.4.5.1's): index -> real space and back.
STRETCH_CONSTANT2: float = -0.211324865405187  # (1/sqrt(3) - 1) / 2
SQUISH_CONSTANT2: float = 0.366025403784439  # (sqrt(3) - 1) / 2

__all__ = [
    "MAX_PERIOD_CELLS",
    "SQUISH_CONSTANT2",
    "STRETCH_CONSTANT2",
    "cell_counts",
    "course_wrap",
    "image_shifts",
    "simplex_octave",
    "simplex_wraps",
    "snap_frequency",
    "whole",
    "wraps",
]

#: Most cells per period that a tileable lattice wraps (noise, Tile, Bricks' cell values). The
#: wrapped cell indices then stay exact in int64 and float64, and so do fBm's sublattice keys
#: (below the square of it, far under 2**51). A lattice with more cells per period (or a count
#: that overflows) is evaluated unwrapped, and the checker warns (W009): so many cells per
#: View are finer than any texel grid, so nothing a seam could show is lost.
MAX_PERIOD_CELLS = 2**24


def wraps(cells: float) -> bool:
    """Whether a lattice with ``cells`` cells per period can be wrapped: a finite count of at
    most :data:`MAX_PERIOD_CELLS` (either sign)."""
    return math.isfinite(cells) and abs(cells) <= MAX_PERIOD_CELLS


def _stretch(v: tuple[float, float]) -> tuple[float, float]:
    """Real-space vector -> stretched (index) coordinates."""
    s = (v[0] + v[1]) * STRETCH_CONSTANT2
    return v[0] + s, v[1] + s


def _squish(n: tuple[int, int]) -> tuple[float, float]:
    """Index vector -> real-space lattice vector."""
    s = (n[0] + n[1]) * SQUISH_CONSTANT2
    return n[0] + s, n[1] + s


def _candidates(target: tuple[float, float]) -> list[tuple[int, int]]:
    """Integer index vectors around the stretched ``target`` (nearest first), none zero."""
    sx, sy = _stretch(target)
    bx, by = round(sx), round(sy)
    out = [(bx + a, by + b) for a, b in itertools.product((0, -1, 1), repeat=2)]
    return [n for n in out if n != (0, 0)]


def _error(n: tuple[int, int], target: tuple[float, float]) -> float:
    lx, ly = _squish(n)
    return (lx - target[0]) ** 2 + (ly - target[1]) ** 2


def _hnf(n1: tuple[int, int], n2: tuple[int, int]) -> tuple[int, int, int]:
    """(p, q, r) of the sublattice spanned by index vectors n1, n2 (rows): its Hermite basis
    (p, q), (0, r) with p, r > 0 and 0 <= q < r."""
    a, b = n1
    c, d = n2
    det = a * d - b * c
    g, s, t = _ext_gcd(a, c)
    if g < 0:
        g, s, t = -g, -s, -t
    r = abs(det) // g
    q = (s * b + t * d) % r
    return g, q, r


def _ext_gcd(a: int, b: int) -> tuple[int, int, int]:
    """(g, s, t) with s a + t b = g = gcd(a, b) (g may be negative)."""
    if b == 0:
        return (a, 1, 0) if a != 0 else (0, 0, 0)
    g, s, t = _ext_gcd(b, a % b)
    return g, t, s - (a // b) * t


def simplex_octave(
    px: float, py: float, fx: float, fy: float
) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float, float]]:
    """One fBm octave of frequencies (fx, fy) tiling periods (px, py): (m00, m01, m10, m11) of
    the coordinate map M and (p, q, r, 1/p, 1/r) of the sublattice (see the module docstring)."""
    t1, t2 = (fx * px, 0.0), (0.0, fy * py)
    best: tuple[float, tuple[int, int], tuple[int, int]] | None = None
    for n1 in _candidates(t1):
        for n2 in _candidates(t2):
            if n1[0] * n2[1] - n1[1] * n2[0] == 0:
                continue
            err = _error(n1, t1) + _error(n2, t2)
            if best is None or err < best[0]:
                best = (err, n1, n2)
    assert best is not None
    _, n1, n2 = best
    l1, l2 = _squish(n1), _squish(n2)
    m = (l1[0] / px, l2[0] / py, l1[1] / px, l2[1] / py)
    p, q, r = _hnf(n1, n2)
    return m, (float(p), float(q), float(r), 1.0 / p, 1.0 / r)


def simplex_wraps(
    freqs_x: tuple[float, ...], freqs_y: tuple[float, ...], period: tuple[float, float]
) -> bool:
    """Whether every octave of an fBm (frequencies ``freqs_x``, ``freqs_y``) has a wrappable
    number of cells per period (:func:`wraps`), so :func:`simplex_tiling` can tile it."""
    px, py = (float(v) for v in period)
    if not (px > 0 and py > 0 and math.isfinite(px) and math.isfinite(py)):
        return False
    return all(wraps(fx * px) and wraps(fy * py) for fx, fy in zip(freqs_x, freqs_y, strict=True))


def cell_counts(freq_x: float, freq_y: float, period: tuple[float, float]) -> tuple[int, int]:
    """Whole numbers of unit cells (>= 1) nearest to each period at the given frequencies
    (1 for a count that is not finite)."""
    return _count(freq_x * period[0]), _count(freq_y * period[1])


def _count(cells: float) -> int:
    if not math.isfinite(cells):
        return 1
    return max(1, int(round(abs(cells))))


def snap_frequency(freq: float, period: float) -> tuple[float, int]:
    """(frequency, cells): ``freq`` snapped so that ``period`` holds a whole number of cells
    (at least 1), keeping its sign."""
    cells = _count(freq * period)
    return math.copysign(cells / period, freq), cells


#: Relative tolerance of a whole number of cells per period (patterns, Hash).
WHOLE = 1e-6


def whole(value: float) -> int | None:
    """``value`` as a whole number when it is one (within :data:`WHOLE` relative), else None."""
    if not math.isfinite(value):
        return None
    n = round(value)
    return int(n) if abs(value - n) <= WHOLE * max(1.0, abs(value)) else None


def course_wrap(
    period_along: float, period_across: float, size_along: float, size_across: float, shift: float
) -> tuple[int, int, int] | None:
    """(cells along, courses, cells the course shift adds over the courses) of a running-bond
    grid (Bricks, Tile) whose cells of ``size_along`` x ``size_across``, shifted by ``shift``
    cells per course, repeat with the periods; None when they do not."""
    along = whole(_quotient(period_along, size_along))
    across = whole(_quotient(period_across, size_across))
    if not along or not across or not (wraps(along) and wraps(across)):
        return None
    k = whole(shift * across)
    return None if k is None or not wraps(k) else (along, across, k)


def _quotient(a: float, b: float) -> float:
    """a / b, inf when b is 0 (a zero size has no whole number of cells per period)."""
    return a / b if b else math.inf


#: Most images of one shape evaluated per sample grid (a shape so many Views wide that more
#: would reach the samples is drawn unwrapped, with a note; see :func:`image_shifts`).
MAX_IMAGES = 49


def image_shifts(
    box: tuple[float, float, float, float],
    period: tuple[float, float],
    extent: tuple[float, float, float, float],
) -> list[tuple[float, float]] | None:
    """The period shifts (i Px, j Py) of the images of a shape (support ``box``: its coverage
    is exactly 0 outside it) that reach samples in ``extent`` (x0, y0, x1, y1): a tileable
    shape is the maximum of its coverage at ``(x - i Px, y - j Py)`` over them (each other
    image is exactly 0 there). None when there would be more than :data:`MAX_IMAGES` (a shape
    many Views wide) or the numbers (or the image counts) are not finite; the identity shift is
    always included."""
    px, py = period
    bx0, by0, bx1, by1 = box
    ex0, ey0, ex1, ey1 = extent
    values = (px, py, bx0, by0, bx1, by1, ex0, ey0, ex1, ey1)
    if not all(math.isfinite(v) for v in values) or px <= 0 or py <= 0:
        return None
    # an image i reaches the samples when [bx0 + i px, bx1 + i px] meets [ex0, ex1]
    reach = ((ex0 - bx1) / px, (ex1 - bx0) / px, (ey0 - by1) / py, (ey1 - by0) / py)
    if not all(math.isfinite(v) for v in reach):  # a shape (or gap) past the float range
        return None
    i0, i1 = math.floor(reach[0]), math.ceil(reach[1])
    j0, j1 = math.floor(reach[2]), math.ceil(reach[3])
    if (i1 - i0 + 1) * (j1 - j0 + 1) > MAX_IMAGES:
        return None
    shifts = [(0.0, 0.0)]
    for i in range(i0, i1 + 1):
        for j in range(j0, j1 + 1):
            if (i, j) == (0, 0):
                continue
            sx, sy = i * px, j * py
            if bx0 + sx <= ex1 and bx1 + sx >= ex0 and by0 + sy <= ey1 and by1 + sy >= ey0:
                shifts.append((sx, sy))
    return shifts
