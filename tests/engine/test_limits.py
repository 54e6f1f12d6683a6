"""Bounded evaluation (issue "Reliability" #2): Defines are shared across equal coordinate frames,
the expanded work is counted before evaluating (E071 / LimitError), the memory estimate bounds
what evaluation allocates, and the memory budget setting is validated."""

from __future__ import annotations

import math
import tracemalloc
from dataclasses import replace

import numpy as np
import pytest

import matloom
from matloom.engine.backends import available_backends, get_backend
from matloom.engine.evaluate import EvalStats, evaluate, prepare
from matloom.engine.limits import (
    MEMORY_ENV,
    LimitError,
    Limits,
    Usage,
    check_request,
    estimate_memory_mb,
    fit_seed_batch,
    memory_budget_mb,
)
from matloom.engine.schedules.seed_batch import seeded_nodes
from matloom.lang.cost import MAX_EXPANDED_NODES, FrameTable, expanded_cost, frame_key
from matloom.lang.random_program import RandomConfig, random_program

BACKENDS = available_backends()


def chain(
    levels: int, first: str = "Translate({d}, 1, 0)", second: str = "Translate({d}, 2, 0)"
) -> str:
    """The issue's reproducer: each level adds two transformed copies of the previous one."""
    lines = ["Define(d0, fBm(octaves=16, seed=1))"]
    for k in range(1, levels + 1):
        d = f"d{k - 1}"
        lines.append(f"Define(d{k}, {first.format(d=d)} + {second.format(d=d)})")
    lines.append(f"Material(Layer(1).height(d{levels}))")
    return "\n".join(lines)


def doubling_chain(levels: int) -> str:
    """Offsets 0 or 2**k per level: 2**levels distinct frames, however they are shared."""
    lines = ["Define(d0, fBm(octaves=2, seed=1))"]
    for k in range(1, levels + 1):
        lines.append(f"Define(d{k}, Translate(d{k - 1}, 0, 0) + Translate(d{k - 1}, {2**k}, 0))")
    lines.append(f"Material(Layer(1).height(d{levels}))")
    return "\n".join(lines)


# ---------------------------------------------------------------------------- frame sharing
@pytest.mark.parametrize("backend", BACKENDS)
def test_chain_of_45_levels_evaluates_each_define_once_per_distinct_frame(backend: str) -> None:
    text = chain(45)
    assert len(text) > 2500  # the issue's 2.6 KB program that never finished
    stats = EvalStats()
    maps = evaluate(text, 8, 8, backend=backend, stats=stats)
    # level 45 - j is used at offsets j..2j: j + 1 frames each
    assert stats.define_evaluations == sum(j + 1 for j in range(46)) == 1081
    assert np.isfinite(maps.height).all()


def test_rotate_chain_frames_grow_linearly() -> None:
    cost = expanded_cost(prepare(chain(45, "Rotate({d}, 1)", "Rotate({d}, 2)")))
    # rotations by 1 and 2 degrees in any order reach the angles 0..90: one frame each
    assert cost.frames <= 2 * 45 + 2
    assert cost.define_evaluations <= 1081 + 45
    assert not cost.over


def test_equal_frames_reached_by_different_paths_share_the_define() -> None:
    text = (
        "Define(n, fBm(seed=4))\n"
        "Material(Layer(1).height(Translate(Translate(n, 1, 0), 2, 0)"
        " + Translate(Translate(n, 2, 0), 1, 0)))"
    )
    for backend in BACKENDS:
        stats = EvalStats()
        evaluate(text, 16, 16, backend=backend, stats=stats)
        assert stats.define_evaluations == 1


def test_shared_define_equals_its_single_path_value() -> None:
    """Sharing only changes which path's coordinates a Define uses: here both are exact."""
    shared = "Define(n, fBm(seed=4))\nMaterial(Layer(1).height(Translate(n, 1, 0) + Translate(Scale(n, 1, 1), 1, 0)))"
    single = "Define(n, fBm(seed=4))\nMaterial(Layer(1).height(Translate(n, 1, 0) * 2))"
    a = evaluate(shared, 32, 32, backend="numpy")
    b = evaluate(single, 32, 32, backend="numpy")
    np.testing.assert_array_equal(a.height, b.height)


def test_distinct_frames_stay_distinct() -> None:
    table = FrameTable()
    near = table.child(0, "Translate", (1e-9, 0.0))
    assert near != 0
    assert table.child(0, "Translate", (0.0, 0.0)) == 0
    assert table.child(0, "Scale", (1.0, 1.0)) == 0
    assert table.child(0, "Rotate", (math.cos(0.0), math.sin(0.0))) == 0
    assert table.child(0, "Scale", (-1.0, 1.0)) not in (0, near)
    assert table.child(0, "Translate", (math.nan, 0.0)) not in (0, near)  # never merged
    assert frame_key((1.0, 0.0, -0.0, 0.0, 1.0, 0.0)) == frame_key((1.0 + 1e-15, 0, 0, 0, 1, 0))
    assert frame_key((1.0, 0, 0, 0, 1, 0)) != frame_key((1.0 + 1e-9, 0, 0, 0, 1, 0))


PROGRAMS = (
    [random_program(s) for s in range(12)]
    + [
        random_program(s, config=RandomConfig(min_defs=4, max_defs=8, max_depth=4))
        for s in range(6)
    ]
    + [
        chain(6, "Rotate({d}, 30)", "Scale({d}, 2, 1)"),
        chain(5, "Scale({d}, -1, 1)", "Translate({d}, 0.5, 0.25)"),
    ]
)


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("index", range(len(PROGRAMS)))
def test_static_count_matches_the_evaluator(index: int, backend: str) -> None:
    program = prepare(PROGRAMS[index])
    stats = EvalStats()
    evaluate(program, 8, 8, backend=backend, stats=stats)
    assert stats.define_evaluations == expanded_cost(program).define_evaluations


# ---------------------------------------------------------------------------- work limits
def test_check_reports_exponential_frames_with_count_and_limit() -> None:
    diags = [d for d in matloom.check(doubling_chain(30)) if d.is_error]
    assert [d.code for d in diags] == ["E071"]
    assert f"{MAX_EXPANDED_NODES:,}" in diags[0].message
    assert "Define evaluations" in diags[0].message


def test_check_accepts_the_shared_chain() -> None:
    assert not [d for d in matloom.check(chain(45)) if d.is_error]
    assert not [
        d for d in matloom.check(chain(45, "Rotate({d}, 1)", "Rotate({d}, 2)")) if d.is_error
    ]


def test_evaluate_refuses_an_unchecked_program_over_the_node_limit() -> None:
    program = matloom.parse(doubling_chain(3))
    limits = Limits(max_expanded_nodes=10)
    with pytest.raises(LimitError, match="expression-node evaluations"):
        evaluate(program, 8, 8, limits=limits)


def test_evaluate_refuses_the_unchecked_weave_of_the_issue_before_any_work() -> None:
    """Issue 22 #2: an unchecked program (no E071 from the checker) with the 2^20-step Weave
    search is refused by the engine's count, naming the call, instead of running for seconds
    (hours inside Tiles)."""
    from matloom.lang.parser import parse_source

    text = (
        'Define(cloth, Weave(over=1048576, under=1, shift=2, output="along"))\n'
        "Material(Layer(1).height(Tile(Translate(cloth, 0.5, 0), 1, 1, seed=1)))\n"
    )
    program, diags = parse_source(text)  # parsed, not checked
    assert program is not None and not diags
    with pytest.raises(LimitError, match=r"Weave in Define 'cloth' counts [\d,]+ node") as err:
        evaluate(program, 4, 4)
    assert "\n" not in str(err.value) and "E071" in str(err.value)


def test_the_largest_texel_limit_names_the_costliest_call() -> None:
    program = prepare("Material(Layer(1).height(Worley(seed=1) + fBm(octaves=16, seed=2)))")
    nodes = expanded_cost(program).nodes
    limits = Limits(max_node_texels=nodes * 64)
    with pytest.raises(LimitError, match="costliest call is Worley in layer 0"):
        evaluate(program, 9, 8, limits=limits)


def test_every_library_entry_and_docs_example_fits_at_the_largest_size() -> None:
    """The work weights and the node-texel budget together: every shipped program renders at
    8192x8192 (the weights were measured, the budget was set so that none is refused)."""
    from pathlib import Path

    from matloom.lang.parser import parse_source
    from matloom.library import library

    texts = {name: entry.program for name, entry in library().entries.items()}
    examples = Path(__file__).resolve().parents[2] / "docs" / "examples"
    texts |= {p.name: p.read_text() for p in sorted(examples.glob("*.mat"))}
    assert len(texts) > 400
    cap = Limits().max_node_texels // (8192 * 8192)
    over = []
    for name, text in texts.items():
        program, _ = parse_source(text)  # parsed only: the library tests check them
        assert program is not None, name
        if expanded_cost(program, cap).over:
            over.append(name)
    assert not over


def test_node_texel_limit_depends_on_the_size() -> None:
    program = prepare(chain(4))
    nodes = expanded_cost(program).nodes
    limits = Limits(max_node_texels=nodes * 64)
    evaluate(program, 8, 8, limits=limits)  # exactly at the limit
    with pytest.raises(LimitError, match="node-texels"):
        evaluate(program, 9, 8, limits=limits)


@pytest.mark.parametrize(
    "width, height", [(0, 8), (8, -1), (8.5, 8), ("8", 8), (True, 8), (9000, 8)]
)
def test_bad_sizes_are_limit_errors(width: object, height: object) -> None:
    with pytest.raises(LimitError):
        evaluate(chain(1), width, height)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------- memory
@pytest.mark.parametrize("raw", ["abc", "-1", "0", "nan", "inf", "-inf", "1e999", "12MB"])
def test_bad_memory_budget_is_a_one_line_limit_error(
    raw: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(MEMORY_ENV, raw)
    with pytest.raises(LimitError, match=MEMORY_ENV) as info:
        evaluate(chain(1), 8, 8)
    assert "\n" not in str(info.value)


def test_memory_budget_setting() -> None:
    assert memory_budget_mb({}) == 8192
    assert memory_budget_mb({MEMORY_ENV: " 512 "}) == 512
    assert memory_budget_mb({MEMORY_ENV: "0.5"}) == 0.5


def test_memory_budget_is_read_at_each_request(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(MEMORY_ENV, "1")
    with pytest.raises(LimitError, match="needs about"):
        evaluate(chain(1), 512, 512)
    monkeypatch.setenv(MEMORY_ENV, "4096")
    evaluate(chain(1), 64, 64)


def test_estimate_grows_with_define_evaluations() -> None:
    small = expanded_cost(prepare(chain(2)))
    large = expanded_cost(prepare(chain(20)))
    for fused in (True, False):
        assert estimate_memory_mb(256, 256, large, fused=fused) > estimate_memory_mb(
            256, 256, small, fused=fused
        )


MEMORY_PROGRAMS = [PROGRAMS[i] for i in (0, 3, 12, 14, len(PROGRAMS) - 2, len(PROGRAMS) - 1)]


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("index", range(len(MEMORY_PROGRAMS)))
def test_traced_peak_is_below_the_estimate(index: int, backend: str) -> None:
    """numpy's buffers (traced by tracemalloc) stay under the estimate; benchmarks/soak.py
    checks peak RSS over many more programs."""
    program = prepare(MEMORY_PROGRAMS[index])
    be = get_backend(backend)
    evaluate(program, 8, 8, backend=be)
    estimate = check_request(program, 160, 96, fused=be.fused).memory_mb
    tracemalloc.start()
    try:
        evaluate(program, 160, 96, backend=be)
        peak = tracemalloc.get_traced_memory()[1] / 2**20
    finally:
        tracemalloc.stop()
    assert peak <= estimate, (peak, estimate)


def test_a_sweep_chunk_shrinks_to_fit_the_budget() -> None:
    program = prepare(chain(6, "Rotate({d}, 30)", "Scale({d}, 2, 1)"))
    usage = Usage(seed_batch=64, threads=2, batched=frozenset(seeded_nodes(program)))
    roomy = fit_seed_batch(program, 256, 256, usage)
    one = check_request(program, 256, 256, fused=False, usage=replace(usage, seed_batch=1))
    tight = fit_seed_batch(program, 256, 256, usage, Limits(max_memory_mb=one.memory_mb * 1.5))
    assert roomy == 64
    assert 1 <= tight < 64
    with pytest.raises(LimitError, match="sweeping"):
        fit_seed_batch(program, 256, 256, usage, Limits(max_memory_mb=1))
