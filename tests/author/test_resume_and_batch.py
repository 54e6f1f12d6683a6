"""Interrupted runs resume without redoing finished stages; batches run several prompts at once."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

from click.testing import CliRunner

from author.chat_server import ChatServer, Fault
from author.conftest import FAST_FLAGS, is_critic
from matloom.author.records import validate_record_file
from matloom.cli.main import cli

REPO = Path(__file__).resolve().parents[2]
DEV_PROMPTS = REPO / "tests" / "data" / "prompts-dev.json"


def _cli_process(args: list[str], cwd: Path) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    return subprocess.Popen(
        [sys.executable, "-m", "matloom", *args],
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )


def test_resume_after_kill_mid_run(server: ChatServer, tmp_path: Path) -> None:
    # Requests: gen P0, critic P0, gen P1, critic P1, gen P2 <- hangs; then the process is killed.
    server.inject(Fault(), Fault(), Fault(), Fault(), Fault(hang=True))
    run = tmp_path / "run"
    args = [
        "generate",
        "mossy stone",
        "-o",
        str(run),
        "--model",
        "m",
        "--base-url",
        server.base_url,
        "--scorer",
        "test-colour",
        "--variants",
        "4",
        "--rounds",
        "5",
        "--quiet",
        *FAST_FLAGS,
    ]
    proc = _cli_process(args, tmp_path)
    try:
        assert server.state.hung.wait(180), proc.stderr.read().decode() if proc.poll() else ""
        before = validate_record_file(run / "record.json")
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait(30)
    server.release()
    assert before.status == "running"
    assert len(before.programs) == 2 and len(before.critiques) == 2
    assert before.turns[-1].accepted is False  # P2's turn was in flight
    seen = len(server.requests)

    # The run folder is ours: its recorded server may be used (without a new --base-url).
    result = CliRunner().invoke(cli, ["generate", "--resume", "--trust-record", "-o", str(run)])
    assert result.exit_code == 0, result.stderr
    after = validate_record_file(run / "record.json")
    new = server.requests[seen:]
    # Finished stages are not redone: 4 revisions (P2..P5) and 4 critiques (P2..P5) only.
    assert sum(not is_critic(r) for r in new) == 4 and sum(is_critic(r) for r in new) == 4
    assert not is_critic(new[0])  # the interrupted turn is the first thing redone
    assert [p.text for p in after.programs[:2]] == [p.text for p in before.programs]
    assert [c.match_score for c in after.critiques[:2]] == [c.match_score for c in before.critiques]
    assert len(after.programs) == 6 and after.status == "finished" and len(after.sessions) == 2
    assert [t.program_index for t in after.turns] == [0, 1, 2, 3, 4, 5]
    assert after.settings == before.settings  # the resumed run keeps its recorded settings


def test_resume_a_failed_run_with_a_new_base_url(server: ChatServer, tmp_path: Path) -> None:
    run = tmp_path / "run"
    dead = ["--base-url", "http://127.0.0.1:9/v1", "--max-retries", "0"]
    first = CliRunner().invoke(
        cli,
        [
            "generate",
            "oak bark",
            "-o",
            str(run),
            "--model",
            "m",
            "--scorer",
            "test-colour",
            "--variants",
            "2",
            "--rounds",
            "1",
            *dead,
            *FAST_FLAGS,
        ],
    )
    assert first.exit_code == 1 and "--resume" in first.stderr
    resumed = CliRunner().invoke(
        cli, ["generate", "--resume", "-o", str(run), "--base-url", server.base_url]
    )
    assert resumed.exit_code == 0, resumed.stderr
    record = validate_record_file(run / "record.json")
    assert record.status == "finished" and record.settings.generator.base_url == server.base_url
    assert record.settings.rounds == 1 and record.prompt == "oak bark"


def test_batch_of_the_71_development_prompts(server: ChatServer, tmp_path: Path) -> None:
    prompts = json.loads(DEV_PROMPTS.read_text())["prompts"]
    assert len(prompts) == 71
    out = tmp_path / "batch"
    result = CliRunner().invoke(
        cli,
        [
            "generate",
            "--prompts",
            str(DEV_PROMPTS),
            "-o",
            str(out),
            "--jobs",
            "4",
            "--model",
            "m",
            "--base-url",
            server.base_url,
            "--rounds",
            "1",
            "--variants",
            "2",
            "--scorer",
            "test-colour",
            "--json",
            "--quiet",
            *FAST_FLAGS,
        ],
    )
    assert result.exit_code == 0, result.stderr
    rows = json.loads(result.stdout)
    assert [r["id"] for r in rows] == [p["id"] for p in prompts]
    assert all(r["status"] == "finished" for r in rows)
    for p in prompts:
        record = validate_record_file(out / p["id"] / "record.json")
        assert record.prompt == p["text"] and record.status == "finished"
        assert len(record.programs) == 2 and len(record.critiques) == 2
        assert (out / p["id"] / "material.mat").exists()
    assert sum(is_critic(r) for r in server.requests) == 2 * 71

    # Resuming a finished batch redoes nothing.
    seen = len(server.requests)
    again = CliRunner().invoke(
        cli,
        [
            "generate",
            "--prompts",
            str(DEV_PROMPTS),
            "-o",
            str(out),
            "--resume",
            "--jobs",
            "4",
            "--model",
            "m",
            "--base-url",
            server.base_url,
            "--quiet",
            *FAST_FLAGS,
        ],
    )
    assert again.exit_code == 0 and len(server.requests) == seen
