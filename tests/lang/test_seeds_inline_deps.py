"""Seed canonicalisation, seed variants, the Define inliner and channel dependency sets."""

from __future__ import annotations

import difflib
import random
import re
from pathlib import Path

import numpy as np
import pytest

import matloom
from matloom.lang import ast as A
from matloom.lang.deps import channel_dependencies
from matloom.lang.inline import inline_defines
from matloom.lang.printer import format_program
from matloom.lang.seeds import SEED_LIMIT, canonicalize_seeds, derive_seed, seed_variants
from matloom.lang.static import static_number

PARITY = Path(__file__).resolve().parents[1] / "data" / "parity"
SEED_LITERAL = re.compile(r"seed=(\d+)")


def _fixture(name: str) -> str:
    return (PARITY / f"{name}.mat").read_text(encoding="utf-8")


def _seeds(text: str) -> list[int]:
    return [int(s) for s in SEED_LITERAL.findall(text)]


def _canonical(text: str, program_seed: int) -> str:
    return format_program(canonicalize_seeds(matloom.parse(text), program_seed))


# ---------------------------------------------------------------------------- canonicalize_seeds
def test_canonicalize_is_deterministic_and_ignores_global_random_state() -> None:
    source = _fixture("seedless")
    random.seed(1)
    np.random.seed(1)
    first = _canonical(source, 123)
    random.seed(999)
    np.random.seed(999)
    py_state, np_state = random.getstate(), np.random.get_state()
    second = _canonical(source, 123)
    assert first == second
    # ... and it does not consume global random numbers either
    assert random.getstate() == py_state
    assert np.array_equal(np.random.get_state()[1], np_state[1])


def test_different_program_seeds_give_different_seeds() -> None:
    source = _fixture("seedless")
    a, b = _seeds(_canonical(source, 1)), _seeds(_canonical(source, 2))
    assert len(a) == len(b) == 4
    assert all(x != y for x, y in zip(a, b, strict=True))
    assert all(0 <= s < SEED_LIMIT for s in a + b)


def test_canonicalize_follows_the_reference_draw_order() -> None:
    """Defines first, then layers in fixed channel order (roughness after basecolor), post-order."""
    text = _canonical(_fixture("seedless"), 77)
    assert _seeds(text) == [derive_seed(77, k) for k in range(4)]


def test_shared_define_noise_keeps_one_seed_and_identical_inline_calls_differ() -> None:
    program = canonicalize_seeds(matloom.parse(_fixture("seedless")), 5)
    seeds_by_freq: dict[float, set[int]] = {}
    for _, expr in A.program_expressions(inline_defines(program)):
        for node in A.walk(expr):
            if isinstance(node, A.Call) and node.func == "fBm":
                freq = static_number(node.arg("base_freq"))
                seeds_by_freq.setdefault(freq, set()).add(static_number(node.arg("seed")))
    assert len(seeds_by_freq[3]) == 1  # Define(n, fBm(.., base_freq=3)) used 4 times: one seed
    assert len(seeds_by_freq[8]) == 2  # two textually identical inline calls: two seeds


def test_explicit_seeds_are_kept() -> None:
    source = _fixture("tile")
    assert _canonical(source, 3) == format_program(matloom.parse(source))


# ---------------------------------------------------------------------------- seed variants
def _seed_spans(text: str) -> list[tuple[int, int]]:
    return [m.span(1) for m in SEED_LITERAL.finditer(text)]


def test_seed_variants_count_and_original_first() -> None:
    text = _canonical(_fixture("seedless"), 0)
    variants = seed_variants(text, 3, seed=11)
    assert len(variants) == 4 and variants[0] == text
    assert len(set(variants)) == 4


def test_seed_variants_change_only_seed_digits() -> None:
    text = _fixture("brick").strip()
    spans = _seed_spans(text)
    for variant in seed_variants(text, 3, seed=4)[1:]:
        assert SEED_LITERAL.sub("seed=N", variant) == SEED_LITERAL.sub("seed=N", text)
        matcher = difflib.SequenceMatcher(None, text, variant, autojunk=False)
        for op, i1, i2, _, _ in matcher.get_opcodes():
            if op == "equal":
                continue
            assert any(lo <= i1 and i2 <= hi for lo, hi in spans), (op, text[i1:i2])
        matloom.parse(variant)  # still a valid program


def test_seed_variants_preserve_equality_groups() -> None:
    text = (
        "Define(a, fBm(seed=5))\nDefine(b, fBm(octaves=2, seed=5))\nDefine(c, Worley(seed=9))\n"
        "Material(Layer(1).roughness(a + b + c))"
    )
    for variant in seed_variants(text, 5, seed=0)[1:]:
        s = _seeds(variant)
        assert s[0] == s[1]  # shared seeds stay shared
        assert s[2] != s[0]  # distinct seeds are redrawn independently
        assert all(0 <= v < SEED_LIMIT for v in s)


def test_seed_variants_are_reproducible_and_remap_negative_seeds() -> None:
    text = _fixture("tile")
    assert seed_variants(text, 3, seed=7) == seed_variants(text, 3, seed=7)
    assert seed_variants(text, 3, seed=7) != seed_variants(text, 3, seed=8)
    negative = seed_variants("fBm(seed=-3) + fBm(seed = -3)", 2, seed=1)
    assert all(v >= 0 for t in negative[1:] for v in map(int, re.findall(r"\d+", t)))


@pytest.mark.parametrize("k", [0, -1])
def test_no_variants_for_k_below_one(k: int) -> None:
    assert seed_variants(_fixture("tile"), k) == [_fixture("tile")]


def test_no_variants_without_seeds() -> None:
    text = _fixture("bricks")
    assert seed_variants(text, 3) == [text]


# ---------------------------------------------------------------------------- inliner
def test_inlined_tile_has_no_define_and_reparses() -> None:
    program = matloom.parse(_fixture("tile"))
    inlined_text = format_program(inline_defines(program))
    assert "Define(" not in inlined_text
    reparsed = matloom.parse(inlined_text)
    assert reparsed.defines == ()
    assert inlined_text.count("Bricks(") == 3  # tileMask: alpha + two uses in height
    assert inlined_text.count("seed=1007923142") == 1  # glazeGrain used once
    assert format_program(inline_defines(reparsed)) == inlined_text


def test_inlining_chained_defines() -> None:
    program = matloom.parse(_fixture("defines_chain"))
    inlined = inline_defines(program)
    assert inlined.defines == ()
    assert not any(
        isinstance(n, A.Ref) for _, e in A.program_expressions(inlined) for n in A.walk(e)
    )
    assert matloom.parse(format_program(inlined)) == inlined


def test_inliner_refuses_exponential_growth_but_the_program_stays_valid() -> None:
    doubling = "".join(f"Define(d{k}, d{k - 1} + d{k - 1})\n" for k in range(1, 40))
    text = "Define(d0, X())\n" + doubling + "Material(Layer(1).height(d39))"
    assert matloom.check(text) == []  # shallow and small as written (Defines are shared)
    with pytest.raises(matloom.ProgramError) as info:
        inline_defines(matloom.parse(text))
    assert info.value.diagnostics[0].code == "E070"


def test_inlined_output_of_a_long_define_chain_reparses() -> None:
    chain = "".join(f"Define(d{k}, d{k - 1} + 1)\n" for k in range(1, 99))
    program = matloom.parse("Define(d0, X())\n" + chain + "Material(Layer(1).height(d98))")
    inlined_text = format_program(inline_defines(program))
    assert matloom.parse(inlined_text).defines == ()


#: named noises without a seed, used more than once and next to seedless inline noise
_SEEDLESS_NAMED = [
    _fixture("seedless"),
    "Define(grain, fBm(base_freq=6, to_01=True))\n"
    "Define(cells, Worley(base_freq=4, to_01=True))\n"
    "Material(Layer(1).basecolor(grain * 200, cells * 180, 60)"
    ".roughness(fBm(base_freq=9, to_01=True) * 0.5 + grain * 0.5).height(cells * 0.02 + grain * 0.01))",
]


def _map_hashes(program: A.Program | str) -> dict[str, str]:
    import hashlib

    from matloom.engine.evaluate import evaluate
    from matloom.engine.maps import ARRAY_FIELDS

    maps = evaluate(program, 32, 32)
    return {
        k: hashlib.sha256(np.ascontiguousarray(getattr(maps, k)).tobytes()).hexdigest()
        for k in ARRAY_FIELDS
    }


@pytest.mark.parametrize("source", _SEEDLESS_NAMED, ids=["seedless-fixture", "two-named"])
def test_inlining_seedless_named_noise_keeps_every_map_bit_identical(source: str) -> None:
    # `fmt --inline` prints this text: rendering it must give the maps the original gives
    inlined_text = format_program(inline_defines(matloom.parse(source)))
    assert "Define(" not in inlined_text
    assert _map_hashes(inlined_text) == _map_hashes(source)


# ---------------------------------------------------------------------------- dependencies
def _literal_ref(deps, line_no: int, needle: str, source: str):
    line = source.splitlines()[line_no - 1]
    col = line.index(needle) + 1
    hits = [p for p in deps if (p.line, p.col) == (line_no, col)]
    assert len(hits) == 1, (line_no, col, needle)
    return hits[0]


def test_tile_dependencies_follow_the_paper() -> None:
    source = _fixture("tile")
    deps = channel_dependencies(matloom.parse(source))
    lines = source.splitlines()
    rough_line = next(i for i, t in enumerate(lines, 1) if "(0.04 + (glazeGrain" in t)
    grain_line = next(i for i, t in enumerate(lines, 1) if t.startswith("Define(glazeGrain"))
    mask_line = next(i for i, t in enumerate(lines, 1) if t.startswith("Define(tileMask"))
    roughness_only = [
        _literal_ref(deps["roughness"], rough_line, "0.04", source),
        _literal_ref(deps["roughness"], rough_line, "0.05", source),
        _literal_ref(deps["roughness"], grain_line, "5", source),  # octaves=5
        _literal_ref(deps["roughness"], grain_line, "35", source),  # base_freq=35
        _literal_ref(deps["roughness"], grain_line, "1007923142", source),  # seed
    ]
    for ref in roughness_only:
        assert ref in deps["roughness"]
        assert ref not in deps["basecolor"]
        assert ref not in deps["height"]
        assert ref not in deps["alpha"]
    assert roughness_only[-1].is_seed
    mortar = _literal_ref(deps["alpha"], mask_line, "0.02", source)
    for channel in ("alpha", "height", "basecolor", "roughness", "normal", "ao"):
        assert mortar in deps[channel]
