"""Unit tests of the prompt texts: revision sections, the critic schema and layouts, the measured
"Resolution and previews" section, one answer format, answer extraction and seed notes."""

from __future__ import annotations

import re

import pytest

import matloom
from matloom.author.prompts.critic import (
    PreviousView,
    critic_system_prompt,
    critic_user_message,
    response_skeleton,
)
from matloom.author.prompts.previews import (
    VISIBLE_LEVELS,
    channel_changes,
    previews_section,
    slope_changes,
)
from matloom.author.prompts.revision import (
    diagnostics_message,
    missing_program_message,
    reply_too_large_message,
    revision_message,
)
from matloom.author.prompts.system import ANSWER_FORMAT, system_prompt
from matloom.author.records import EditRecord
from matloom.author.stages.critique_parse import parse_critique
from matloom.author.stages.generate import added_seed_notes, extract_answer
from matloom.lang.api import analyse, parse
from matloom.lang.seeds import canonicalize_seeds
from matloom.render.lit import LIT_LAYOUT_NOTE


def sections(text: str) -> dict[str, str]:
    return {
        title: body.strip() for title, body in re.findall(r"## (.+)\n((?:(?!## ).*\n?)*)", text)
    }


def test_revision_message_sections() -> None:
    text = revision_message(
        61,
        ["the grout is too wide"],
        [],
        edits=[EditRecord(layer=0, channel="basecolor", change="(40, 40, 40) -> (90, 90, 90)")],
        views=("flat", "lit"),
        added_seeds=["fBm at line 2, column 15: seed=7"],
        previous_score=48,
    )
    parts = sections(text)
    assert list(parts) == [
        "Score", "What differs", "What to change", "Concrete edits", "Preview", "Seeds", "Answer",
    ]  # fmt: skip
    assert parts["Score"] == "61/100 (the previous version scored 48/100)"
    assert parts["What to change"] == "- (no suggestions)"
    assert parts["Concrete edits"] == "- layer 0 .basecolor: (40, 40, 40) -> (90, 90, 90)"
    assert "the flat and the lit previews" in parts["Preview"]
    assert "- fBm at line 2, column 15: seed=7" in parts["Seeds"]
    assert parts["Answer"].endswith(ANSWER_FORMAT)
    bare = sections(revision_message(30, [], ["darker"]))
    assert list(bare) == ["Score", "What differs", "What to change", "Answer"]
    assert bare["Score"] == "30/100" and bare["What differs"] == "- (none noted)"


def test_every_generator_turn_asks_for_the_same_answer_format() -> None:
    _, diagnostics = analyse("Material(Layer(1).roughnes(1))")
    for text in (
        missing_program_message(),
        reply_too_large_message(10, 5),
        diagnostics_message("x", diagnostics),
        revision_message(50, [], []),
    ):
        assert ANSWER_FORMAT in text
        assert "ONLY" not in text and "only the" not in text
    assert "the last one is used" in system_prompt() and "Think first" in system_prompt()


def test_critic_schema_shows_a_number_and_optional_fields() -> None:
    full = response_skeleton(edits=True, history=True)
    assert '"match_score": <number 0-100' in full and '"match_score": "' not in full
    assert '"edits": [{"layer": <layer index' in full and '"define": "<Define name>"' in full
    assert '"better_than_previous": <true or false>' in full
    plain = response_skeleton(edits=False)
    assert "edits" not in plain and "better_than_previous" not in plain
    render_only = critic_user_message("slate", ["render"], program=None, stats=None)
    assert '"edits"' not in render_only and "match_score is a number" in render_only
    with_code = critic_user_message("slate", ["render", "code"], program="P", stats=None)
    assert '"edits"' in with_code and "leave the list empty" in with_code


def test_critic_layouts_and_history_in_the_prompts() -> None:
    flat = critic_system_prompt(["render", "code"])
    assert "a single render of the material on a flat plane seen head-on" in flat
    assert "do not over-penalise those" in flat and "lit render" not in flat
    both = critic_system_prompt(["render", "code"], ("flat", "lit"), history=True)
    assert "2 renders of the same material" in both
    assert f"About the lit render: {LIT_LAYOUT_NOTE.split(': ', 1)[1]}" in both
    assert "judge gloss, metal, sheen, coat, transmission and relief from the lit render" in both
    assert "previous version's render(s) and score" in both and "regression" in both
    user = critic_user_message(
        "slate", ["render"], program=None, stats=None, views=("flat", "lit"),
        previous=PreviousView(index=0, score=40, images=2), history=True,
    )  # fmt: skip
    assert (
        "1. this version, flat layout; 2. this version, lit layout; 3. the previous version, "
        "flat layout; 4. the previous version, lit layout" in user
    )
    assert "scored 40/100" in user and '"better_than_previous"' in user


def test_previews_section_follows_the_render_size() -> None:
    text = previews_section(256)
    assert "256 x 256 px" in text and "(x2 - x1) / 256" in text and "0.00391" in text
    assert "at most about 64 repeats" in text and "a slope of 0.31" in text
    assert "The lit preview" not in text


def test_previews_section_is_measured_from_the_shading() -> None:
    flat = channel_changes("flat")
    assert flat["metallic"] >= VISIBLE_LEVELS > flat["roughness"]  # no environment to reflect
    assert flat["anisotropy_angle"] == 0
    lit = channel_changes("lit")
    for name in ("roughness", "metallic", "coat", "transmission", "anisotropy_angle"):
        assert lit[name] >= VISIBLE_LEVELS, name
    slopes = list(slope_changes("flat").values())
    assert slopes == sorted(slopes) and slopes[-1] > 40
    text = previews_section(512, ("flat", "lit"))
    hidden = {
        view: line.split("cannot show ", 1)[1].split(" (under", 1)[0].split(", ")
        for view, line in zip(("flat", "lit"), re.findall(r"It cannot show .*", text))
    }
    assert hidden["flat"] == [n for n, v in flat.items() if v < VISIBLE_LEVELS]
    assert "roughness" in hidden["flat"] and "roughness" not in hidden["lit"]
    assert LIT_LAYOUT_NOTE.split(": ", 1)[1].rstrip(".") in text


def test_system_prompt_describes_the_runs_layouts() -> None:
    default = system_prompt()
    assert "# Resolution and previews" in default and "The flat preview" in default
    both = system_prompt(views=("flat", "lit"), render_size=384)
    assert "The lit preview" in both and "384 x 384 px" in both


def test_parse_critique_edits_and_verdict() -> None:
    answer = parse_critique(
        '{"match_score": "81/100", "differences": null, "suggestions": "x", "edits": ['
        '{"layer": "2", "channel": "height", "change": "x 0.5"}, {"layer": 1}, 7, [], '
        '{"define": "veins", "value": "base_freq 3 -> 5"}], "better_than_previous": "yes"}'
    )
    assert answer.match_score == 81 and answer.differences == [] and answer.suggestions == ["x"]
    assert [(e.layer, e.channel, e.define, e.change) for e in answer.edits] == [
        (2, "height", None, "x 0.5"),
        (None, None, "veins", "base_freq 3 -> 5"),
    ]  # an entry with no change (an object without one, a bare number) is dropped
    assert answer.better_than_previous is True
    assert parse_critique('{"match_score": 5, "better_than_previous": "unsure"}').edits == []
    assert (
        parse_critique('{"match_score": 5, "better_than_previous": false}').better_than_previous
        is False
    )


@pytest.mark.parametrize(
    ("reply", "program"),
    [
        ("a <material>A</material> b <material>B</material> c", "B"),
        ("<MATERIAL>A</MATERIAL> talk about <material> then </material>", " then "),
        ("no tags\nMaterial(Layer(1))", "Material(Layer(1))"),
        ("<material>A</material> and an unclosed <material> B", "A"),
    ],
)
def test_extract_answer_takes_the_last_complete_block(reply: str, program: str) -> None:
    found, _ = extract_answer(reply)
    assert found is not None and found.strip() == program.strip()


def test_seed_notes_match_the_canonical_seeds() -> None:
    source = (
        "Define(g, fBm(octaves=3))\n"
        "Material(Layer(1).roughness(Worley()).basecolor(g * 255, 9, fBm(seed=4)))"
    )
    canonical = matloom.format(source)
    notes = added_seed_notes(source, canonical, 11)
    pinned = matloom.format(canonicalize_seeds(parse(canonical), 11))
    seeds = re.findall(r"seed=(\d+)", pinned)
    assert notes == [
        f"fBm at line 1, column 11: seed={seeds[0]}",
        f"Worley at line 2, column 29: seed={seeds[2]}",
    ]
    same_seeds = [n.split(": ")[1] for n in added_seed_notes(canonical, canonical, 11)]
    assert same_seeds == [n.split(": ")[1] for n in notes]
