"""The size of a feature in texture units, measured on its mask: the dominant period (the
spacing of rows, the repeat of a grid) or the extent of its pieces (a penny's diameter, a
board's width, a check's side, the cells a grid of lines encloses).

A mask is evaluated over the View's window (:func:`mask_map`: a layer's coverage, a Define, or
the height map of the whole material), thresholded half way between its low and high values,
and read by :func:`feature_size`:

* ``"apart"``: the dominant period along x and along y (the power spectrum of the rows and of
  the columns); ``rows=True`` (rows, lines, stripes are "apart") the larger, else the smaller;
* ``"width"`` / ``"length"`` / ``"across"``: the pieces (4-connected components). A network
  (one piece spanning the window both ways: a grid of strips, lead came) is measured by the
  cells it encloses (``"width"``: its lines' width); stripes (pieces spanning one way) by
  their width; separate pieces by the median of their bounding boxes (``"width"`` the smaller
  side, ``"length"`` the larger, ``"across"`` the larger unless they are at least twice as
  long as wide, as boards are: their width).
"""

from __future__ import annotations

import numpy as np

from matloom.engine.evaluate import evaluate
from matloom.lang import ast as A

#: Grid side a feature is measured on.
SIZE = 256
#: A piece spans an axis when its bounding box covers this share of the window.
_SPANS = 0.9


def mask_map(program: A.Program, mask: A.Node | None, size: int = SIZE) -> np.ndarray:
    """``mask`` (a coverage expression) evaluated over the program's window; with ``None``,
    the material's height map (its basecolor luminance when it has no relief)."""
    if mask is None:
        maps = evaluate(program, size, size)
        h = np.asarray(maps.height, np.float64)
        if np.isfinite(h).all() and float(np.ptp(h)) > 1e-9:
            return h
        rgb = np.asarray(maps.basecolor_linear, np.float64)
        return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722
    probe = A.Program(
        program.view,
        program.defines,
        (
            A.Layer(None, (A.ChannelSet("roughness", (A.Num(0),)),)),
            A.Layer(mask, (A.ChannelSet("roughness", (A.Num(1),)),)),
        ),
    )
    return np.asarray(evaluate(probe, size, size).roughness, np.float64)


def _binary(m: np.ndarray) -> np.ndarray | None:
    m = np.where(np.isfinite(m), m, 0.0)
    lo, hi = np.percentile(m, 0.5), np.percentile(m, 99.5)
    if hi - lo < 1e-9:
        return None
    fg = m > (lo + hi) / 2
    share = float(fg.mean())
    return fg if 0.001 < share < 0.999 else None


def label(fg: np.ndarray) -> np.ndarray:
    """4-connected components of ``fg``: each pixel's label is the smallest flat index of its
    component (``fg.size`` off the mask)."""
    h, w = fg.shape
    off = fg.size
    lab = np.where(fg, np.arange(off).reshape(h, w), off)
    while True:
        m = lab.copy()
        m[1:] = np.minimum(m[1:], lab[:-1])
        m[:-1] = np.minimum(m[:-1], lab[1:])
        m[:, 1:] = np.minimum(m[:, 1:], lab[:, :-1])
        m[:, :-1] = np.minimum(m[:, :-1], lab[:, 1:])
        flat = np.where(fg, m, off).ravel()
        on = flat < off
        for _ in range(4):  # pointer jumping: a label's own label is smaller or equal
            flat[on] = flat[flat[on]]
        new = flat.reshape(h, w)
        if np.array_equal(new, lab):
            return new
        lab = new


def _boxes(lab: np.ndarray, off: int) -> np.ndarray:
    """Per component: (height, width, touches the border, area) in pixels."""
    h, w = lab.shape
    on = lab < off
    ids, inv = np.unique(lab[on], return_inverse=True)
    rows, cols = np.nonzero(on)
    n = len(ids)
    r0, r1 = np.full(n, h), np.full(n, -1)
    c0, c1 = np.full(n, w), np.full(n, -1)
    np.minimum.at(r0, inv, rows)
    np.maximum.at(r1, inv, rows)
    np.minimum.at(c0, inv, cols)
    np.maximum.at(c1, inv, cols)
    area = np.bincount(inv, minlength=n)
    edge = (r0 == 0) | (c0 == 0) | (r1 == h - 1) | (c1 == w - 1)
    return np.stack([r1 - r0 + 1, c1 - c0 + 1, edge, area], axis=1).astype(np.float64)


def _runs(fg: np.ndarray) -> np.ndarray:
    """Lengths (pixels) of the runs of ``fg`` along its rows that touch neither end."""
    pad = np.pad(fg.astype(np.int8), ((0, 0), (1, 1)))
    d = np.diff(pad, axis=1)
    starts = np.nonzero(d == 1)
    ends = np.nonzero(d == -1)
    length = ends[1] - starts[1]
    inner = (starts[1] > 0) & (ends[1] < fg.shape[1])
    return length[inner] if inner.any() else length


def _period(fg: np.ndarray, span: float) -> float | None:
    """The dominant period along the rows (units), or None when there is none."""
    x = fg.astype(np.float64)
    x = x - x.mean(axis=1, keepdims=True)
    power = (np.abs(np.fft.rfft(x, axis=1)) ** 2).mean(axis=0)
    power[0] = 0.0
    total = float(power.sum())
    if total <= 0:
        return None
    k = int(np.argmax(power))
    if power[k] < 0.05 * total:
        return None
    kf = float(k)
    if 0 < k < len(power) - 1:  # the peak between bins (a window of no whole repeat)
        a, b, c = power[k - 1], power[k], power[k + 1]
        den = a - 2 * b + c
        if den < 0:
            kf = k + 0.5 * (a - c) / den
    return span / kf if kf > 0 else None


def feature_size(
    m: np.ndarray, span_x: float, span_y: float, how: str = "across", rows: bool = False
) -> float | None:
    """The feature's size in units (see the module docstring), or None when the mask shows
    no feature."""
    fg = _binary(m)
    if fg is None:
        return None
    ny, nx = fg.shape
    ux, uy = span_x / nx, span_y / ny
    if how == "apart":
        found = [p for p in (_period(fg, span_x), _period(fg.T, span_y)) if p is not None]
        if not found:
            return None
        return max(found) if rows else min(found)
    off = fg.size
    boxes = _boxes(label(fg), off)
    big = boxes[np.argmax(boxes[:, 3])]
    spans_y, spans_x = big[0] >= _SPANS * ny, big[1] >= _SPANS * nx
    if spans_x and spans_y and big[3] > 0.5 * fg.sum():  # a network: its cells, its lines
        if how == "width":
            runs = np.concatenate([_runs(fg) * ux, _runs(fg.T) * uy])
            return float(np.median(runs)) if runs.size else None
        return feature_size(~fg * 1.0, span_x, span_y, how, rows)
    if spans_x != spans_y and big[3] > 0.3 * fg.sum():  # stripes: their width
        runs = _runs(fg.T) * uy if spans_x else _runs(fg) * ux
        return float(np.median(runs)) if runs.size else None
    keep = boxes[(boxes[:, 2] == 0) & (boxes[:, 3] >= 0.25 * np.median(boxes[:, 3]))]
    if len(keep) == 0:
        keep = boxes
    hs, ws = keep[:, 0] * uy, keep[:, 1] * ux
    small = float(np.median(np.minimum(hs, ws)))
    large = float(np.median(np.maximum(hs, ws)))
    if how == "width" or (how == "across" and large >= 2 * small):
        return small
    return large
