"""`generate` checks every setting before the first model request (issue 22, defect 14), refuses
a prompt that is not text with one line and no record (defect 15), and names its material
after the prompt (not ``material``)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS
from matloom.author.config import MAX_SIZE, AuthorConfig, ModelSettings
from matloom.author.finalize import material_name
from matloom.author.resume import AccessFlags, resumed_access
from matloom.cli.main import cli
from matloom.engine.limits import DEFAULT_LIMITS

REPO = Path(__file__).resolve().parents[2]
QUICK = ["--rounds", "0", "--scorer", "none", "--variants", "0"]


def generate(server: ChatServer, out: Path, *extra: str) -> Result:
    args = ["generate", "red brick", "-o", str(out), "--model", "m", "--base-url"]
    return CliRunner().invoke(cli, [*args, server.base_url, *QUICK, *FAST_FLAGS, *extra])


def assert_refused_up_front(result: Result, server: ChatServer, out: Path, *words: str) -> None:
    assert result.exit_code == 1, result.stdout
    assert server.requests == []  # nothing paid for
    assert not (out / "record.json").exists()
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: "), result.stderr
    assert all(w in lines[0] for w in words), lines[0]


@pytest.mark.parametrize(
    ("flags", "words"),
    [
        (["--export-size", "9000"], ["export_size", "8192"]),
        (["--critique-size", "100000"], ["critique_size"]),
        (["--timeout", "nan"], ["timeout_s"]),
        (["--timeout", "0"], ["timeout_s"]),
        (["--retry-backoff", "-5"], ["backoff_s"]),
        (["--max-retries", "-1"], ["max_retries"]),
        (["--extra-body", "[1, 2]"], ["--extra-body", "JSON object"]),
        (["--extra-body", "{nope"], ["--extra-body", "not valid JSON"]),
    ],
)
def test_bad_flags_fail_before_any_request(
    server: ChatServer, tmp_path: Path, flags: list[str], words: list[str]
) -> None:
    out = tmp_path / "run"
    assert_refused_up_front(generate(server, out, *flags), server, out, *words)


@pytest.mark.parametrize(
    ("line", "word"),
    [
        ("backoff_s = -5", "backoff_s"),
        ("timeout_s = nan", "timeout_s"),
        ("temperature = inf", "temperature"),
    ],
)
def test_bad_profile_values_fail_before_any_request(
    server: ChatServer, tmp_path: Path, line: str, word: str
) -> None:
    config = tmp_path / "mine.toml"
    config.write_text(f'[profiles.p]\nmodel = "m"\nbase_url = "{server.base_url}"\n{line}\n')
    out = tmp_path / "run"
    result = CliRunner().invoke(
        cli,
        ["generate", "red brick", "-o", str(out), "--config", str(config), "--profile", "p",
         *QUICK, *FAST_FLAGS],
    )  # fmt: skip
    assert_refused_up_front(result, server, out, "profile 'p' is invalid", word)


def test_the_memory_budget_is_checked_before_any_request(
    server: ChatServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("MATLOOM_MAX_MEMORY_MB", "1")
    out = tmp_path / "run"
    result = generate(server, out, "--export-size", "512")
    assert_refused_up_front(result, server, out, "MATLOOM_MAX_MEMORY_MB")


def test_resuming_an_edited_record_with_a_bad_size_is_one_line(tmp_path: Path) -> None:
    run = tmp_path / "run"
    first = CliRunner().invoke(cli, ["generate", "red brick", "-o", str(run), *FAST_FLAGS])
    assert first.exit_code == 0, first.stderr
    data = json.loads((run / "record.json").read_text())
    data["settings"]["export_size"] = 9000
    (run / "record.json").write_text(json.dumps(data))
    again = CliRunner().invoke(cli, ["generate", "--resume", "-o", str(run)])
    assert again.exit_code == 1 and "Traceback" not in again.stderr
    assert len(again.stderr.strip().splitlines()) == 1 and "export_size" in again.stderr


def test_max_size_is_the_engines_resolution_limit() -> None:
    assert MAX_SIZE == DEFAULT_LIMITS.max_resolution


def test_a_prompt_that_is_not_utf8_is_refused_without_a_record(tmp_path: Path) -> None:
    env = {**os.environ, "PYTHONPATH": str(REPO), "LC_ALL": "C.UTF-8"}
    result = subprocess.run(
        [sys.executable, "-m", "matloom", "generate", b"red \xff velvet", "-o", "run"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 1, result.stderr
    assert "UTF-8" in result.stderr and "Traceback" not in result.stderr
    assert "record" not in result.stderr and not (tmp_path / "run" / "record.json").exists()
    assert len(result.stderr.strip().splitlines()) == 1


def test_material_names_come_from_the_prompt() -> None:
    assert material_name("Red brick wall!") == "red_brick_wall"
    assert material_name("Café crème, wet") == "cafe_creme_wet"
    assert material_name("azulejo-portuguese-tiles") == "azulejo_portuguese_tiles"
    assert material_name("苔") == "material"
    long = material_name("very " * 30 + "long")
    assert len(long) <= 48 and long.startswith("very_very") and not long.endswith("_")


def test_a_critic_on_the_generators_server_follows_its_new_server() -> None:
    old = ModelSettings(model="g", base_url="http://old/v1", api_key_env="K")
    recorded = AuthorConfig(generator=old, critic=old.model_copy(update={"model": "c"}))
    new = old.model_copy(update={"base_url": "http://new/v1"})
    built = recorded.model_copy(update={"generator": new})
    flags = AccessFlags(generator_endpoint=True)
    resumed = resumed_access(recorded, built, flags)
    assert resumed.generator.base_url == resumed.critic.base_url == "http://new/v1"
    assert resumed.generator.api_key_env is None and resumed.critic.api_key_env is None
