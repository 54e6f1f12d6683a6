"""Stopping once the critic asks for no changes (--stop-when-satisfied, on in the recommended
preset), recording why the loop stopped, and the critic quoting the generator's own text."""

from __future__ import annotations

import json
from pathlib import Path

from author.chat_server import ChatServer
from author.conftest import Script, text_of
from author.test_generate_e2e import critic_requests, generate
from matloom.author.records import validate_record_file
from matloom.author.stages.generate import extract_answer

SATISFIED = json.dumps({"match_score": 90, "differences": [], "suggestions": []})
UNHAPPY = json.dumps({"match_score": 50, "differences": ["too dark"], "suggestions": ["lighter"]})


def test_stops_when_the_critic_asks_for_no_changes(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend([UNHAPPY, SATISFIED, UNHAPPY])
    result = generate(
        server, tmp_path / "run", "--rounds", "3", "--scorer", "none", "--stop-when-satisfied"
    )
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert len(record.programs) == 2 and len(record.critiques) == 2
    assert record.stop_reason == "the critic asked for no changes to P1"


def test_paper_runs_every_round_and_says_so(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend([SATISFIED, SATISFIED, SATISFIED])
    result = generate(server, tmp_path / "run", "--rounds", "2", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert len(record.programs) == 3
    assert record.stop_reason == "all 2 revision rounds used"


def test_critic_sees_the_generators_own_text(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend([SATISFIED, SATISFIED])
    result = generate(server, tmp_path / "run", "--rounds", "1", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    first = record.programs[0]
    own = extract_answer(first.authored)[0]
    assert own is not None and own.strip() != first.text.strip()  # seeds were added
    shown = "\n".join(text_of(m) for m in critic_requests(server)[0]["messages"])
    assert own.strip() in shown
