"""The language-2 example gallery (docs/examples): every program is clean, finite and new."""

import struct
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.lang import ast as A
from matloom.lang.static import static_number
from matloom.vocab import CHANNELS, FUNCTIONS

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES_DIR = ROOT / "docs" / "examples"
EXAMPLES = sorted(EXAMPLES_DIR.glob("*.mat"))
PREVIEW_SIZE = 256


def language_2_features(program: A.Program) -> set[str]:
    """Names of the language-2 features a program uses, read from its AST and the registry.

    A feature is a function, a written parameter or a channel whose ``since`` is 2 or more, or a
    field-accepting parameter (Translate/Scale/Rotate) given a per-sample field: one that is not a
    constant expression (an expression of X()/Y() and constants only keeps its language-1
    meaning, evaluated once at the origin).
    """
    found: set[str] = set()
    for _owner, expr in A.program_expressions(program):
        for node in A.walk(expr):
            if not isinstance(node, A.Call):
                continue
            spec = FUNCTIONS[node.func]
            if spec.since >= 2:
                found.add(node.func)
            for arg in node.args:
                param = spec.param(arg.param)
                assert param is not None, f"{node.func} has no parameter {arg.param}"
                if param.since >= 2:
                    found.add(f"{node.func}.{param.name}")
                if param.field and static_number(arg.value) is None:
                    found.add(f"{node.func}.{param.name}=field")
    for layer in program.layers:
        for channel in layer.channels:
            if CHANNELS[channel.name].since >= 2:
                found.add(f".{channel.name}")
    return found


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()[:24]
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path.name} is not a PNG"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_gallery_has_at_least_twelve_programs():
    assert len(EXAMPLES) >= 12, [p.name for p in EXAMPLES]


def test_feature_detection_tells_language_1_from_language_2():
    old = "Define(w, X() * 2)\nMaterial(Layer(1).roughness(Translate(fBm(seed=1), X() * 0.1, 0)))"
    assert language_2_features(matloom.parse(old)) == set()
    new = "Define(w, X() * 2)\nMaterial(Layer(1).roughness(Translate(fBm(seed=1), w, 0)))"
    assert language_2_features(matloom.parse(new)) == {"Translate.dx=field"}
    channel = "Material(Layer(1).anisotropy(1).anisotropy_angle(Fract(X())))"
    assert language_2_features(matloom.parse(channel)) == {"Fract", ".anisotropy_angle"}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_is_clean_and_documented(path):
    text = path.read_text(encoding="utf-8")
    diagnostics = matloom.check(text)
    assert diagnostics == [], "\n".join(d.format() for d in diagnostics)
    assert text.startswith("# "), f"{path.name} should open with a '#' comment saying what it shows"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_evaluates_to_finite_maps(path):
    maps = matloom.evaluate(path.read_text(encoding="utf-8"), 64, 64)
    for name, array in maps.arrays().items():
        assert array.shape[:2] == (64, 64), name
        assert np.isfinite(array).all(), f"{path.name}: non-finite values in {name}"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_uses_language_2(path):
    program = matloom.parse(path.read_text(encoding="utf-8"))
    assert language_2_features(program), f"{path.name} uses no language-2 feature"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_has_a_preview(path):
    preview = EXAMPLES_DIR / "previews" / f"{path.stem}.png"
    assert preview.is_file(), f"missing preview {preview.relative_to(ROOT)}"
    assert _png_size(preview) == (PREVIEW_SIZE, PREVIEW_SIZE)


def test_gallery_readme_lists_every_example():
    readme = (EXAMPLES_DIR / "README.md").read_text(encoding="utf-8")
    for path in EXAMPLES:
        assert f"({path.name})" in readme, f"README.md does not link {path.name}"
        assert f"(previews/{path.stem}.png)" in readme, f"README.md does not show {path.stem}.png"
