"""The library author's API: canonical, deterministic, explainable, pick and seed."""

from __future__ import annotations

import pytest

import matloom
from matloom.lang.seeds import has_seedless_noise
from matloom.library import author, library


def seeds(text: str) -> list[str]:
    return [part.split(")")[0].split(",")[0] for part in text.split("seed=")[1:]]


def test_program_is_clean_canonical_and_commented() -> None:
    r = author("mossy cobblestone")
    assert matloom.check(r.program) == []
    body = "\n".join(line for line in r.program.splitlines() if not line.startswith("#"))
    assert matloom.format(body) == body.rstrip("\n")
    assert r.program.startswith("# library entry: cobblestone (stone)")
    assert "# overlay: mossy" in r.program
    assert not has_seedless_noise(matloom.parse(r.program))


def test_same_prompt_and_seed_give_the_same_result() -> None:
    a = author("large walnut planks, worn", seed=3)
    b = author("large walnut planks, worn", seed=3)
    assert a.program == b.program
    assert a.explanation == b.explanation


def test_seed_changes_the_noise_seeds_only() -> None:
    a = author("cobblestone", seed=0)
    b = author("cobblestone", seed=7)
    assert a.entry == b.entry
    assert seeds(a.program) != seeds(b.program)
    assert seeds(a.program) == seeds(library().entry("cobblestone").program)
    strip = lambda t: [ln for ln in t.splitlines() if "seed=" not in ln]  # noqa: E731
    assert strip(a.program) == strip(b.program)


def test_pick_takes_the_nth_candidate() -> None:
    best = author("cracked desert mud")
    second = author("cracked desert mud", pick=2)
    assert second.entry == best.candidates[1].name != best.entry
    assert second.rank == 2
    with pytest.raises(ValueError, match="candidates"):
        author("cracked desert mud", pick=999)


def test_explanation_lists_candidates_entry_adaptations_and_ignored_words() -> None:
    r = author("large red brick wall with zorblax, mossy")
    text = r.explanation
    for needle in (
        "candidates:",
        "*1. brick-wall",
        "entry: brick-wall",
        "adaptations:",
        "View",
        "colour brick",
        "overlays: mossy",
        "ignored: zorblax",
    ):
        assert needle in text, (needle, text)


def test_unit_m_is_the_entrys_physical_size_over_the_view() -> None:
    r = author("cobblestone")
    entry = library().entry("cobblestone")
    side = abs(matloom.parse(r.program).view.x2 - matloom.parse(r.program).view.x1)
    assert abs(r.unit_m * side - entry.size_m) < 1e-6


def test_empty_prompt_still_gives_a_program() -> None:
    r = author("")
    assert r.entry == "generic-surface"
    assert matloom.check(r.program) == []


def test_long_descriptive_prompt() -> None:
    r = author(
        "This fabric is cornflower blue with embossed horizontal lines woven throughout. "
        "It has a sheen to it and feels soft."
    )
    assert library().entry(r.entry).category == "fabric"
    assert matloom.check(r.program) == []


def test_a_parameterised_define_survives_the_author() -> None:
    # language 3's Define(name(a), expr) is used by calls of its name, not by Refs: pruning the
    # unused Defines dropped it, and `matloom generate` failed with E030 on such entries
    from matloom.lang.api import parse
    from matloom.library.overlay import prune_defines

    text = (
        "Define(ring(d), Clamp(((0.1 - d) * 10), 0, 1))\nDefine(unused, 3)\n"
        "Material(Layer(1).basecolor((ring(Abs(X())) * 255), 0, 0))"
    )
    pruned = prune_defines(parse(text))
    assert [d.name for d in pruned.defines] == ["ring"]
    for request in ("sashiko stitching", "amethyst geode crystal cluster"):
        r = author(request)
        assert any(d.params for d in r.ast.defines), r.entry  # an entry that uses them
        assert matloom.check(r.program) == [], r.explanation
