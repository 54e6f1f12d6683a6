"""Per-instance geometry of ``Tile`` (motif instancing), numpy version.

The plane is divided into cells of ``width`` x ``height``; row ``r = floor(y / height)`` is
shifted right by ``r * offset * width`` (as Bricks shifts its courses). For a sample and one of
the 9 neighbour offsets (dr, dc), the instance is the one of cell (r + dr, c + dc), where c is
the sample's column in row r + dr. Each cell draws five uniform numbers from a splitmix64 hash
of (seed, stream, row, column): its shift (streams 0, 1: up to ``jitter`` times the cell size
per axis), its rotation (stream 2: within +-``rotate`` degrees), its scale (stream 3: in
[scale_min, scale_max]) and whether it is kept (stream 4: with ``probability``).

:func:`instance` returns the sample's coordinates in that instance's frame (origin at the
instance centre, rotated and scaled with it) and which samples the instance can reach (kept,
and inside the motif's support box when one is known). The numba kernel (:mod:`.tile_numba`)
computes the same numbers in the same order; the rotation's cosine and sine come from
:func:`cos_sin` (basic arithmetic only), so the backends agree bit for bit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.ops.periodic import wraps

#: The 9 (row, column) offsets of a sample's own cell and its neighbours.
NEIGHBOURS: tuple[tuple[int, int], ...] = tuple((dr, dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1))
#: Cell indices beyond this magnitude are not hashed (the instance is dropped).
MAX_CELL = 2.0**52
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_STREAMS = 5
#: Tile's outputs (language 3): the motif's maximum over the instances ("mask"), or a value of
#: the instance whose motif is largest at the sample (:func:`attribute`, ``u``/``v``: its local
#: coordinates).
TILE_OUTPUTS: tuple[str, ...] = ("mask", "instance_value", "row", "column", "angle", "u", "v")
#: Hash stream of the instance values (after the 5 streams of the instance geometry).
VALUE_STREAM = 5


@dataclass(frozen=True)
class TileParams:
    """Tile's static parameters (see the registry entry)."""

    width: float
    height: float
    jitter: float = 0.0
    rotate: float = 0.0
    scale_min: float = 1.0
    scale_max: float = 1.0
    probability: float = 1.0
    offset: float = 0.0
    seed: int = 0
    #: Tileable output (:meth:`tiled`): rows and columns per period and the whole number of
    #: cells the row shift adds up to over those rows; 0: the cells do not wrap.
    wrap_rows: int = 0
    wrap_cols: int = 0
    wrap_shift: int = 0

    @classmethod
    def of(cls, params: dict[str, Any]) -> TileParams:
        return cls(**{k: params[k] for k in cls.__dataclass_fields__ if k in params})

    def tiled(self, period: tuple[float, float]) -> TileParams:
        """These parameters made periodic with ``period`` (Px, Py): the cell size snapped to a
        whole number of cells per period, the row offset to a whole number of cells per
        period of rows, and the cells' random numbers taken from the wrapped cell. Unchanged
        (unwrapped, the checker's W009) when a period holds too many cells or rows to wrap or
        the row offset adds up to too many cells over them
        (:func:`~matloom.ops.periodic.wraps`)."""
        from dataclasses import replace

        px, py = (float(v) for v in period)
        across, up = px / float(self.width), py / float(self.height)
        if not (wraps(across) and wraps(up)):
            return self
        cols, rows = max(1, round(across)), max(1, round(up))
        if not wraps(float(self.offset) * rows):
            return self
        shift = round(float(self.offset) * rows)
        return replace(
            self,
            width=px / cols,
            height=py / rows,
            offset=shift / rows,
            wrap_rows=rows,
            wrap_cols=cols,
            wrap_shift=shift,
        )

    @property
    def rotates(self) -> bool:
        return self.rotate != 0.0

    def consts(self) -> np.ndarray:
        """float64 constants of the kernels: w, h, offset * w, jitter * w, jitter * h,
        scale_min, scale_max - scale_min, probability, rotate in radians."""
        w, h = float(self.width), float(self.height)
        return np.array(
            [
                w,
                h,
                float(self.offset) * w,
                float(self.jitter) * w,
                float(self.jitter) * h,
                float(self.scale_min),
                float(self.scale_max) - float(self.scale_min),
                float(self.probability),
                float(self.rotate) * (math.pi / 180.0),
                float(self.wrap_rows),
                float(self.wrap_cols),
                float(self.wrap_shift),
            ]
        )


def _mix(z: np.ndarray) -> np.ndarray:
    """The splitmix64 finaliser (uint64, wrapping)."""
    z = (z ^ (z >> np.uint64(30))) * _M1
    z = (z ^ (z >> np.uint64(27))) * _M2
    return z ^ (z >> np.uint64(31))


def stream_keys(seed: int) -> np.ndarray:
    """uint64 (5,): the hash key of each stream for ``seed``."""
    base = (int(seed) * 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
    return np.array([(base + k) & 0xFFFFFFFFFFFFFFFF for k in range(_STREAMS)], dtype=np.uint64)


def uniform(key: np.uint64, row: np.ndarray, col: np.ndarray) -> np.ndarray:
    """A uniform [0, 1) float64 per (row, col) (int64 arrays) for one stream key."""
    with np.errstate(over="ignore"):
        z = _mix(np.uint64(key) + _GOLDEN)
        z = _mix(z + row.astype(np.uint64))
        z = _mix(z + col.astype(np.uint64))
    return (z >> np.uint64(11)).astype(np.float64) * (1.0 / 9007199254740992.0)


def instance_parts(
    x: np.ndarray, y: np.ndarray, p: TileParams, dr: int, dc: int
) -> tuple[np.ndarray, ...]:
    """(dx, dy, scale, theta, keep) of neighbour (dr, dc) at every sample (full grids,
    float64): the offset from the instance centre, its scale, its rotation in radians and
    whether it is kept. Non-finite coordinates and cells past :data:`MAX_CELL` are dropped
    (NaN offsets)."""
    k = p.consts()
    w, h, shift_w, jit_w, jit_h, smin, srange, prob, rot, nr, nc, ks = (float(v) for v in k)
    x64, y64 = np.broadcast_arrays(np.asarray(x, np.float64), np.asarray(y, np.float64))
    with np.errstate(all="ignore"):
        r = np.floor(y64 / h) + dr
        shift = r * shift_w
        c = np.floor((x64 - shift) / w) + dc
        valid = (np.abs(r) < MAX_CELL) & (np.abs(c) < MAX_CELL)
        hr, hc = (r, c) if nc == 0 else wrap_cell(r, c, nr, nc, ks)
        ri = np.where(valid, hr, 0.0).astype(np.int64)
        ci = np.where(valid, hc, 0.0).astype(np.int64)
        keys = stream_keys(p.seed)
        u = [uniform(keys[s], ri, ci) for s in range(_STREAMS)]
        keep = valid & (u[4] < prob)
        cx = (c + 0.5) * w + shift + (2.0 * u[0] - 1.0) * jit_w
        cy = (r + 0.5) * h + (2.0 * u[1] - 1.0) * jit_h
        dx = np.where(valid, x64 - cx, np.nan)
        dy = np.where(valid, y64 - cy, np.nan)
        scale = smin + srange * u[3]
        theta = (2.0 * u[2] - 1.0) * rot
    return dx, dy, scale, theta, keep


def attribute(x: np.ndarray, y: np.ndarray, p: TileParams, dr: int, dc: int, output: str) -> Any:
    """The instance value (hash stream :data:`VALUE_STREAM`, uniform in [0, 1)), the row or
    column index (wrapped in tileable output, as the random numbers' cell) or the rotation in
    degrees (counter-clockwise, in [-rotate, rotate]) of neighbour (dr, dc)'s instance at the
    samples (x, y) (float64 arrays of one shape); NaN where the cell is not valid. The same
    cells as :func:`instance_parts` (and the numba kernel): numpy serves both backends."""
    k = p.consts()
    w, h, shift_w, nr, nc, ks = (float(k[i]) for i in (0, 1, 2, 9, 10, 11))
    x64, y64 = np.asarray(x, np.float64), np.asarray(y, np.float64)
    with np.errstate(all="ignore"):
        r = np.floor(y64 / h) + dr
        c = np.floor((x64 - r * shift_w) / w) + dc
        valid = (np.abs(r) < MAX_CELL) & (np.abs(c) < MAX_CELL)
        hr, hc = (r, c) if nc == 0 else wrap_cell(r, c, nr, nc, ks)
        if output in ("row", "column"):
            return np.where(valid, hr if output == "row" else hc, np.nan)
        ri = np.where(valid, hr, 0.0).astype(np.int64)
        ci = np.where(valid, hc, 0.0).astype(np.int64)
        if output == "angle":
            u = uniform(stream_keys(p.seed)[2], ri, ci)
            return np.where(valid, (2.0 * u - 1.0) * float(p.rotate), np.nan)
        if output != "instance_value":
            raise ValueError(f"Tile has no instance attribute {output!r}")
        base = (int(p.seed) * 0x9E3779B97F4A7C15) & 0xFFFFFFFFFFFFFFFF
        key = np.uint64((base + VALUE_STREAM) & 0xFFFFFFFFFFFFFFFF)
        return np.where(valid, uniform(key, ri, ci), np.nan)


def wrap_cell(r: Any, c: Any, nr: float, nc: float, ks: float) -> tuple[Any, Any]:
    """The cell whose random numbers cell (r, c) takes in tileable output: the row modulo
    ``nr`` rows, the column moved back by the ``ks`` cells the row shift adds per ``nr``
    rows, then modulo ``nc`` (float64 integers; floor of an exact quotient)."""
    kr = np.floor(r / nr)
    rr = r - kr * nr
    cc = c + kr * ks
    return rr, cc - np.floor(cc / nc) * nc


#: Taylor coefficients of sin (odd powers 3..17) and cos (even powers 2..18) for
#: :func:`cos_sin` (half angles in [-pi/2, pi/2]: errors below 1e-14).
SIN_COEFFS: tuple[float, ...] = tuple((-1.0) ** k / math.factorial(2 * k + 1) for k in range(1, 9))
COS_COEFFS: tuple[float, ...] = tuple((-1.0) ** k / math.factorial(2 * k) for k in range(1, 10))


def _series(h2: np.ndarray, coeffs: tuple[float, ...]) -> np.ndarray:
    """1 + c1 h2 + c2 h2^2 + ... by Horner's rule (in this order in both backends)."""
    acc = np.full_like(h2, coeffs[-1])
    for c in coeffs[-2::-1]:
        acc = acc * h2 + c
    return acc * h2 + 1.0


def cos_sin(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(cos, sin) of angles in [-pi, pi] from additions and products only (Taylor series of
    the half angle, then the double-angle formulas), so that numpy and numba agree bit for bit
    whatever libm or SIMD library each uses."""
    h = theta * 0.5
    h2 = h * h
    s = h * _series(h2, SIN_COEFFS)
    c = _series(h2, COS_COEFFS)
    return (c - s) * (c + s), 2.0 * (s * c)


def local_coords(
    dx: np.ndarray, dy: np.ndarray, scale: np.ndarray, theta: np.ndarray, rotates: bool
) -> tuple[np.ndarray, np.ndarray]:
    """The instance-frame coordinates: the offset rotated by -theta, divided by the scale."""
    with np.errstate(all="ignore"):
        if not rotates:
            return dx / scale, dy / scale
        cos, sin = cos_sin(theta)
        return (cos * dx + sin * dy) / scale, (cos * dy - sin * dx) / scale


def inside_box(
    lx: np.ndarray, ly: np.ndarray, keep: np.ndarray, box: tuple[float, ...] | None
) -> np.ndarray:
    """Kept instances whose local coordinates lie in ``box`` (x0, y0, x1, y1; None: all)."""
    if box is None:
        return keep
    x0, y0, x1, y1 = box
    return keep & (lx >= x0) & (lx <= x1) & (ly >= y0) & (ly <= y1)


def instance(
    x: np.ndarray,
    y: np.ndarray,
    p: TileParams,
    dr: int,
    dc: int,
    box: tuple[float, ...] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(local x, local y, inside) of neighbour (dr, dc) at every sample (numpy backend):
    ``inside`` marks the kept instances whose local coordinates lie in ``box``."""
    dx, dy, scale, theta, keep = instance_parts(x, y, p, dr, dc)
    lx, ly = local_coords(dx, dy, scale, theta, p.rotates)
    return lx, ly, inside_box(lx, ly, keep, box)
