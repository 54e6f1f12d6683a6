"""The generator and critic prompts: rendered from the registry, snapshot-tested, examples valid.

Regenerate the snapshot after an intended change with::

    MATLOOM_UPDATE_SNAPSHOTS=1 .venv/bin/python -m pytest tests/author/test_prompts.py
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import matloom
from matloom.author.prompts.critic import critic_system_prompt, critic_user_message
from matloom.author.prompts.system import FEW_SHOT_EXAMPLES, PITFALLS, PLAYBOOK, system_prompt
from matloom.cli.main import cli
from matloom.vocab import CHANNELS, FUNCTIONS

STRUCTURE = {"View", "Define", "Material", "Layer"}
SNAPSHOT = Path(__file__).parent / "snapshots" / "system_prompt.txt"
#: The paper's six example descriptions and their layer counts (reference-engine.md §8.2).
PAPER_EXAMPLES = {
    "Polished green marble": 1,
    "Frosted glass panel in a brushed steel frame": 2,
    "Weathered red brick wall with pale mortar": 3,
    "Chipped blue paint over rusted steel": 4,
    "Beach sand with pebbles": 3,
    "Glow-in-the-dark stars with a crescent moon and a comet": 4,
}


def test_system_prompt_snapshot() -> None:
    text = system_prompt()
    if os.environ.get("MATLOOM_UPDATE_SNAPSHOTS"):
        SNAPSHOT.parent.mkdir(parents=True, exist_ok=True)
        SNAPSHOT.write_text(text, encoding="utf-8")
    assert SNAPSHOT.exists(), "run with MATLOOM_UPDATE_SNAPSHOTS=1 to create the snapshot"
    assert text == SNAPSHOT.read_text(encoding="utf-8")


def test_every_function_and_channel_is_documented_from_the_registry() -> None:
    text = system_prompt()
    for spec in FUNCTIONS.values():
        assert f"`{spec.signature()}`" in text, spec.name
        assert spec.doc in text, spec.name
    for channel in CHANNELS.values():
        assert f"`.{channel.name}({', '.join(channel.arg_names)})`" in text
        assert channel.units in text


def test_prose_names_only_registry_functions() -> None:
    """Hand-written sections may mention calls, but only ones the parser knows."""
    for section in (PITFALLS, PLAYBOOK):
        for name in re.findall(r"`([A-Za-z_]+)\(", section):
            assert name in FUNCTIONS or name in STRUCTURE, name
        for name in re.findall(r"`([A-Za-z_]+)`", section):
            assert name in FUNCTIONS or any(name in s.param_names for s in FUNCTIONS.values()), name


def test_sections_of_the_reference_prompt_are_present() -> None:
    text = system_prompt()
    for heading in (
        "# Program structure",
        "# Coordinates & View",
        "# Define",
        "# Expressions",
        "## Threshold",
        "## Noise",
        "## Patterns",
        "## Shapes",
        "## Transforms",
        "## Combining masks",
        "# Five things that surprise generators",
        "# Organic texture playbook",
        "# Examples",
        "# Output format",
    ):
        assert heading in text, heading
    assert text.startswith("You are an expert technical artist.")
    assert text.count("<material>") == 1 + len(FEW_SHOT_EXAMPLES)
    assert len(re.findall(r"^\d\. ", PITFALLS, re.MULTILINE)) == 5
    assert PLAYBOOK.count("\n- ") == 5


def test_optional_sections_can_be_left_out() -> None:
    bare = system_prompt(playbook=False, few_shot=False)
    assert "# Organic texture playbook" not in bare
    assert "Description:" not in bare
    assert "# Output format" in bare


@pytest.mark.parametrize("example", FEW_SHOT_EXAMPLES, ids=lambda e: e.file_name)
def test_few_shot_example_is_canonical_clean_and_renders(example) -> None:
    program = example.program()
    assert matloom.check(program) == []  # no errors and no warnings
    assert matloom.format(program) == program  # canonical: the model sees what it will get back
    assert len(matloom.parse(program).layers) == PAPER_EXAMPLES[example.description]
    image = matloom.preview(program, 64)
    assert image.shape == (64, 64, 3) and image.dtype == np.uint8
    assert image.std() > 2.0  # a pattern, not a flat swatch


def test_few_shot_descriptions_are_the_papers_six() -> None:
    assert [e.description for e in FEW_SHOT_EXAMPLES] == list(PAPER_EXAMPLES)


def test_critic_prompt_depends_on_signals() -> None:
    full = critic_system_prompt(["render", "stats", "code"])
    assert "a single render" in full and "# Program structure" in full
    assert "ground your visual judgment" in full
    text_only = critic_system_prompt(["stats", "code"])
    assert "no render is shown" in text_only and "a single render" not in text_only
    render_only = critic_system_prompt(["render"])
    assert "never assume anything about the code" in render_only
    assert "# Program structure" not in render_only


def test_critic_user_message_is_co_star() -> None:
    msg = critic_user_message("red brick", ["render", "code", "stats"], program="P", stats="S")
    for section in (
        "## Context",
        "## Objective",
        "## Style",
        "## Tone",
        "## Audience",
        "## Response",
    ):
        assert section in msg
    assert "<description>red brick</description>" in msg and "<program>\nP\n</program>" in msg
    assert '"match_score"' in msg


def test_prompt_command_prints_the_system_prompt() -> None:
    result = CliRunner().invoke(cli, ["prompt", "--print"])
    assert result.exit_code == 0
    assert result.stdout == system_prompt()
