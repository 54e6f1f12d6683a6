"""`matloom generate` end to end against the scripted Chat Completions server on 127.0.0.1."""

from __future__ import annotations

import json
import re
import socket
from pathlib import Path

import numpy as np
from click.testing import CliRunner, Result

import matloom
from author.chat_server import ChatServer, Fault
from author.conftest import FAST_FLAGS, Script, example_program, image_parts, is_critic, text_of
from matloom.author.records import validate_record_file
from matloom.cli.main import cli

BROKEN = """I think this works.
<material>
View(0, 0, 2, 2)
Material(
  Layer(1)
    .basecolor(200, 120, 80)
    .roughnes(0.5)
)
</material>"""


def generate(
    server: ChatServer | None,
    out: Path,
    *extra: str,
    prompt: str = "red brick wall",
    model: str = "test-vision-model",
) -> Result:
    flags = ["--model", model, "--retry-backoff", "0.01", "--max-retries", "2", "--timeout", "20"]
    if server is not None:
        flags += ["--base-url", server.base_url]
    args = [
        "generate",
        prompt,
        "-o",
        str(out),
        *flags,
        "--scorer",
        "test-colour",
        "--variants",
        "8",
        *FAST_FLAGS,
        *extra,
    ]
    return CliRunner().invoke(cli, args)


def generator_requests(server: ChatServer) -> list[dict]:
    return [r for r in server.requests if not is_critic(r)]


def critic_requests(server: ChatServer) -> list[dict]:
    return [r for r in server.requests if is_critic(r)]


def test_full_run_with_repair_critique_selection_and_seed_search(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.generator.append(BROKEN)
    result = generate(server, tmp_path / "run", "--json")
    assert result.exit_code == 0, result.stderr
    summary = json.loads(result.stdout)  # stdout carries only the result

    # Stage I repair: the second generator request carries the structured diagnostic.
    repair = text_of(generator_requests(server)[1]["messages"][-1])
    assert re.search(r"program:5:6: error E\d+: unknown layer channel", repair)
    assert "^^^" in repair and "hint: did you mean `roughness`?" in repair
    # Accepted programs are canonicalised with explicit seeds for rendering and the record; the
    # conversation keeps the model's own reply, and the revision turn lists the added seeds.
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert all("seed=" in p.text for p in record.programs)
    later = generator_requests(server)[2]["messages"]
    shown = [text_of(m) for m in later if m["role"] == "assistant"][-1]
    assert shown == record.turns[0].attempts[1].reply == record.programs[0].authored
    assert record.programs[0].text not in shown and record.programs[0].added_seeds
    seeds = text_of(later[-1]).split("## Seeds\n", 1)[1]
    assert all(note in seeds for note in record.programs[0].added_seeds)

    # Stage II: five rounds -> P0..P5, one critique each, images for a multimodal critic.
    assert len(record.programs) == 6 and len(record.critiques) == 6
    assert len(critic_requests(server)) == 6
    for request in critic_requests(server):
        assert len(request["messages"]) == 2  # stateless: system + one user turn
        (part,) = image_parts(request["messages"][1])
        assert part["image_url"]["url"].startswith("data:image/jpeg;base64,")
    revision = text_of(generator_requests(server)[2]["messages"][-1])
    for heading in ("## Score", "## What differs", "## What to change", "## Answer"):
        assert heading in revision
    assert "including any seed= values" in revision and "the last one is used" in revision

    # Stage III: selection over the trajectory, sweeps over distinct {0, j, 5}.
    assert record.selection.method == "scorer" and len(record.selection.scores) == 6
    j = record.selection.index
    assert record.selection.scores[j] == max(record.selection.scores)
    assert record.seed_search.candidates == sorted({0, j, 5})
    for sweep in record.seed_search.sweeps:
        assert sweep.variants == 8 and len(sweep.scores) == 9
        assert sweep.best_score >= sweep.original_score
    assert record.final.score == max(s.best_score for s in record.seed_search.sweeps)

    # Results on disk and in the summary.
    run = tmp_path / "run"
    assert (run / "material.mat").read_text().strip() == record.final.program
    assert matloom.check(record.final.program) == [] or all(
        not d.is_error for d in matloom.check(record.final.program)
    )
    assert (run / "preview.png").exists() and (run / "basecolor.png").exists()
    assert summary["program"] == record.final.program and summary["status"] == "finished"
    d = record.durations
    assert len(d.generation) == 6 and len(d.critique) == 6 and d.select is not None
    assert len(d.seed_search) == len(record.seed_search.candidates) and d.total > 0
    assert record.models.generator == "test-vision-model" and record.models.scorer == "test-colour"
    assert record.turns[0].attempts[0].outcome == "parse_error"
    assert record.turns[0].attempts[1].outcome == "accepted"


def test_text_only_critic_gets_no_image(server: ChatServer, tmp_path: Path) -> None:
    result = generate(server, tmp_path / "run", "--rounds", "2", "--critic-model", "glm-5.2")
    assert result.exit_code == 0, result.stderr
    requests = critic_requests(server)
    assert len(requests) == 3
    for request in requests:
        assert request["model"] == "glm-5.2"
        assert image_parts(request["messages"][1]) == []
        assert "no render is shown" in text_of(request["messages"][0])
        assert "Appearance scalars" in text_of(request["messages"][1])
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert all(c.signals == ["stats", "code"] and c.render is None for c in record.critiques)
    assert record.models.critic == "glm-5.2"


def test_critic_signal_subset(server: ChatServer, tmp_path: Path) -> None:
    result = generate(server, tmp_path / "run", "--rounds", "1", "--critic-signals", "render")
    assert result.exit_code == 0, result.stderr
    for request in critic_requests(server):
        user = request["messages"][1]
        assert len(image_parts(user)) == 1
        assert "<program>" not in text_of(user) and "Appearance scalars" not in text_of(user)


def test_malformed_critic_json_is_repaired_or_retried(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.critic.extend(
        [
            'Here you go:\n```json\n{"match_score": 61, // fine\n "differences": ["a",],'
            ' "suggestions": ["b"]\n```',  # comment, trailing comma, unclosed: repairable
            "I refuse to answer in JSON.",  # no object at all: retried
            '{"match_score": 70, "differences": ["c"], "suggestions": ["d"]}',
        ]
    )
    result = generate(server, tmp_path / "run", "--rounds", "1")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    first, second = record.critiques
    assert (first.match_score, first.differences, first.attempts) == (61, ["a"], 1)
    assert (second.match_score, second.attempts) == (70, 2)
    assert "could not be parsed" in second.messages[-1].text


def test_selection_falls_back_to_critic_score_without_scorer(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    scores = [40, 75, 75]
    script.critic.extend(
        json.dumps({"match_score": s, "differences": [], "suggestions": []}) for s in scores
    )
    result = generate(server, tmp_path / "run", "--rounds", "2", "--scorer", "none")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.selection.method == "critic"
    assert record.selection.index == 1  # tie between P1 and P2 -> the earliest
    assert record.seed_search.skipped and record.final.program_index == 1
    assert "seed search skipped" in result.stderr


def test_never_parseable_model_fails_cleanly_after_four_attempts(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    script.default_generator = lambda body: "Sorry, I can only describe it in words."
    result = generate(server, tmp_path / "run")
    assert result.exit_code == 1
    assert "no parseable program after 4 attempt(s)" in result.stderr
    assert "Traceback" not in result.stderr and result.stdout == ""
    assert len(generator_requests(server)) == 4
    assert "could not find a program" in text_of(generator_requests(server)[1]["messages"][-1])
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.status == "failed" and len(record.turns[0].attempts) == 4
    assert {a.outcome for a in record.turns[0].attempts} == {"no_program"}


def test_connection_refused_fails_cleanly_and_keeps_the_record(tmp_path: Path) -> None:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    result = CliRunner().invoke(
        cli,
        [
            "generate",
            "moss",
            "-o",
            str(tmp_path / "run"),
            "--model",
            "m",
            "--base-url",
            f"http://127.0.0.1:{port}/v1",
            "--max-retries",
            "1",
            "--retry-backoff",
            "0.01",
            *FAST_FLAGS,
        ],
    )
    assert result.exit_code == 1
    assert "cannot connect" in result.stderr and "Traceback" not in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.status == "failed" and "cannot connect" in record.error


def test_timeouts_and_429_inside_a_run(server: ChatServer, tmp_path: Path) -> None:
    server.inject(Fault(status=429), Fault(delay=2.0))
    result = generate(server, tmp_path / "run", "--rounds", "1", "--timeout", "0.5")
    assert result.exit_code == 0, result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.status == "finished" and len(record.programs) == 2


def test_existing_run_folder_needs_resume(server: ChatServer, tmp_path: Path) -> None:
    assert generate(server, tmp_path / "run", "--rounds", "0").exit_code == 0
    again = generate(server, tmp_path / "run", "--rounds", "0")
    assert again.exit_code == 1 and "--resume" in again.stderr


def test_offline_author_without_a_model(tmp_path: Path) -> None:
    result = CliRunner().invoke(
        cli,
        [
            "generate",
            "green marble",
            "-o",
            str(tmp_path / "run"),
            "--scorer",
            "test-colour",
            "--variants",
            "4",
            *FAST_FLAGS,
        ],
    )
    assert result.exit_code == 0, result.stderr
    assert "using the material library" in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.author == "library" and record.programs[0].source == "library"
    assert matloom.parse(result.stdout)  # stdout is just the program
    assert len(record.seed_search.sweeps) == 1


def test_seedless_program_gets_explicit_seeds_from_the_run_seed(
    server: ChatServer, script: Script, tmp_path: Path
) -> None:
    program = example_program(2)
    assert "seed=" not in program
    script.default_generator = lambda body: f"<material>{program}</material>"
    runs = []
    for name, seed in (("a", "1"), ("b", "1"), ("c", "2")):
        result = generate(
            server, tmp_path / name, "--rounds", "0", "--seed", seed, "--variants", "0"
        )
        assert result.exit_code == 0, result.stderr
        runs.append(validate_record_file(tmp_path / name / "record.json").programs[0].text)
    assert runs[0] == runs[1] != runs[2]
    assert np.array_equal(matloom.preview(runs[0], 32), matloom.preview(runs[1], 32))
