"""`--start library`: the material library writes P0 and the model critiques and revises it;
plus the offline CLI paths (`--explain`, `--pick`, seed search with a scorer, byte-identical
output), the `start` setting itself and records written before the library (``"builtin"``).

Runs against the scripted Chat Completions server on 127.0.0.1 (see chat_server.py). The
expected P0 is the canonical form of what :func:`matloom.library.author` returns for the same
prompt and seed.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner, Result
from pydantic import ValidationError

import matloom
from author.chat_server import ChatServer, Fault
from author.conftest import FAST_FLAGS, GENERATOR_MARK, is_critic, text_of
from matloom.author.config import AuthorConfig
from matloom.author.prompts.revision import request_message
from matloom.author.records import validate_record_file
from matloom.cli.main import cli
from matloom.library import author

PROMPT = "weathered red brick wall"


def library_p0(prompt: str, seed: int = 0, pick: int | None = None) -> str:
    """The canonical text of the library's program (its header comments dropped)."""
    return matloom.format(author(prompt, seed=seed, pick=pick).program)


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


# ------------------------------------------------------------------ --start library, with a model


def test_start_library_critiques_the_library_program_first(
    server: ChatServer, tmp_path: Path
) -> None:
    result = model_run(server, tmp_path / "run", "--start", "library", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    expected_p0 = library_p0(PROMPT)

    # No generation request: the very first request is the critique of the offline P0.
    assert is_critic(server.requests[0])
    assert expected_p0 in text_of(server.requests[0]["messages"][1])

    # P0 is the library's program, recorded with its source, header comments and explanation.
    p0 = record.programs[0]
    assert p0.text == expected_p0 and p0.source == "library"
    assert p0.authored == author(PROMPT, seed=0).program
    assert record.library_explanation == author(PROMPT, seed=0).explanation
    assert record.author == "llm" and record.settings.start == "library"

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
    result = model_run(server, tmp_path / "run", "--start", "library", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    (revision,) = [r for r in server.requests if not is_critic(r)]
    system, request, answer, critique_turn = revision["messages"]
    assert system["role"] == "system" and GENERATOR_MARK in text_of(system)
    assert request["role"] == "user" and text_of(request) == request_message(PROMPT)
    assert answer["role"] == "assistant"
    assert text_of(answer) == _material_block(library_p0(PROMPT))
    assert critique_turn["role"] == "user" and "## Score\n" in text_of(critique_turn)


def test_start_library_uses_the_run_seed_and_pick(server: ChatServer, tmp_path: Path) -> None:
    args = ("--start", "library", "--rounds", "0", "--seed", "7", "--pick", "2")
    assert model_run(server, tmp_path / "run", *args).exit_code == 0
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.programs[0].text == library_p0(PROMPT, seed=7, pick=2)
    assert record.programs[0].text != library_p0(PROMPT, seed=0, pick=2)
    assert record.programs[0].text != library_p0(PROMPT, seed=7)
    assert record.settings.pick == 2
    assert len(record.programs) == 1 and server.requests == []  # rounds 0: no model call at all


def test_start_builtin_is_the_old_name_of_library(server: ChatServer, tmp_path: Path) -> None:
    result = model_run(server, tmp_path / "run", "--start", "builtin", "--rounds", "0")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.start == "library" and record.programs[0].source == "library"
    assert record.programs[0].text == library_p0(PROMPT)


def test_pick_without_start_library_is_ignored_with_a_note(
    server: ChatServer, tmp_path: Path
) -> None:
    result = model_run(server, tmp_path / "run", "--rounds", "0", "--pick", "2")
    assert result.exit_code == 0, result.stderr
    assert "--pick applies only with --start library" in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.programs[0].source == "generator"


def test_start_model_is_the_default(server: ChatServer, tmp_path: Path) -> None:
    result = model_run(server, tmp_path / "run", "--rounds", "0")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.start == "model" and record.programs[0].source == "generator"
    assert len(server.requests) == 1 and not is_critic(server.requests[0])


def test_resume_after_a_failed_revision_keeps_the_library_p0(
    server: ChatServer, tmp_path: Path
) -> None:
    # Request 1 (critique of P0) is answered; the revision fails on every attempt (3 x 500).
    server.inject(Fault(), Fault(status=500), Fault(status=500), Fault(status=500))
    run = tmp_path / "run"
    first = model_run(server, run, "--start", "library", "--rounds", "1")
    assert first.exit_code == 1 and "--resume" in first.stderr
    before = validate_record_file(run / "record.json")
    assert before.status == "failed"
    assert len(before.programs) == 1 and len(before.critiques) == 1
    seen = len(server.requests)

    resumed = run_cli("generate", "--resume", "-o", str(run), "--base-url", server.base_url)
    assert resumed.exit_code == 0, resumed.stderr
    after = validate_record_file(run / "record.json")
    new = server.requests[seen:]
    # Neither P0 nor its critique is redone: one revision, then the critique of P1.
    assert [is_critic(r) for r in new] == [False, True]
    assert text_of(new[0]["messages"][2]) == _material_block(before.programs[0].text)
    assert after.programs[0] == before.programs[0]
    assert after.critiques[0] == before.critiques[0]
    assert len(after.programs) == 2 and after.status == "finished"
    assert after.settings.start == "library" and len(after.sessions) == 2


# ------------------------------------------------------------------ offline CLI


def test_explain_offline_prints_the_explanation_on_stderr_and_only_the_program_on_stdout(
    tmp_path: Path,
) -> None:
    result = offline_run(tmp_path / "run", "--explain", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    expected = author("red brick wall", seed=0)
    assert result.stdout == library_p0("red brick wall") + "\n"
    assert expected.explanation in result.stderr
    for needle in (
        "candidates:",
        f"*1. {expected.entry} ",
        f"entry: {expected.entry} ",
        "adaptations:",
        "ignored:",
    ):
        assert needle in result.stderr and needle not in result.stdout
    assert "using the material library" in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.library_explanation == expected.explanation
    assert record.author == "library" and record.models.generator == "library"


def test_offline_program_carries_its_physical_size_into_the_export(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "none", prompt="cobblestone")
    assert result.exit_code == 0, result.stderr
    expected = author("cobblestone")
    program = matloom.parse((tmp_path / "run" / "material.mat").read_text(encoding="utf-8"))
    assert program.view.unit_m == expected.unit_m and program.tileable == expected.tileable
    manifest = json.loads((tmp_path / "run" / "material.json").read_text(encoding="utf-8"))
    assert manifest["physical_size"]["unit_m"] == expected.unit_m
    assert manifest["tileable"] == expected.tileable


def test_pick_takes_the_nth_candidate_offline(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "none", "--pick", "2", "--explain")
    assert result.exit_code == 0, result.stderr
    second = author("red brick wall", pick=2)
    assert second.rank == 2 and second.entry != author("red brick wall").entry
    assert result.stdout == library_p0("red brick wall", pick=2) + "\n"
    assert f"*2. {second.entry}" in result.stderr


def test_pick_past_the_candidates_is_a_one_line_error(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "none", "--pick", "999")
    assert result.exit_code == 1
    errors = [line for line in result.stderr.splitlines() if line.startswith("Error")]
    assert errors == [errors[0]] and "--pick 999: only" in errors[0], result.stderr
    assert "candidates matched" in errors[0] and "Traceback" not in result.stderr
    assert not (tmp_path / "run" / "record.json").exists()  # refused before anything was written
    zero = offline_run(tmp_path / "run0", "--scorer", "none", "--pick", "0")
    assert zero.exit_code == 2 and "--pick" in zero.stderr


def test_offline_generate_is_byte_identical_for_the_same_prompt_and_seed(tmp_path: Path) -> None:
    def files(folder: Path) -> dict[str, bytes]:
        return {
            p.name: p.read_bytes()
            for p in sorted(folder.iterdir())
            if p.is_file() and p.name != "record.json" and not p.name.startswith(".")
        }

    outputs = []
    for name in ("a", "b"):
        result = offline_run(tmp_path / name, "--seed", "3", prompt="mossy cobblestone")
        assert result.exit_code == 0, result.stderr
        outputs.append((result.stdout, files(tmp_path / name)))
    assert outputs[0] == outputs[1]
    assert {"material.mat", "material.json", "preview.png", "basecolor.png"} <= set(outputs[0][1])
    other = offline_run(tmp_path / "c", "--seed", "4", prompt="mossy cobblestone")
    assert other.exit_code == 0 and other.stdout != outputs[0][0]


def test_offline_seed_search_with_a_scorer_is_logged(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "test-colour", "--variants", "4")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.author == "library" and record.models.scorer == "test-colour"
    search = record.seed_search
    assert search.done and search.skipped is None and search.candidates == [0]
    (sweep,) = search.sweeps
    assert sweep.program_index == 0 and sweep.variants == 4 and len(sweep.scores) == 5
    assert sweep.best_score == max(sweep.scores) and sweep.best_score >= sweep.original_score
    assert record.final.program == sweep.best_program and record.final.score == sweep.best_score
    assert result.stdout.strip() == record.final.program
    assert "seed search skipped" not in result.stderr


@pytest.mark.parametrize("start", ["library", "builtin", "model"])
def test_start_without_a_model_says_it_is_irrelevant(tmp_path: Path, start: str) -> None:
    result = offline_run(tmp_path / "run", "--start", start, "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    assert "--start is irrelevant without a model" in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.author == "library" and record.programs[0].source == "library"


def test_no_start_note_when_the_flag_is_not_given(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    assert "--start" not in result.stderr


# ------------------------------------------------------------------ the setting itself


def test_start_setting_validation() -> None:
    assert AuthorConfig().start == "model"
    assert AuthorConfig(start="library").start == "library"
    assert AuthorConfig(start="builtin").start == "library"  # the old name
    with pytest.raises(ValidationError):
        AuthorConfig(start="llm")
    assert AuthorConfig().pick is None and AuthorConfig(pick=3).pick == 3
    with pytest.raises(ValidationError):
        AuthorConfig(pick=0)


def test_records_written_before_the_library_still_load(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    path = tmp_path / "run" / "record.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    data["author"] = "builtin"
    data["programs"][0]["source"] = "builtin"
    data["settings"]["start"] = "builtin"
    data["builtin_explanation"] = data.pop("library_explanation")
    path.write_text(json.dumps(data), encoding="utf-8")
    old = validate_record_file(path)
    assert old.author == "builtin" and old.offline and old.programs[0].source == "builtin"
    assert old.settings.start == "library"
    assert old.library_explanation == author("red brick wall").explanation
    saved = json.loads(old.model_dump_json())  # saved again under the new names
    assert saved["library_explanation"] == old.library_explanation
    assert "builtin_explanation" not in saved and saved["settings"]["start"] == "library"


def test_cli_rejects_an_unknown_start(tmp_path: Path) -> None:
    result = offline_run(tmp_path / "run", "--start", "llm")
    assert result.exit_code == 2 and "'llm' is not one of" in result.stderr
