"""The ``output`` keyword of Worley, Bricks and Weave (language 2), on every backend.

Cell values, border distances and brick/thread positions are checked against brute force
(every feature point of a wide block of cells, the brick layout written out, the thread drawn
step by step); the backends agree bit for bit; the default output is today's field; canonical
text is unchanged for programs without ``output=`` and the sweep varies cell values with seeds.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.engine.backends import Backend, available_backends, get_backend
from matloom.engine.evaluate import evaluate
from matloom.engine.kernels.noise import WORLEY_CELL_SALT
from matloom.engine.kernels.noise_numpy import worley_hash
from matloom.engine.kernels.opensimplex import worley_seed_term
from matloom.engine.maps import ARRAY_FIELDS
from matloom.lang.deps import channel_dependencies
from matloom.lang.printer import format_program
from matloom.lang.seeds import canonicalize_seeds, uses_seed

DATA = Path(__file__).resolve().parents[1] / "data"
BACKENDS = available_backends()
METRICS = ("euclidean", "manhattan", "chebyshev")


@pytest.fixture(params=BACKENDS)
def backend(request: pytest.FixtureRequest) -> Backend:
    return get_backend(request.param)


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return (
        a.shape == b.shape
        and a.dtype == b.dtype
        and bool((a.view(np.uint64) == b.view(np.uint64)).all())
    )


# ---------------------------------------------------------------------------- Worley
def _features(seed: int, lo: int, hi: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every feature point of the cells [lo, hi)^2: cells (N, 2) and points (N,) x, y."""
    cx, cy = np.meshgrid(np.arange(lo, hi, dtype=np.int64), np.arange(lo, hi, dtype=np.int64))
    cx, cy = cx.ravel(), cy.ravel()
    term = worley_seed_term(seed)
    return (
        np.stack([cx, cy], 1),
        cx + worley_hash(cx, cy, term, 0),
        cy + worley_hash(cx, cy, term, 1),
    )


def _metric(du: np.ndarray, dv: np.ndarray, distance: str) -> np.ndarray:
    if distance == "euclidean":
        return np.hypot(du, dv)
    if distance == "manhattan":
        return np.abs(du) + np.abs(dv)
    return np.maximum(np.abs(du), np.abs(dv))


def _samples(n: int, lo: float, hi: float, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    return rng.uniform(lo, hi, n), rng.uniform(lo, hi, n)


@pytest.mark.parametrize("distance", METRICS)
def test_worley_cell_value_is_one_value_per_cell(backend: Backend, distance: str) -> None:
    x, y = _samples(4000, -1.3, 1.7, seed=1)
    fx, fy = 3.0, -2.5
    got = backend.worley(
        x,
        y,
        distance=distance,
        combination="F2",
        freq_x=fx,
        freq_y=fy,
        to_01=True,
        seed=7,
        output="cell_value",
    )
    cells, px, py = _features(7, -12, 12)
    d = _metric((x * fx)[:, None] - px[None, :], (y * fy)[:, None] - py[None, :], distance)
    nearest = np.argmin(d, axis=1)
    groups: dict[int, set[float]] = defaultdict(set)
    for k, value in zip(nearest, got):
        groups[int(k)].add(float(value))
    assert all(len(values) == 1 for values in groups.values())
    values = [next(iter(v)) for v in groups.values()]
    assert len(groups) > 20 and len(set(values)) == len(values)
    assert all(0.0 <= v < 1.0 for v in values)
    cx, cy = cells[nearest, 0], cells[nearest, 1]
    expected = worley_hash(cx, cy, worley_seed_term(7), WORLEY_CELL_SALT)
    assert np.array_equal(got, expected)


def _edge_brute(
    x: np.ndarray, y: np.ndarray, fx: float, fy: float, seed: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Distance in x/y units to the nearest bisector of the nearest feature point (Euclidean
    cells), over every point of a wide block; and the nearest border point (x, y)."""
    _, px, py = _features(seed, -40, 40)
    u, v = (x * fx)[:, None], (y * fy)[:, None]
    key = (u - px) ** 2 + (v - py) ** 2
    first = np.argmin(key, axis=1)
    p1x, p1y = px[first][:, None], py[first][:, None]
    nu, nv = px[None, :] - p1x, py[None, :] - p1y  # bisector normals (uv)
    num = (key - key[np.arange(len(x)), first][:, None]) / 2
    gx, gy = nu * fx, nv * fy  # the normal in x/y units
    norm = np.hypot(gx, gy)
    with np.errstate(divide="ignore", invalid="ignore"):
        dist = np.where(norm > 0, num / norm, np.inf)
    k = np.argmin(dist, axis=1)
    rows = np.arange(len(x))
    d = dist[rows, k]
    # the border point: step d from (x, y) along the bisector's normal (towards Pk)
    zx = x + d * gx[rows, k] / norm[rows, k]
    zy = y + d * gy[rows, k] / norm[rows, k]
    return d, zx, zy


@pytest.mark.parametrize("freqs", [(4.0, 4.0), (2.0, 7.0), (-3.0, 1.5), (9.0, -0.8)])
def test_worley_edge_matches_brute_force(backend: Backend, freqs: tuple[float, float]) -> None:
    fx, fy = freqs
    x, y = _samples(1500, -0.8, 0.9, seed=2)
    kw = dict(distance="manhattan", combination="F1", freq_x=fx, freq_y=fy, to_01=False, seed=5)
    got = backend.worley(x, y, output="edge", **kw)
    expected, zx, zy = _edge_brute(x, y, fx, fy, 5)
    assert np.max(np.abs(got - expected)) <= 1e-6
    assert np.all(got >= 0)
    on_border = backend.worley(zx, zy, output="edge", **kw)
    assert np.max(on_border) <= 1e-6


def test_worley_edge_is_zero_on_borders(backend: Backend) -> None:
    """At the brute-force nearest border point: edge 0, and F1 = F2 (two feature points)."""
    x, y = _samples(200, 0.0, 3.0, seed=3)
    kw = dict(distance="euclidean", combination="F1", freq_x=1.0, freq_y=1.0, to_01=False)
    _, zx, zy = _edge_brute(x, y, 1.0, 1.0, 9)
    assert np.max(backend.worley(zx, zy, seed=9, output="edge", **kw)) <= 1e-9
    f1 = backend.worley(zx, zy, seed=9, **kw)
    f2 = backend.worley(zx, zy, seed=9, **{**kw, "combination": "F2"})
    assert np.max(np.abs(f2 - f1)) <= 1e-9  # equidistant from two feature points


def test_worley_outputs_agree_across_backends_and_seed_batches() -> None:
    if len(BACKENDS) < 2:
        pytest.skip("one backend")
    nb, npy = get_backend("numba"), get_backend("numpy")
    x = (np.arange(70, dtype=np.float32)[None, :] + 0.5) / 35 - 1
    y = (np.arange(50, dtype=np.float32)[::-1, None] + 0.5) / 35 - 1
    c, s = np.cos(0.4), np.sin(0.4)
    rotated = ((c * x + s * y).astype(np.float32), (-s * x + c * y).astype(np.float32))
    huge = (x.astype(np.float64) * 1e7, y.astype(np.float64))  # hashed cells (no table)
    for xx, yy in ((x, y), rotated, huge):
        for distance in METRICS:
            for output in ("cell_value", "edge"):
                kw = dict(
                    distance=distance,
                    combination="F1",
                    freq_x=6.0,
                    freq_y=-4.0,
                    to_01=False,
                    output=output,
                )
                a = npy.worley(xx, yy, seed=3, **kw)
                assert _same_bits(a, nb.worley(xx, yy, seed=3, **kw))
                for backend in (npy, nb):
                    batch = backend.worley_seed_batch(xx, yy, seeds=[3, 4], **kw)
                    assert np.array_equal(batch[0], a.astype(np.float32), equal_nan=True)
                    other = backend.worley(xx, yy, seed=4, **kw).astype(np.float32)
                    assert np.array_equal(batch[1], other, equal_nan=True)


def test_worley_non_finite_coordinates_give_nan(backend: Backend) -> None:
    x = np.array([0.3, np.nan, np.inf, 0.7])
    y = np.array([0.1, 0.2, 0.3, -np.inf])
    for output in ("cell_value", "edge"):
        out = backend.worley(
            x,
            y,
            distance="euclidean",
            combination="F1",
            freq_x=3.0,
            freq_y=3.0,
            to_01=False,
            seed=1,
            output=output,
        )
        assert np.isfinite(out[0]) and np.isnan(out[1:]).all()


# ---------------------------------------------------------------------------- Bricks
BRICKS = dict(brick_width=0.3, brick_height=0.2, offset=0.37, mortar=0.04, feather=0.02)


def _brick_layout(x: np.ndarray, y: np.ndarray, axis: str, bw: float, bh: float, offset: float):
    """Brick (column, row) and the cell's lower-left corner, written out in float64."""
    if axis == "row":
        row = np.floor(y / bh)
        left = row * offset * bw
        col = np.floor((x - left) / bw)
        return col, row, left + col * bw, row * bh
    col = np.floor(x / bw)
    bottom = col * offset * bh
    row = np.floor((y - bottom) / bh)
    return col, row, col * bw, bottom + row * bh


@pytest.mark.parametrize("axis", ["row", "column"])
def test_bricks_positions_and_edge_match_the_layout(backend: Backend, axis: str) -> None:
    x, y = _samples(5000, -1.1, 1.3, seed=4)
    bw, bh, offset, mortar = 0.3, 0.2, 0.37, 0.04
    kw = dict(BRICKS, axis=axis)
    col, row, x0, y0 = _brick_layout(x, y, axis, bw, bh, offset)
    lx, ly = x - x0, y - y0
    safe = (np.minimum(lx, bw - lx) > 1e-9) & (np.minimum(ly, bh - ly) > 1e-9)
    u = backend.bricks(x, y, output="u", **kw)
    v = backend.bricks(x, y, output="v", **kw)
    edge = backend.bricks(x, y, output="edge", **kw)
    assert np.allclose(u[safe], (lx / bw)[safe], rtol=0, atol=1e-9)
    assert np.allclose(v[safe], (ly / bh)[safe], rtol=0, atol=1e-9)
    assert u.min() >= 0 and u.max() <= 1 and v.min() >= 0 and v.max() <= 1
    h = mortar / 2
    inside = np.minimum(np.minimum(lx - h, bw - h - lx), np.minimum(ly - h, bh - h - ly))
    assert np.allclose(edge, np.maximum(inside, 0.0), rtol=0, atol=1e-9)
    assert np.all(edge[inside < -1e-9] == 0)
    mask = backend.bricks(x, y, **{**kw, "feather": 0.0})
    assert np.all(mask[edge > 0] == 1)


@pytest.mark.parametrize("axis", ["row", "column"])
def test_bricks_cell_value_is_constant_per_brick_and_seeded(backend: Backend, axis: str) -> None:
    x, y = _samples(5000, -1.1, 1.3, seed=5)
    kw = dict(BRICKS, axis=axis)
    col, row, x0, y0 = _brick_layout(x, y, axis, 0.3, 0.2, 0.37)
    lx, ly = x - x0, y - y0
    safe = (np.minimum(lx, 0.3 - lx) > 1e-9) & (np.minimum(ly, 0.2 - ly) > 1e-9)
    a = backend.bricks(x, y, output="cell_value", seed=11, **kw)
    b = backend.bricks(x, y, output="cell_value", seed=12, **kw)
    groups: dict[tuple[float, float], set[float]] = defaultdict(set)
    for c, r, value in zip(col[safe], row[safe], a[safe]):
        groups[(c, r)].add(float(value))
    assert len(groups) > 50 and all(len(v) == 1 for v in groups.values())
    per_brick = [next(iter(v)) for v in groups.values()]
    assert len(set(per_brick)) == len(per_brick) and 0 <= min(per_brick) and max(per_brick) < 1
    assert np.mean(a != b) > 0.99
    with pytest.raises(ValueError, match="seed"):
        backend.bricks(x, y, output="cell_value", **kw)


@pytest.mark.parametrize("axis", ["row", "column"])
def test_bricks_outputs_agree_across_backends(axis: str) -> None:
    if len(BACKENDS) < 2:
        pytest.skip("one backend")
    x = (np.arange(90, dtype=np.float32)[None, :] + 0.5) / 30 - 1.5
    y = (np.arange(60, dtype=np.float32)[::-1, None] + 0.5) / 30 - 1
    c, s = np.cos(0.3), np.sin(0.3)
    rotated = ((c * x + s * y).astype(np.float32), (-s * x + c * y).astype(np.float32))
    odd = (
        np.array([[np.nan, np.inf, -np.inf, 1e30, 0.5]]),
        np.array([[0.1, 0.2, 0.3, 0.4, np.nan]]),
    )
    for xx, yy in ((x, y), rotated, (x.astype(np.float64), y.astype(np.float64)), odd):
        for output in ("mask", "cell_value", "u", "v", "edge"):
            kw = dict(BRICKS, axis=axis, output=output, seed=3)
            a = get_backend("numpy").bricks(xx, yy, **kw)
            assert _same_bits(a, get_backend("numba").bricks(xx, yy, **kw)), output


# ---------------------------------------------------------------------------- Weave
WEAVES = [
    dict(over=1, under=1, shift=1),
    dict(over=2, under=1, shift=1),
    dict(over=3, under=2, shift=-1),
    dict(over=4, under=1, shift=2),  # satin: warp floats found by stepping
    dict(over=3, under=3, shift=3),
    dict(over=2, under=2, shift=0),  # endless warp floats
]


def _on_top(col: np.ndarray, row: np.ndarray, over: int, under: int, shift: int) -> np.ndarray:
    return np.mod(col - row * shift, over + under) < over


def _same_thread_on_top(c: float, r: float, warp: bool, steps: int, draft: dict) -> int | None:
    """Cells next to (c, r) along its thread (``steps`` = +-1 per cell) with the same thread on
    top, up to a limit of 4 repeats (None: an endless float)."""
    limit = 4 * (draft["over"] + draft["under"])
    for j in range(1, limit):
        cc, rr = (c, r + j * steps) if warp else (c + j * steps, r)
        if bool(_on_top(np.array(cc), np.array(rr), **draft)) != warp:
            return j - 1
    return None


def _along_brute(u: np.ndarray, v: np.ndarray, draft: dict) -> np.ndarray:
    """Walk each texel's thread cell by cell to find its float."""
    col, row = np.floor(u), np.floor(v)
    warp = _on_top(col, row, **draft)
    out = np.empty(u.shape)
    for k in range(u.size):
        c, r, w = col.flat[k], row.flat[k], bool(warp.flat[k])
        back = _same_thread_on_top(c, r, w, -1, draft)
        frac = (v.flat[k] - r) if w else (u.flat[k] - c)
        if back is None:  # endless float: each cell on its own
            out.flat[k] = frac
        else:
            ahead = _same_thread_on_top(c, r, w, 1, draft)
            out.flat[k] = (back + frac) / (back + 1 + ahead)
    return out


@pytest.mark.parametrize("draft", WEAVES, ids=lambda d: "{over}-{under}-{shift}".format(**d))
def test_weave_outputs_match_the_threads(backend: Backend, draft: dict) -> None:
    x = (np.arange(61, dtype=np.float64)[None, :] + 0.37) / 61 - 0.3
    y = (np.arange(47, dtype=np.float64)[::-1, None] + 0.61) / 47 - 0.2
    kw = dict(draft, freq_x=7.0, freq_y=5.0, warp_width=0.7, feather=0.15)
    mask = backend.weave(x, y, **kw)
    warp = backend.weave(x, y, output="warp", **kw)
    weft = backend.weave(x, y, output="weft", **kw)
    assert np.array_equal(warp + weft, mask)
    u, v = np.broadcast_arrays(x * 7.0, y * 5.0)
    on_top = _on_top(np.floor(u), np.floor(v), draft["over"], draft["under"], draft["shift"])
    assert np.all(warp[~on_top] == 0) and np.all(weft[on_top] == 0)
    along = backend.weave(x, y, output="along", **kw)
    across = backend.weave(x, y, output="across", **kw)
    for value in (along, across):
        assert value.shape == mask.shape and value.min() >= 0 and value.max() <= 1
    assert np.allclose(along, _along_brute(u, v, draft), rtol=0, atol=1e-12)
    offset = np.where(on_top, u - np.floor(u), v - np.floor(v))  # across the thread on top
    assert np.allclose(across, np.clip((offset - 0.15) / 0.7, 0, 1), rtol=0, atol=1e-12)
    assert np.all((across > 0) & (across < 1) <= (mask > 0))


def test_weave_along_non_finite_and_float32() -> None:
    x = np.array([[np.nan, 0.1, 0.2]], dtype=np.float32)
    y = np.array([[0.3], [np.inf]], dtype=np.float32)
    kw = dict(over=2, under=1, shift=1, freq_x=8.0, freq_y=8.0, warp_width=0.5, feather=0.0)
    for name in BACKENDS:
        out = get_backend(name).weave(x, y, output="along", **kw)
        assert out.dtype == np.float64 and out.shape == (2, 3)
        assert (
            np.isnan(out[:, 0]).all() and np.isnan(out[1]).all() and np.isfinite(out[0, 1:]).all()
        )


# ---------------------------------------------------------------------------- language
_DEFAULTS = [
    ('Worley(distance="manhattan", base_freq=5, seed=3)', 'output="distance"'),
    ("Bricks(brick_width=0.4, feather=0.01)", 'output="mask"'),
    ("Weave(over=2, feather=0.1)", 'output="mask"'),
]


@pytest.mark.parametrize("call,explicit", _DEFAULTS)
def test_default_output_is_todays_field(call: str, explicit: str) -> None:
    with_output = call[:-1] + f", {explicit})"
    plain = f"Material(Layer(1).height({call}).roughness(Rotate({call}, 20)))"
    written = plain.replace(call, with_output)
    assert matloom.format(written) == matloom.format(plain)
    for name in BACKENDS:
        a, b = evaluate(plain, 40, 24, backend=name), evaluate(written, 40, 24, backend=name)
        for key in ARRAY_FIELDS:
            assert np.array_equal(getattr(a, key), getattr(b, key), equal_nan=True), key


def _canonical_files() -> list[Path]:
    """The reference's canonical programs (``seedless`` is a template with SEED in it)."""
    files = sorted((DATA / "parity").glob("*.canonical.mat"))
    files += sorted((DATA / "parity-random").glob("*.canonical.mat"))
    return [f for f in files if f.name != "seedless.canonical.mat"]


def test_canonical_text_of_existing_programs_is_unchanged() -> None:
    files = _canonical_files()
    assert len(files) > 10
    for path in files:
        text = path.read_text()
        program = matloom.parse(text)
        assert matloom.format(program) == text, path.name
        assert format_program(canonicalize_seeds(program, 5)) == text, path.name


def test_format_round_trips_output() -> None:
    text = (
        'Define(a, Worley(combination="F2", seed=3, output="edge"))\n'
        'Define(b, Bricks(axis="column", output="cell_value", seed=4))\n'
        'Define(c, Weave(over=2, output="along"))\n'
        "Material(\n  Layer(1)\n    .height(((a + b) + c))\n)"
    )
    assert matloom.format(text) == text
    assert matloom.format(matloom.format(text)) == text
    # default outputs and unused seeds are not printed
    assert (
        matloom.format(
            'Material(Layer(Bricks(output="mask", seed=4) * Worley(seed=1, output="distance")))'
        )
        == "Material(\n  Layer((Bricks() * Worley(seed=1)))\n)"
    )


def test_canonicalisation_adds_a_seed_only_for_bricks_cell_values() -> None:
    text = (
        'Define(a, Bricks(output="u"))\nDefine(b, Bricks())\n'
        'Define(c, Bricks(output="cell_value"))\nMaterial(Layer(1).height(a + b + c))'
    )
    out = format_program(canonicalize_seeds(matloom.parse(text), 2))
    lines = out.splitlines()
    assert lines[0] == 'Define(a, Bricks(output="u"))' and lines[1] == "Define(b, Bricks())"
    assert lines[2].startswith('Define(c, Bricks(output="cell_value", seed=')
    program = matloom.parse(out)
    calls = [d.expr for d in program.defines]
    assert [uses_seed(c) for c in calls] == [False, False, True]
    unused = matloom.parse("Material(Layer(1).height(Bricks(seed=123)))")
    deps = channel_dependencies(unused)
    assert not any(p.is_seed or p.value == 123 for p in deps["height"])


# ---------------------------------------------------------------------------- sweep
def test_sweep_varies_cell_values_with_seeds() -> None:
    pytest.importorskip("numba")
    from matloom.engine.grid import sample_axes
    from matloom.engine.interpret import Evaluator
    from matloom.engine.maps import View
    from matloom.engine.schedules.seed_batch import SweepEvaluator, chunk_program

    text = (
        "View(0, 0, 2, 2)\n"
        'Define(b, Bricks(output="cell_value", seed=5))\n'
        'Define(w, Worley(output="cell_value", base_freq=4, seed=6))\n'
        'Define(e, Worley(output="edge", base_freq=3, seed=6))\n'
        "Material(Layer(1).basecolor(b * 255, w * 255, e * 255))"
    )
    program = matloom.parse(text)
    x, y = sample_axes(View(*program.view_tuple), 32, 32)
    ev = SweepEvaluator(program, x, y, get_backend("numba"))
    maps = [{}, {5: 77, 6: 78}, {5: 79, 6: 6}]
    ev.begin_chunk(maps)
    for define, seed_name in zip(program.defines, ("b", "w", "e")):
        batch = np.asarray(ev.field(define.expr))
        assert batch.shape == (3, 32, 32) and batch.dtype == np.float32, seed_name
        for k, m in enumerate(maps):
            variant = matloom.parse(
                format_program(program)
                .replace("seed=5", f"seed={m.get(5, 5)}")
                .replace("seed=6", f"seed={m.get(6, 6)}")
            )
            expr = next(d.expr for d in variant.defines if d.name == define.name)
            dense = Evaluator(variant, x, y, get_backend("numpy"))
            expected = np.asarray(dense.field(expr), dtype=np.float32)
            assert np.array_equal(batch[k], expected), (define.name, k)
        assert not np.array_equal(batch[0], batch[1])
    chunk_program(ev, maps, 32)  # the fused sweep path takes the program
