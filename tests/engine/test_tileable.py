"""Tileable output: every noise, Hash, Tile and the brick cell values repeat with the View, on
both backends with the same bits; non-tileable output is unchanged (the parity tests).

Periodicity is shown by evaluating a field on twice the View with the View's periods (what a
tileable render of the View uses): the right half equals the left half, the top the bottom.
"""

from __future__ import annotations

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import prepare
from matloom.engine.grid import sample_axes
from matloom.engine.interpret import Evaluator
from matloom.engine.maps import View

BACKENDS = [b for b in ("numpy", "numba") if b in available_backends()]

FIELDS = {
    "fBm": "fBm(octaves=5, base_freq=2.7, seed=3)",
    "fBm anisotropic": "fBm(octaves=4, base_freq_x=1.3, base_freq_y=-5.2, to_01=True, seed=4)",
    "Worley F1": "Worley(base_freq=3.3, seed=5)",
    "Worley F2-F1 manhattan": 'Worley(distance="manhattan", combination="F2-F1", '
    "base_freq_x=2.2, base_freq_y=4, seed=6)",
    "Worley cell_value": 'Worley(base_freq=2.6, output="cell_value", seed=7)',
    "Worley edge": 'Worley(base_freq=2.6, output="edge", seed=7)',
    "Hash": "Hash(X() * 4, Y() * 3, seed=8)",
    "Hash of Floor": "Hash(Floor(X() * 6) + 0.5, Floor(Y() * 2) + 0.5, seed=8)",
    "Tile": "Tile(Fill(Ellipse(0, 0, 0.2, 0.15), feather=0.02), 0.37, 0.29, jitter=0.3, "
    "rotate=40, scale_min=0.7, probability=0.8, offset=0.45, seed=9)",
    "Tile of fBm": "Tile(fBm(octaves=2, seed=2), 0.5, 0.5, jitter=0.2, seed=9)",
    "Bricks cell_value": "Bricks(brick_width=0.5, brick_height=0.25, offset=0.5, "
    'output="cell_value", seed=10)',
    "Bricks columns": 'Bricks(brick_width=0.25, brick_height=0.5, offset=0.25, axis="column", '
    'output="cell_value", seed=10)',
    "Scaled fBm": "Scale(fBm(octaves=3, base_freq=2, seed=11), 0.7, 1.3)",
    "Translated Worley": "Translate(Worley(base_freq=3, seed=12), 0.31, -0.2)",
    "Translate warp": "Translate(Worley(base_freq=3, seed=12), fBm(octaves=2, base_freq=2, "
    "seed=13) * 0.1, Worley(base_freq=2, seed=14) * 0.1)",
    "Rotate 180": "Rotate(fBm(octaves=3, base_freq=2, seed=15), 180)",
    "Fract of coordinates": "Fract(X() * 3 + fBm(octaves=2, base_freq=2, seed=16))",
}


def doubled(
    expr: str, backend: str, n: int = 48, view: tuple = (0.25, -0.5, 1.25, 0.5)
) -> np.ndarray:
    """``expr`` on twice the View (2n x 2n texels) with the View's periods, float64."""
    x1, y1, x2, y2 = view
    w, h = x2 - x1, y2 - y1
    program = prepare(f"View({x1}, {y1}, {x2}, {y2})\nMaterial(Layer(1).height({expr}))")
    node = program.layers[0].channel("height").args[0]
    x, y = sample_axes(View(x1, y1, x1 + 2 * w, y1 + 2 * h), 2 * n, 2 * n)
    ev = Evaluator(program, x, y, get_backend(backend), periods=(w, h))
    value = np.asarray(ev.field(node), dtype=np.float64)
    return np.broadcast_to(value, (2 * n, 2 * n))


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("name", list(FIELDS))
def test_field_repeats_with_the_view(name: str, backend: str) -> None:
    v = doubled(FIELDS[name], backend)
    n = v.shape[0] // 2
    assert np.isfinite(v).all()
    assert np.std(v) > 1e-3  # not trivially constant
    # float32 sample coordinates: x + W differs from x by a float32 rounding
    np.testing.assert_allclose(v[:, n:], v[:, :n], atol=2e-4)
    np.testing.assert_allclose(v[n:], v[:n], atol=2e-4)


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
@pytest.mark.parametrize("name", list(FIELDS))
def test_backends_agree_bit_for_bit(name: str) -> None:
    a, b = doubled(FIELDS[name], "numpy"), doubled(FIELDS[name], "numba")
    assert np.array_equal(a, b, equal_nan=True)


PROGRAM = """View(0, 0, 2, 1, tileable=True)
Define(h, Hash(X() * 8, Y() * 4, seed=3))
Define(cells, Worley(base_freq=5, output="cell_value", seed=1))
Material(
  Layer(1)
    .basecolor(120 + cells * 80, 90, 60)
    .roughness(h)
    .height(fBm(octaves=5, base_freq=3, seed=2) * 0.02 + Worley(base_freq=5, seed=1) * 0.01),
  Layer(Tile(Fill(Ellipse(0, 0, 0.05, 0.05), feather=0.01), 0.13, 0.13, jitter=0.3, seed=2))
    .basecolor(200, 40, 40)
    .height(0.03)
)"""


@pytest.mark.skipif(len(BACKENDS) < 2, reason="needs numba")
def test_tileable_render_same_bits_on_both_backends() -> None:
    a = matloom.evaluate(PROGRAM, 96, 48, backend="numpy")
    b = matloom.evaluate(PROGRAM, 96, 48, backend="numba")
    assert a.view.tileable
    for name, array in a.arrays().items():
        assert np.array_equal(array, getattr(b, name), equal_nan=True), name


SMOOTH = """View(0, 0, 2, 1, tileable=True)
Material(Layer(1)
  .roughness(fBm(octaves=5, base_freq=3, to_01=True, seed=2))
  .height(fBm(octaves=5, base_freq=3, seed=2) * 0.02 + Worley(base_freq=5, seed=1) * 0.01))"""


@pytest.mark.parametrize("backend", BACKENDS)
def test_tileable_render_has_no_seam_and_plain_one_does(backend: str) -> None:
    from matloom.engine.tiling import seam_ratio
    from matloom.render.seams import seam_ratios_over_offsets

    tiled = seam_ratios_over_offsets(SMOOTH, 128, 64, offsets=8, backend=backend)
    plain = matloom.evaluate(SMOOTH.replace(", tileable=True", ""), 128, 64, backend=backend)
    for name in ("roughness", "height", "normal", "ao"):
        assert tiled[name] <= 1.2, name
        assert seam_ratio(getattr(plain, name)) > 2.0, name
    assert tiled["metallic"] == 1.0  # a constant map


def test_seam_ratio_definition() -> None:
    from matloom.engine.tiling import seam_ratio

    ramp = np.tile(np.arange(8, dtype=np.float32), (8, 1))  # steps of 1, a wrap jump of 7
    assert seam_ratio(ramp) == pytest.approx(7.0)  # (7 + 0) / (1 + 0): per direction
    assert seam_ratio(ramp.T) == pytest.approx(7.0)
    assert seam_ratio(np.full((4, 4), 0.25)) == 1.0
    tri = np.abs(np.arange(8) - 3.5)[None, :] * np.ones((3, 1))  # 3.5 .. 0.5 .. 3.5
    assert seam_ratio(tri) == pytest.approx(0.0)  # its wrap pair is equal


def test_relief_wraps_in_tileable_output() -> None:
    """The normal and AO at the borders see the opposite edge: a render shifted by whole
    texels is the roll of the unshifted one (up to float32 sampling)."""
    size = 64
    a = matloom.evaluate(PROGRAM, 2 * size, size, backend="numpy")
    dx = 2.0 / (2 * size)
    shifted = PROGRAM.replace("View(0, 0, 2, 1,", f"View({16 * dx}, 0, {2 + 16 * dx}, 1,")
    b = matloom.evaluate(shifted, 2 * size, size, backend="numpy")
    for name in ("height", "normal", "ao"):
        np.testing.assert_allclose(
            getattr(b, name), np.roll(getattr(a, name), -16, axis=1), atol=2e-3
        )


def test_flag_and_api_turn_tiling_on() -> None:
    plain = PROGRAM.replace(", tileable=True", "")
    a = matloom.evaluate(plain, 32, 16, backend="numpy", tileable=True)
    b = matloom.evaluate(PROGRAM, 32, 16, backend="numpy")
    assert a.view.tileable and b.view.tileable
    assert np.array_equal(a.height, b.height)
    c = matloom.evaluate(plain, 32, 16, backend="numpy")
    assert not c.view.tileable and not np.array_equal(a.height, c.height)
    img = matloom.preview(plain, 32, backend="numpy", tileable=True)
    assert img.shape == (32, 32, 3)


def test_rotated_noise_is_noted() -> None:
    program = prepare("View(0, 0, 1, 1)\nMaterial(Layer(1).height(Rotate(fBm(seed=1), 30)))")
    x, y = sample_axes(View(0, 0, 1, 1), 8, 8)
    ev = Evaluator(program, x, y, get_backend("numpy"), periods=(1.0, 1.0))
    ev.field(program.layers[0].channel("height").args[0])
    assert any("fBm" in note and "rotated" in note for note in ev.stats.notes)


# ------------------------------------------------------------------ the language


def test_view_keyword_parses_and_prints() -> None:
    text = "View(0, 0, 2, 1, tileable=True)\nMaterial(Layer(1).roughness(0.5))"
    program = matloom.parse(text)
    assert program.tileable and program.view.as_tuple() == (0.0, 0.0, 2.0, 1.0)
    assert matloom.format(program).startswith("View(0, 0, 2, 1, tileable=True)\n")
    off = matloom.parse(text.replace("True", "False"))
    assert not off.tileable
    assert matloom.format(off).startswith("View(0, 0, 2, 1)\n")  # printed only when true


@pytest.mark.parametrize("bad", ["tileable=3", "tileable=True, tileable=True", "5"])
def test_view_keyword_errors(bad: str) -> None:
    codes = {d.code for d in matloom.check(f"View(0, 0, 1, 1, {bad})\nMaterial(Layer(1))")}
    assert codes & {"E061", "E027"}


def _codes(body: str, view: str = "View(0, 0, 2, 2, tileable=True)") -> list[str]:
    text = f"{view}\nMaterial(Layer(1).height({body}))"
    return [
        f"{d.code}: {d.message} | {d.hint}"
        for d in matloom.check(text)
        if d.code in ("W009", "W010")
    ]


def test_warnings_for_what_cannot_repeat() -> None:
    assert _codes("fBm(seed=1) + Worley(seed=2) + Fract(X() * 3) + Sin(Y() * pi)") == []
    rotated = _codes("Rotate(Worley(seed=2), 30)")
    assert len(rotated) == 1 and "Worley under Rotate" in rotated[0]
    warped = _codes("Scale(fBm(seed=1), fBm(seed=3) + 2, 1)")
    assert len(warped) == 1 and "fBm under a Scale warp" in warped[0]
    assert _codes("Translate(fBm(seed=1), fBm(seed=3), 0)") == []  # periodic offsets
    raw = _codes("X() * 0.1")
    assert len(raw) == 1 and "W010" in raw[0] and "X()" in raw[0]
    fract = _codes("Fract(X() * 1.3)")
    assert len(fract) == 1 and "2.6 x 0 cycles" in fract[0] and "3 x 0" in fract[0]
    hashed = _codes("Hash(X() * 2.2, Y() * 2, seed=1)")
    assert len(hashed) == 1 and "W009" in hashed[0] and "4.4 x 0 cells" in hashed[0]


def test_pattern_warnings_name_the_nearest_tiling_values() -> None:
    bricks = _codes("Bricks(brick_width=1.3, brick_height=0.5, offset=0.37)")
    assert len(bricks) == 1
    assert "brick_width=1.3" in bricks[0] and "brick_width=1" in bricks[0]
    assert "offset=0.37" in bricks[0] and "offset=0.25" in bricks[0]
    assert "View 2.6 x 2" in bricks[0]
    assert _codes("Bricks(brick_width=0.5, brick_height=0.25)") == []
    weave = _codes("Weave(over=3, under=1, base_freq=9.5)")
    assert len(weave) == 1 and "base_freq_x=10" in weave[0]
    assert _codes("Weave(over=3, under=1, base_freq=10)") == []
    assert _codes("Bricks(brick_width=1.3)", view="View(0, 0, 2, 2)") == []  # not tileable


def test_tile_snaps_its_cells_to_the_view() -> None:
    from matloom.engine.kernels.tile import TileParams

    p = TileParams(0.23, 0.3, offset=0.37).tiled((1.0, 1.0))
    assert (p.width, p.wrap_cols) == (0.25, 4)
    assert p.wrap_rows == 3 and p.height == pytest.approx(1 / 3)
    assert p.offset == pytest.approx(1 / 3) and p.wrap_shift == 1


def test_fbm_octave_maps_stay_close_to_the_frequencies() -> None:
    """The per-octave lattice map is within half a lattice cell per period of f * (x, y)."""
    from matloom.engine.kernels.noise import simplex_tiling

    maps, lattices = simplex_tiling((4.0, 8.0, 16.0, 32.0), (4.0, 8.0, 16.0, 32.0), (1.0, 1.0))
    for (m00, m01, m10, m11), f in zip(maps, (4, 8, 16, 32), strict=True):
        assert abs(m00 - f) < 1.0 and abs(m11 - f) < 1.0 and abs(m01) < 1.0 and abs(m10) < 1.0
    assert (lattices[:, 0] >= 1).all() and (lattices[:, 2] >= 1).all()


# The shipped examples (docs/examples, matloom/examples) all tile since issue 13: their warnings,
# exact periodicity and manifest seam ratios at 512 are tested in
# tests/docs/test_examples_tileable.py.


#: Requests whose library entries tile (every entry is checked by ``matloom library check`` and
#: tests/library; this keeps the suite fast).
AUTHOR_SAMPLE = ("acoustic foam", "circuit board", "cracked dry earth", "ice", "wicker")


def test_offline_author_makes_materials_tileable() -> None:
    from matloom.engine.tiling import manifest_entry
    from matloom.library import author, library
    from matloom.vocab.layout import LAYOUT

    backend = "numba" if "numba" in BACKENDS else "numpy"
    lib = library()
    checked = 0
    for prompt in AUTHOR_SAMPLE:
        result = author(prompt)  # tileable=True is the default
        if not lib.entry(result.entry).tileable:  # the library grew a better, untiled match
            continue
        checked += 1
        assert result.tileable, (prompt, result.notes)
        program = matloom.parse(result.program)
        assert program.tileable and program.view.unit_m == result.unit_m
        maps = matloom.evaluate(result.program, 128, 128, backend=backend)
        ratios = manifest_entry(maps, LAYOUT.maps)["seam_ratio"]  # what material.json reports
        assert max(ratios.values()) <= 1.2, (prompt, result.entry, ratios)
    assert checked >= 3
    # An entry that does not tile stays plain, and the result says why.
    named = (author(n.replace("-", " ")) for n in sorted(lib.entries) if not lib.entry(n).tileable)
    untiled = next(r for r in named if not lib.entry(r.entry).tileable)
    assert not untiled.tileable and not matloom.parse(untiled.program).tileable
    assert any(n.startswith("not tileable: ") for n in untiled.notes), untiled.explanation
    plain = author(AUTHOR_SAMPLE[0], tileable=False)
    assert not plain.tileable and not matloom.parse(plain.program).tileable


def test_cli_render_tileable_reports_seam_ratios(tmp_path) -> None:  # noqa: ANN001
    import json

    from click.testing import CliRunner

    from matloom.cli.main import cli

    src = tmp_path / "m.mat"
    src.write_text(SMOOTH.replace(", tileable=True", "") + "\n")
    out = tmp_path / "out"
    args = ["render", str(src), "-o", str(out), "--size", "64", "--backend", "numpy"]
    result = CliRunner().invoke(cli, [*args, "--tileable"])
    assert result.exit_code == 0, result.output
    manifest = json.loads((out / "material.json").read_text())
    assert manifest["tileable"] is True
    assert set(manifest["seam_ratio"]) >= {"roughness", "height", "ao"}
    assert (out / "material.mat").read_text().startswith("View(0, 0, 2, 1, tileable=True)")
    plain = tmp_path / "plain"
    result = CliRunner().invoke(cli, ["render", str(src), "-o", str(plain), "--size", "16"])
    assert result.exit_code == 0, result.output
    assert "seam_ratio" not in json.loads((plain / "material.json").read_text())


def test_cli_tileable_prints_the_warnings(tmp_path) -> None:  # noqa: ANN001
    from click.testing import CliRunner

    from matloom.cli.main import cli

    src = tmp_path / "m.mat"
    src.write_text("View(0, 0, 2, 2)\nMaterial(Layer(1).height(Rotate(fBm(seed=1), 30)))\n")
    out = tmp_path / "p.png"
    args = ["preview", str(src), "-o", str(out), "--size", "16", "--backend", "numpy"]
    result = CliRunner().invoke(cli, [*args, "--tileable"])
    assert result.exit_code == 0, result.output
    assert "W009" in result.output and "fBm under Rotate" in result.output
