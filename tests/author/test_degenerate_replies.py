"""Degenerate model replies: program extraction stays linear, the reply-size cap refuses huge
replies like any bad answer, and no critic answer can make the critique parser fail the run."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from author.chat_server import ChatServer
from author.conftest import Script, example_program, is_critic, text_of
from author.test_generate_e2e import generate
from matloom.author.records import validate_record_file
from matloom.author.stages.critique import CritiqueParseError, parse_critique
from matloom.author.stages.jsonfix import JsonRepairError, repair_json
from matloom.lang.extract import extract_program

PROGRAM = example_program(0)
#: Far above what linear extraction needs (milliseconds); the quadratic scan took 20+ s at
#: 160 KB and never finished at 10 MB.
GENEROUS_S = 10.0


def requests_of(server: ChatServer, critic: bool) -> list[dict]:
    return [r for r in server.requests if is_critic(r) == critic]


@pytest.mark.parametrize("size", [160_000, 10_000_000])
@pytest.mark.parametrize(
    ("unit", "tail", "found"),
    [
        ("<material>", "", None),  # opening tags that never close
        ("<material>", f"\n{PROGRAM}\n", PROGRAM),  # ... then a bare program
        ("```\n", "", None),  # empty fenced blocks
        ("```x", "", None),  # fence marks that never open a block
        ("\n", "", None),  # blank lines
        ("\n", f"{PROGRAM}\n", PROGRAM),  # blank lines, then a bare program
        (" View ", "", None),  # keywords never followed by "("
    ],
)
def test_degenerate_replies_extract_in_linear_time(
    size: int, unit: str, tail: str, found: str | None
) -> None:
    reply = unit * (size // len(unit)) + tail
    start = time.perf_counter()
    program, _ = extract_program(reply)
    assert time.perf_counter() - start < GENEROUS_S
    assert program == found


def test_extraction_order_is_unchanged() -> None:
    tagged = f"Thinking.\n<MATERIAL>\n```mat\n{PROGRAM}\n```\n</material> trailing"
    assert extract_program(tagged) == (PROGRAM, "Thinking.")
    fenced = f"Here:\n```\nnot a program\n```\nand\n```dsl\n{PROGRAM}\n```"
    assert extract_program(fenced) == (PROGRAM, "Here:\n```\nnot a program\n```\nand")
    bare = f"Intro line\n\n   \n  {PROGRAM}"
    assert extract_program(bare) == (PROGRAM, "Intro line")
    assert extract_program("no program here") == (None, "no program here")


def test_ten_megabyte_reply_is_refused_and_the_model_asked_again(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.generator.append("<material>" * 1_000_000)  # 10 MB, never closed
    result = generate(server, tmp_path / "run", "--rounds", "0", "--variants", "0")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    refused, accepted = record.turns[0].attempts
    assert refused.outcome == "too_large" and accepted.outcome == "accepted"
    assert "10,000,000 characters long, over the limit of 1,000,000" in refused.error
    assert refused.reply.startswith("<material>") and len(refused.reply) < 5_000
    retry = requests_of(server, critic=False)[1]["messages"]
    assert len(text_of(retry[-2])) < 5_000  # the clipped reply, not 10 MB sent back
    assert "over the limit of 1,000,000" in text_of(retry[-1])
    assert (tmp_path / "run" / "record.json").stat().st_size < 1_000_000


def test_reply_size_cap_is_configurable(server: ChatServer, script: Script, tmp_path: Path) -> None:
    degenerate = "<material>" * 16_000  # 160 KB
    script.generator.append(degenerate)
    result = generate(
        server, tmp_path / "a", "--rounds", "0", "--variants", "0", "--max-reply-chars", "100000"
    )
    assert result.exit_code == 0, result.stderr
    attempts = validate_record_file(tmp_path / "a" / "record.json").turns[0].attempts
    assert attempts[0].outcome == "too_large" and "100,000" in attempts[0].error
    # Under the default cap the same reply is read (quickly) and holds no program.
    script.generator.append(degenerate)
    result = generate(server, tmp_path / "b", "--rounds", "0", "--variants", "0")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "b" / "record.json")
    assert record.settings.max_reply_chars == 1_000_000
    assert record.turns[0].attempts[0].outcome == "no_program"


def test_unparseable_critic_answers_fail_the_critique_not_the_run(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    # P0's critic answers: all four attempts (critic_retries = 3) unusable.
    script.critic.extend(["{" * 3000, "{" * 1_000_000, "[" * 5000, "{" * 2_000_000])
    result = generate(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.status == "finished" and record.final is not None
    (critique,) = record.critiques
    assert not critique.ok and critique.attempts == 4
    assert critique.error.startswith("unparseable critique after 4 attempt(s)")
    assert "over the limit of 1,000,000" in critique.error  # the last, 2 MB, answer
    assert record.stop_reason.startswith("critique of P0 failed")
    assert [len(r) for r in critique.replies[:3]] == [3000, 1_000_000, 5000]
    assert len(critique.replies[3]) < 5_000  # over the cap: stored clipped
    retries = requests_of(server, critic=True)[1:]
    assert all(len(text_of(r["messages"][-2])) < 10_000 for r in retries)  # echoes clipped
    assert "65,536" in text_of(retries[1]["messages"][-1])  # 1 MB: too long to repair
    assert "no JSON object" in text_of(retries[2]["messages"][-1])


def test_critic_retry_after_a_malformed_answer_recovers(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    good = json.dumps({"match_score": 64, "differences": ["d"], "suggestions": ["s"]})
    script.critic.extend(["{" * 3000, good])
    result = generate(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    first = validate_record_file(tmp_path / "run" / "record.json").critiques[0]
    assert first.ok and (first.match_score, first.attempts) == (64, 2)
    assert "could not be parsed" in first.messages[-1].text


ADVERSARIAL = [
    "{" * 3000,
    "{" * 1_000_000,
    '{"' * 30_000,
    "{" + "]a{" * 20_000,
    "{" + "{,1}" * 15_000,
    "{" + '"a"1' * 15_000,
    '{"match_score": 50, "differences": ' + "[" * 5000,
    '{"a":' * 1000,
    "[" * 3000 + "{",
]


@pytest.mark.parametrize("answer", ADVERSARIAL, ids=lambda a: f"{a[:8]!r}x{len(a)}")
def test_adversarial_critic_answers_raise_critique_parse_error(answer: str) -> None:
    start = time.perf_counter()
    with pytest.raises(CritiqueParseError):
        parse_critique(answer)
    assert time.perf_counter() - start < GENEROUS_S


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ('{"a": 1, "b": [1, 2,],}', {"a": 1, "b": [1, 2]}),
        ("{'a': 'it\\'s', 'b': True, 'c': None}", {"a": "it's", "b": True, "c": None}),
        ('{a: "x" "y", b: 2}', {"a": "x", "y": None, "b": 2}),
        ('{"a": ["x", "y"}', {"a": ["x", "y"]}),
        ('{"a": "cut off', {"a": "cut off"}),
        ('{"a": {"b": [1, {"c": 2', {"a": {"b": [1, {"c": 2}]}}),
        ('{"a": 1 /100, "b": "\\u00e9\\n"} ```', {"a": 1, "100": None, "b": "é\n"}),
        ('{"a": }', {"a": None}),
    ],
)
def test_repair_json_reads_near_json(text: str, expected: object) -> None:
    assert repair_json(text) == expected


def test_repair_json_limits() -> None:
    with pytest.raises(JsonRepairError, match="over the 100"):
        repair_json("{" + " " * 200 + "}", max_chars=100)
    with pytest.raises(JsonRepairError, match="nested deeper than 3"):
        repair_json('{"a": [[[1]]]}', max_depth=3)
    assert repair_json('{"a": [[1]]}', max_depth=3) == {"a": [[1]]}
    with pytest.raises(JsonRepairError, match="no JSON value"):
        repair_json(":,}]")
