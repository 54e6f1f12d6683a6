"""`--drafts N`: the generator writes N first drafts, each asked to take a different approach;
every draft is critiqued, and the revisions continue from the best one.

Runs against the scripted Chat Completions server on 127.0.0.1 (see chat_server.py).
"""

from __future__ import annotations

import json
from pathlib import Path

from author.chat_server import ChatServer
from author.conftest import Script, image_parts, is_critic, text_of
from author.test_loop_v3 import answer, brick, critique, generate, recommended, requests_of
from matloom.author.config import AuthorConfig
from matloom.author.prompts.revision import draft_message
from matloom.author.records import validate_record_file
from matloom.author.settings_presets import preset_values

#: Three drafts that differ visibly (the mortar's colour).
DRAFTS = [brick("190, 185, 175"), brick("90, 85, 80"), brick("230, 225, 215")]


def test_revisions_continue_from_the_best_draft(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    script.generator.extend([answer(p) for p in DRAFTS])
    script.critic.extend([critique(50), critique(80), critique(60), critique(85)])
    result = recommended(server, tmp_path / "run", "--drafts", "3", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    generator = requests_of(server, critic=False)
    assert len(generator) == 4 and len(requests_of(server, critic=True)) == 4
    # each later draft sees the earlier ones as its own answers and is asked for another
    for number, request in ((2, generator[1]), (3, generator[2])):
        messages = request["messages"]
        assert text_of(messages[-1]) == draft_message(number, 3)
        mine = [text_of(m) for m in messages if m["role"] == "assistant"]
        assert mine == [answer(p) for p in DRAFTS[: number - 1]]
    # the revision continues from draft 2, the critic's best, and shows its program
    revision = text_of(generator[3]["messages"][-1])
    assert "Continuing from draft 2 (score 80/100), the best so far; draft 3: score 60/100" in (
        revision
    )
    assert f"<material>\n{DRAFTS[1]}\n</material>" in revision
    assert "Dropped attempt" not in revision  # an unchosen draft is not a dropped revision
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert [t.kind for t in record.turns] == ["initial", "draft", "draft", "revision"]
    assert len(record.programs) == 4 and record.settings.drafts == 3


def test_drafts_have_no_previous_round(script: Script, server: ChatServer, tmp_path: Path) -> None:
    """The critic's history (recommended) starts with the first revision, whose previous round
    is the draft it revised, not the last draft."""
    script.generator.extend([answer(p) for p in DRAFTS])
    script.critic.extend([critique(70), critique(40), critique(50), critique(75)])
    result = recommended(server, tmp_path / "run", "--drafts", "3", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    critics = requests_of(server, critic=True)
    counts = [len(image_parts(r["messages"][-1])) for r in critics]
    assert counts[0] == counts[1] == counts[2] and counts[3] > counts[2]
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert [c.history is not None for c in record.critiques] == [False, False, False, True]
    assert record.critiques[3].history.previous_index == 0


def test_a_satisfied_critic_does_not_stop_the_drafts(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    script.generator.extend([answer(p) for p in DRAFTS[:2]])
    satisfied = json.dumps({"match_score": 90, "differences": [], "suggestions": []})
    script.critic.extend([satisfied, satisfied])
    result = recommended(server, tmp_path / "run", "--drafts", "2", "--rounds", "2")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert len(record.programs) == 2  # both drafts, then stopped: nothing left to change
    assert record.stop_reason == "the critic asked for no changes to P1"


def test_drafts_with_no_revision_rounds_are_critiqued_and_selected(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    script.generator.extend([answer(p) for p in DRAFTS])
    script.critic.extend([json.dumps({"match_score": s}) for s in (40, 30, 65)])
    result = recommended(server, tmp_path / "run", "--drafts", "3", "--rounds", "0")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert len(record.programs) == 3 and len(record.critiques) == 3
    assert record.selection is not None and record.selection.index == 2
    assert record.stop_reason == "all drafts written"


def test_one_draft_is_the_default_and_the_library_writes_one(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    assert AuthorConfig().drafts == 1
    assert AuthorConfig.model_validate(preset_values("paper")).drafts == 1
    result = recommended(
        server, tmp_path / "run", "--drafts", "3", "--rounds", "0", "--start", "library"
    )
    assert result.exit_code == 0, result.stderr
    assert not [r for r in server.requests if not is_critic(r)]
    assert len(validate_record_file(tmp_path / "run" / "record.json").programs) == 1


def test_out_of_range_drafts_are_refused(server: ChatServer, tmp_path: Path) -> None:
    result = recommended(server, tmp_path / "run", "--drafts", "9")
    assert result.exit_code != 0 and "--drafts" in result.output


def test_recommended_writes_three_drafts() -> None:
    assert AuthorConfig.model_validate(preset_values("recommended")).drafts == 3


def test_a_satisfied_critique_of_the_best_draft_stops_the_loop(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    """After the drafts, the best draft's critique decides: it asked for nothing, so there is
    nothing to revise (the last draft's own suggestions are not the best's)."""
    script.generator.extend([answer(p) for p in DRAFTS])
    satisfied = json.dumps({"match_score": 90, "differences": [], "suggestions": []})
    script.critic.extend([satisfied, critique(40), critique(50)])
    result = recommended(server, tmp_path / "run", "--drafts", "3", "--rounds", "2")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert len(record.programs) == 3
    assert record.stop_reason == "the critic asked for no changes to P0"


def test_without_revise_from_best_the_revision_still_starts_from_the_best_draft(
    script: Script, server: ChatServer, tmp_path: Path
) -> None:
    """The paper's loop continues from the last program; after drafts it takes the best one
    all the same, and the revision turn shows it."""
    script.generator.extend([answer(p) for p in DRAFTS])
    script.critic.extend([critique(90), critique(40), critique(30), critique(60)])
    args = ["--settings", "paper", "--drafts", "3", "--rounds", "1"]
    result = generate(server, tmp_path / "run", *args)
    assert result.exit_code == 0, result.stderr
    revision = text_of(requests_of(server, critic=False)[3]["messages"][-1])
    assert "Continuing from draft 1 (score 90/100), the best so far" in revision
    assert f"<material>\n{DRAFTS[0]}\n</material>" in revision
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.stop_reason == "all 1 revision rounds used"
