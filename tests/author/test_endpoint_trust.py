"""Credentials go only where the user said: a run folder's record.json and a matloom.toml in the
current folder cannot choose the server or the key variable (issue 22, defect 3); stderr names
both. Also: a resumed run is the same run (prompt and settings), and ``--extra-body`` is not
stored (defect 16).

Two real servers on 127.0.0.1: the user's, and the one an attacker wrote into the folder. Each
records the Authorization header it receives.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner, Result

from author.chat_server import ChatServer
from author.conftest import FAST_FLAGS, Script
from matloom.author.config import ModelSettings, api_key_for
from matloom.author.finalize import material_name
from matloom.author.records import validate_record_file
from matloom.cli.main import cli
from matloom.io.outdir import INDEX_NAME, file_sha256
from matloom.library import author

VICTIM = "victim-SECRET-token-5f2a9c7d31"
EXTRA_SECRET = "xtra-SECRET-0a1b2c3d4e5f6789"
QUICK = ["--rounds", "0", "--scorer", "none", "--variants", "0", "--max-retries", "0"]


@pytest.fixture
def attacker() -> Iterator[ChatServer]:
    with ChatServer(Script()) as srv:
        yield srv


@pytest.fixture(autouse=True)
def _victim_token(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("VICTIM_TOKEN", VICTIM)


def run_cli(*args: str) -> Result:
    return CliRunner().invoke(cli, list(args))


def authorizations(server: ChatServer) -> list[str]:
    return [h.get("authorization", "") for h in server.state.headers]


def tamper(run: Path, edit: Callable[[dict[str, Any]], None]) -> None:
    """Edit record.json as an attacker would, keeping the folder's index consistent (the file's
    SHA-256, size and time updated), so MatLoom takes the file for its own."""
    path = run / "record.json"
    data = json.loads(path.read_text())
    edit(data)
    path.write_text(json.dumps(data, indent=2))
    index = json.loads((run / INDEX_NAME).read_text())
    stat = path.stat()
    entry = index["files"]["record.json"]
    entry.update(sha256=file_sha256(path), size=stat.st_size, mtime_ns=stat.st_mtime_ns)
    (run / INDEX_NAME).write_text(json.dumps(index, indent=1))


def failed_model_run(run: Path) -> None:
    """A run whose server was down: its record waits for --resume."""
    dead = ["--model", "m", "--base-url", "http://127.0.0.1:9/v1"]
    first = run_cli("generate", "oak bark", "-o", str(run), *dead, *QUICK, *FAST_FLAGS)
    assert first.exit_code == 1 and "--resume" in first.stderr


# ------------------------------------------------------------------ record.json (defect 3a)


@pytest.mark.parametrize("key_env", ["VICTIM_TOKEN", None])
def test_resume_never_sends_a_key_to_a_server_the_record_names(
    server: ChatServer, attacker: ChatServer, tmp_path: Path, key_env: str | None
) -> None:
    run = tmp_path / "run"
    failed_model_run(run)

    def point_at_attacker(data: dict[str, Any]) -> None:
        data["settings"]["generator"].update(base_url=attacker.base_url, api_key_env=key_env)

    tamper(run, point_at_attacker)
    refused = run_cli("generate", "--resume", "-o", str(run))
    assert refused.exit_code == 1
    assert attacker.requests == [] and server.requests == []
    assert attacker.base_url in refused.stderr and "--trust-record" in refused.stderr
    assert len(refused.stderr.strip().splitlines()) == 1 and "Traceback" not in refused.stderr

    # The user's own server, given again: the recorded key variable is not adopted either.
    resumed = run_cli("generate", "--resume", "-o", str(run), "--base-url", server.base_url)
    assert resumed.exit_code == 0, resumed.stderr
    assert attacker.requests == []
    assert authorizations(server) == ["Bearer test-key"]  # MATLOOM_API_KEY, not VICTIM_TOKEN
    assert f"generator m at {server.base_url}, API key from $MATLOOM_API_KEY" in resumed.stderr
    assert validate_record_file(run / "record.json").status == "finished"


def test_resume_refuses_a_critic_server_written_into_the_record(
    server: ChatServer, attacker: ChatServer, tmp_path: Path
) -> None:
    run = tmp_path / "run"
    failed_model_run(run)

    def add_critic(data: dict[str, Any]) -> None:
        data["settings"]["critic"] = {"model": "c", "base_url": attacker.base_url}

    tamper(run, add_critic)
    refused = run_cli("generate", "--resume", "-o", str(run), "--base-url", server.base_url)
    assert refused.exit_code == 1 and "critic" in refused.stderr
    assert attacker.base_url in refused.stderr and "--critic-base-url" in refused.stderr
    assert attacker.requests == [] and server.requests == []


def test_trust_record_uses_the_recorded_server_and_says_so(
    server: ChatServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    run = tmp_path / "run"
    failed_model_run(run)
    monkeypatch.setenv("MY_OWN_KEY", "own-key-123456789")
    tamper(
        run,
        lambda d: d["settings"]["generator"].update(
            base_url=server.base_url, api_key_env="MY_OWN_KEY"
        ),
    )
    resumed = run_cli("generate", "--resume", "--trust-record", "-o", str(run))
    assert resumed.exit_code == 0, resumed.stderr
    assert authorizations(server) == ["Bearer own-key-123456789"]
    assert f"at {server.base_url}, API key from $MY_OWN_KEY" in resumed.stderr


# ------------------------------------------------------------------ ./matloom.toml (defect 3b)


def test_a_matloom_toml_in_the_current_folder_is_not_read_without_config(
    attacker: ChatServer, tmp_path: Path
) -> None:
    # conftest runs every test in tmp_path: this is the current folder.
    (tmp_path / "matloom.toml").write_text(
        '[matloom]\nprofile = "evil"\n\n[profiles.evil]\nmodel = "m"\n'
        f'base_url = "{attacker.base_url}"\napi_key_env = "VICTIM_TOKEN"\n'
    )
    plain = run_cli("generate", "red brick", "-o", str(tmp_path / "plain"), *FAST_FLAGS)
    assert plain.exit_code == 0, plain.stderr
    assert attacker.requests == []
    assert validate_record_file(tmp_path / "plain" / "record.json").author == "library"
    assert "matloom.toml is not read" in plain.stderr and "--config" in plain.stderr

    # Named with --config, it is the user's choice, and stderr names the server and the key.
    chosen = run_cli(
        "generate", "red brick", "-o", str(tmp_path / "chosen"), "--config", "matloom.toml",
        *QUICK, *FAST_FLAGS,
    )  # fmt: skip
    assert chosen.exit_code == 0, chosen.stderr
    assert authorizations(attacker) == [f"Bearer {VICTIM}"]
    assert f"generator m at {attacker.base_url}, API key from $VICTIM_TOKEN" in chosen.stderr
    assert "default profile 'evil' of matloom.toml" in chosen.stderr


def test_a_named_key_variable_does_not_fall_back_to_another_key(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("MATLOOM_API_KEY", "matloom-key")
    monkeypatch.delenv("EMPTY_PROVIDER_KEY", raising=False)
    assert api_key_for(ModelSettings(model="m", api_key_env="EMPTY_PROVIDER_KEY")) is None
    assert api_key_for(ModelSettings(model="m")) == "matloom-key"


# ------------------------------------------------------------------ resume = the same run


def test_resume_with_another_prompt_or_other_settings_is_refused(tmp_path: Path) -> None:
    run = tmp_path / "run"
    first = run_cli("generate", "red velvet", "-o", str(run), *FAST_FLAGS)
    assert first.exit_code == 0, first.stderr
    program = (run / "material.mat").read_bytes()
    # The offline author names the material after the library entry it used.
    entry = author("red velvet", seed=0).entry
    assert json.loads((run / "material.json").read_text())["name"] == material_name(entry)

    other = run_cli("generate", "blue velvet", "-o", str(run), "--resume", *FAST_FLAGS)
    assert other.exit_code == 1
    assert "'red velvet'" in other.stderr and "'blue velvet'" in other.stderr
    assert other.stdout == "" and "record is kept" not in other.stderr

    settings = run_cli("generate", "-o", str(run), "--resume", "--rounds", "2", "--seed", "7")
    assert settings.exit_code == 1
    assert "rounds: 5 -> 2" in settings.stderr and "seed: 0 -> 7" in settings.stderr

    same = run_cli("generate", "red velvet", "-o", str(run), "--resume", *FAST_FLAGS)
    assert same.exit_code == 0, same.stderr
    assert (run / "material.mat").read_bytes() == program
    assert validate_record_file(run / "record.json").prompt == "red velvet"


# ------------------------------------------------------------------ --extra-body (defect 16)


def test_extra_body_is_sent_but_not_stored_and_resume_asks_for_it(
    server: ChatServer, tmp_path: Path
) -> None:
    run = tmp_path / "run"
    body = json.dumps({"api_token": EXTRA_SECRET, "reasoning": {"enabled": True}})
    model = ["--model", "m", "--base-url", server.base_url]
    first = run_cli(
        "generate", "Red brick wall!", "-o", str(run), *model, "--extra-body", body, "--json",
        *QUICK, *FAST_FLAGS,
    )  # fmt: skip
    assert first.exit_code == 0, first.stderr
    assert server.requests[0]["api_token"] == EXTRA_SECRET  # sent to the user's server
    stored = [p for p in run.rglob("*") if p.is_file() and EXTRA_SECRET.encode() in p.read_bytes()]
    assert stored == [] and EXTRA_SECRET not in first.stdout + first.stderr
    record = validate_record_file(run / "record.json")
    assert record.settings.generator.extra_body == {
        "api_token": "[REDACTED]",
        "reasoning": {"enabled": True},
    }
    # The material is named after the prompt, in material.json and the summary.
    assert json.loads((run / "material.json").read_text())["name"] == "red_brick_wall"
    assert json.loads(first.stdout)["name"] == "red_brick_wall"

    again = run_cli("generate", "--resume", "-o", str(run), *model)
    assert again.exit_code == 1 and "--extra-body" in again.stderr
    given = run_cli("generate", "--resume", "-o", str(run), *model, "--extra-body", body)
    assert given.exit_code == 0, given.stderr
