"""`--start builtin`: the offline author writes P0 and the model critiques and revises it; plus
the offline CLI paths (`--explain`, seed search with a scorer) and the `start` setting itself.

Runs against the scripted Chat Completions server on 127.0.0.1 (see chat_server.py). The
expected P0 is what :func:`matloom.author.builtin.author` returns for the same prompt and seed.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner, Result
from pydantic import ValidationError

import matloom
from author.chat_server import ChatServer, Fault
from author.conftest import FAST_FLAGS, GENERATOR_MARK, is_critic, text_of
from matloom.author.builtin import author
from matloom.author.config import AuthorConfig
from matloom.author.prompts.revision import request_message
from matloom.author.records import validate_record_file
from matloom.cli.main import cli

PROMPT = "weathered red brick wall"


def run_cli(*args: str) -> Result:
    return CliRunner().invoke(cli, list(args))


def model_run(server: ChatServer, out: Path, *extra: str, prompt: str = PROMPT) -> Result:
    """`matloom generate` with the scripted model, a test scorer and small render sizes."""
    return run_cli(
        "generate",
        prompt,
        "-o",
        str(out),
        "--model",
        "test-vision-model",
        "--base-url",
        server.base_url,
        "--retry-backoff",
        "0.01",
        "--max-retries",
        "2",
        "--timeout",
        "20",
        "--scorer",
        "test-colour",
        "--variants",
        "4",
        *FAST_FLAGS,
        *extra,
    )


def offline_run(out: Path, *extra: str, prompt: str = "red brick wall") -> Result:
    return run_cli("generate", prompt, "-o", str(out), *FAST_FLAGS, *extra)


def _material_block(program: str) -> str:
    return f"<material>\n{program.strip()}\n</material>"


# ------------------------------------------------------------------ --start builtin, with a model


def test_start_builtin_critiques_the_offline_program_first(
    server: ChatServer, tmp_path: Path
) -> None:
    result = model_run(server, tmp_path / "run", "--start", "builtin", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    expected_p0 = author(PROMPT, seed=0).program

    # No generation request: the very first request is the critique of the offline P0.
    assert is_critic(server.requests[0])
    assert expected_p0 in text_of(server.requests[0]["messages"][1])

    # P0 is the offline author's program, recorded with its source and explanation.
    p0 = record.programs[0]
    assert p0.text == expected_p0 and p0.source == "builtin"
    assert record.builtin_explanation == author(PROMPT, seed=0).explanation
    assert record.author == "llm" and record.settings.start == "builtin"

    # --rounds 1: P0 and one revision P1, each critiqued once.
    assert len(record.programs) == 2 and len(record.critiques) == 2
    assert record.programs[1].source == "generator"
    assert [is_critic(r) for r in server.requests] == [True, False, True]
    assert [t.program_index for t in record.turns] == [1]  # no model turn for P0

    # Stage III ran as usual over the trajectory.
    assert record.selection is not None and len(record.selection.scores) == 2
    assert record.seed_search.done and record.seed_search.sweeps
    assert record.status == "finished" and (tmp_path / "run" / "material.mat").exists()


def test_revision_turn_shows_p0_as_the_models_previous_answer(
    server: ChatServer, tmp_path: Path
) -> None:
    result = model_run(server, tmp_path / "run", "--start", "builtin", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    (revision,) = [r for r in server.requests if not is_critic(r)]
    system, request, answer, critique_turn = revision["messages"]
    assert system["role"] == "system" and GENERATOR_MARK in text_of(system)
    assert request["role"] == "user" and text_of(request) == request_message(PROMPT)
    assert answer["role"] == "assistant"
    assert text_of(answer) == _material_block(author(PROMPT, seed=0).program)
    assert critique_turn["role"] == "user" and "## Score\n" in text_of(critique_turn)


def test_start_builtin_uses_the_run_seed(server: ChatServer, tmp_path: Path) -> None:
    args = ("--start", "builtin", "--rounds", "0", "--seed", "7")
    assert model_run(server, tmp_path / "run", *args).exit_code == 0
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.programs[0].text == author(PROMPT, seed=7).program
    assert record.programs[0].text != author(PROMPT, seed=0).program
    assert len(record.programs) == 1 and server.requests == []  # rounds 0: no model call at all


def test_start_model_is_the_default(server: ChatServer, tmp_path: Path) -> None:
    result = model_run(server, tmp_path / "run", "--rounds", "0")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.start == "model" and record.programs[0].source == "generator"
    assert len(server.requests) == 1 and not is_critic(server.requests[0])


def test_resume_after_a_failed_revision_keeps_the_builtin_p0(
    server: ChatServer, tmp_path: Path
) -> None:
    # Request 1 (critique of P0) is answered; the revision fails on every attempt (3 x 500).
    server.inject(Fault(), Fault(status=500), Fault(status=500), Fault(status=500))
    run = tmp_path / "run"
    first = model_run(server, run, "--start", "builtin", "--rounds", "1")
    assert first.exit_code == 1 and "--resume" in first.stderr
    before = validate_record_file(run / "record.json")
    assert before.status == "failed"
    assert len(before.programs) == 1 and len(before.critiques) == 1
    seen = len(server.requests)

    resumed = run_cli("generate", "--resume", "-o", str(run))
    assert resumed.exit_code == 0, resumed.stderr
    after = validate_record_file(run / "record.json")
    new = server.requests[seen:]
    # Neither P0 nor its critique is redone: one revision, then the critique of P1.
    assert [is_critic(r) for r in new] == [False, True]
    assert text_of(new[0]["messages"][2]) == _material_block(before.programs[0].text)
    assert after.programs[0] == before.programs[0]
    assert after.critiques[0] == before.critiques[0]
    assert len(after.programs) == 2 and after.status == "finished"
    assert after.settings.start == "builtin" and len(after.sessions) == 2


# ------------------------------------------------------------------ offline CLI


def test_explain_offline_prints_the_recipe_on_stderr_and_only_the_program_on_stdout(
    tmp_path: Path,
) -> None:
    result = offline_run(tmp_path / "run", "--explain", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    expected = author("red brick wall", seed=0)
    assert result.stdout == expected.program + "\n"
    assert expected.explanation in result.stderr
    assert "recipe:" in result.stderr and "recipe:" not in result.stdout
    assert matloom.parse(result.stdout)


def test_offline_seed_search_with_a_scorer_is_logged(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "test-colour", "--variants", "4")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.author == "builtin" and record.models.scorer == "test-colour"
    search = record.seed_search
    assert search.done and search.skipped is None and search.candidates == [0]
    (sweep,) = search.sweeps
    assert sweep.program_index == 0 and sweep.variants == 4 and len(sweep.scores) == 5
    assert sweep.best_score == max(sweep.scores) and sweep.best_score >= sweep.original_score
    assert record.final.program == sweep.best_program and record.final.score == sweep.best_score
    assert result.stdout.strip() == record.final.program
    assert "seed search skipped" not in result.stderr


@pytest.mark.parametrize("start", ["builtin", "model"])
def test_start_without_a_model_says_it_is_irrelevant(tmp_path: Path, start: str) -> None:
    result = offline_run(tmp_path / "run", "--start", start, "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    assert "--start is irrelevant without a model" in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.author == "builtin" and record.programs[0].source == "builtin"


def test_no_start_note_when_the_flag_is_not_given(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    assert "--start" not in result.stderr


# ------------------------------------------------------------------ the setting itself


def test_start_setting_validation() -> None:
    assert AuthorConfig().start == "model"
    assert AuthorConfig(start="builtin").start == "builtin"
    with pytest.raises(ValidationError):
        AuthorConfig(start="llm")


def test_cli_rejects_an_unknown_start(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--start", "llm")
    assert result.exit_code == 2 and "'llm' is not one of" in result.stderr
