"""The API key and base-URL credentials never reach record.json, other artefacts or the CLI's
output, even when a server echoes the request headers in an error body."""

from __future__ import annotations

import base64
from pathlib import Path

import pytest
from click.testing import CliRunner, Result

from author.chat_server import ChatServer, Fault
from author.conftest import FAST_FLAGS
from matloom.author.config import ModelSettings
from matloom.author.records import validate_record_file
from matloom.author.redact import Redactor, redact_url, url_secrets
from matloom.cli.main import cli

KEY = "sk-test-7d1c9e0b4a-SECRET-KEY"
PASSWORD = "pw-SECRET-4b9e1f"
QUERY_KEY = "query-SECRET-88c2d1"


def run_cli(out: Path, base_url: str | None, *extra: str) -> Result:
    args = ["generate", "red brick wall", "-o", str(out), "--model", "test-vision-model"]
    if base_url is not None:
        args += ["--base-url", base_url]
    args += ["--retry-backoff", "0.01", "--max-retries", "1", "--timeout", "20"]
    args += ["--scorer", "test-colour", "--variants", "4", "--rounds", "1", *FAST_FLAGS, *extra]
    return CliRunner().invoke(cli, args)


def leaks(folder: Path, secrets: list[str], *outputs: str) -> list[str]:
    """Where any of ``secrets`` appears: files under ``folder`` (all of them) and outputs."""
    found = []
    for path in sorted(folder.rglob("*")):
        if path.is_file():
            data = path.read_bytes()
            found += [f"{path}: {s}" for s in secrets if s.encode() in data]
    for n, text in enumerate(outputs):
        found += [f"output {n}: {s}" for s in secrets if s in text]
    return found


def with_userinfo(server: ChatServer) -> str:
    scheme, rest = server.base_url.split("//", 1)
    return f"{scheme}//alice:{PASSWORD}@{rest}"


@pytest.mark.parametrize("status", [400, 500])
def test_api_key_echoed_in_an_error_body_is_redacted(
    server: ChatServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, status: int
) -> None:
    monkeypatch.setenv("MATLOOM_API_KEY", KEY)
    server.inject(*[Fault(status=status, echo_headers=True)] * 2)  # the request and its retry
    result = run_cli(tmp_path / "run", server.base_url)
    assert result.exit_code == 1
    assert server.state.headers[0]["authorization"] == f"Bearer {KEY}"  # sent, then echoed
    assert f"HTTP {status}" in result.stderr
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.status == "failed" and f"HTTP {status}" in record.error
    if status == 400:  # the body is quoted in the message: the key is replaced in it
        assert "Bearer [REDACTED]" in result.stderr and "Bearer [REDACTED]" in record.error
    assert leaks(tmp_path / "run", [KEY], result.stdout, result.stderr) == []


def test_key_in_a_failing_run_then_finished_on_resume_is_never_stored(
    server: ChatServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("MATLOOM_API_KEY", KEY)
    server.inject(Fault(status=400, echo_headers=True))
    first = run_cli(tmp_path / "run", server.base_url)
    assert first.exit_code == 1
    again = run_cli(tmp_path / "run", server.base_url, "--resume")
    assert again.exit_code == 0, again.stderr
    assert validate_record_file(tmp_path / "run" / "record.json").status == "finished"
    outputs = [first.stdout, first.stderr, again.stdout, again.stderr]
    assert leaks(tmp_path / "run", [KEY], *outputs) == []


def test_base_url_userinfo_is_redacted_and_resume_asks_for_the_url(
    server: ChatServer, tmp_path: Path
) -> None:
    url = with_userinfo(server)
    basic = base64.b64encode(f"alice:{PASSWORD}".encode()).decode()
    server.inject(Fault(status=400, echo_headers=True))
    failed = run_cli(tmp_path / "run", url)
    assert failed.exit_code == 1
    assert server.state.headers[0]["authorization"] == f"Basic {basic}"  # sent, then echoed
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.generator.base_url == redact_url(url)
    assert "REDACTED@127.0.0.1" in record.settings.generator.base_url
    # Resuming needs the URL again (the record does not have its credentials) ...
    no_url = run_cli(tmp_path / "run", None, "--resume")
    assert no_url.exit_code == 1 and "pass --base-url" in no_url.stderr
    # ... and finishes with it.
    resumed = run_cli(tmp_path / "run", url, "--resume")
    assert resumed.exit_code == 0, resumed.stderr
    outputs = [r.stdout + r.stderr for r in (failed, no_url, resumed)]
    secrets = [PASSWORD, basic, f"alice:{PASSWORD}"]
    assert leaks(tmp_path / "run", secrets, *outputs) == []


def test_base_url_query_key_is_redacted(server: ChatServer, tmp_path: Path) -> None:
    url = f"{server.base_url}?key={QUERY_KEY}"
    result = run_cli(tmp_path / "run", url)
    assert server.requests == [] and result.exit_code == 1  # the client cannot use such a URL
    record = validate_record_file(tmp_path / "run" / "record.json")
    assert record.settings.generator.base_url.endswith("?key=REDACTED")
    assert "?key=REDACTED" in result.stderr
    assert leaks(tmp_path / "run", [QUERY_KEY], result.stdout, result.stderr) == []


def test_redactor_unit() -> None:
    url = f"https://alice:{PASSWORD}@host.example/v1?key={QUERY_KEY}&v=2#frag"
    assert redact_url(url) == "https://REDACTED@host.example/v1?key=REDACTED&v=REDACTED#REDACTED"
    assert PASSWORD in url_secrets(url) and QUERY_KEY in url_secrets(url)
    redactor = Redactor.for_settings([ModelSettings(model="m", base_url=url), None])
    text = f'error at {url}: {{"authorization": "Bearer {KEY}", "key": "{QUERY_KEY}"}}'
    cleaned = redactor.text(text)
    assert PASSWORD not in cleaned and QUERY_KEY not in cleaned
    assert redact_url(url) in cleaned
    # JSON with an escaped secret is redacted after decoding, and stays valid JSON.
    tricky = ModelSettings(model="m", base_url='https://h/v1?key=ab"cd\\efgh')
    dumped = '{"a": "x ab\\"cd\\\\efgh y", "n": 1}'
    assert Redactor.for_settings([tricky]).json_text(dumped) == (
        '{\n  "a": "x [REDACTED] y",\n  "n": 1\n}\n'
    )
    assert Redactor().json_text(dumped) == dumped  # nothing to redact: unchanged
