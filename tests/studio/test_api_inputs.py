"""Bad input to the studio's HTTP API gets a one-line JSON error, never a 500 (a real server,
tests/studio/conftest.py): bodies nested too deep, lone surrogates, NaN and Infinity where a
whole number goes, a wrong method, odd static paths, paths too long or deep, a bad
``Last-Event-ID``."""

from __future__ import annotations

import json
from typing import Any

import pytest

pytest.importorskip("starlette", reason="the studio needs the [studio] extra (starlette)")

DEMO = "black_ceramic_tiles.mat"
#: The conftest's server helper (tests/studio/conftest.py).
StudioServer = Any


def demo(studio: StudioServer) -> str:
    return (studio.root / DEMO).read_text(encoding="utf-8")


def one_line_error(reply: Any, status: int) -> str:
    assert reply.status == status, reply.body[:300]
    message = reply.json()["error"]
    assert isinstance(message, str) and "\n" not in message and "internal error" not in message
    return message


def test_a_body_nested_too_deep_is_a_400(studio: StudioServer) -> None:
    deep = b"[" * 100_000 + b"]" * 100_000
    for path in ("/api/check", "/api/evaluate", "/api/save"):
        assert "nested too deep" in one_line_error(studio.post(path, deep), 400)


def test_a_lone_surrogate_is_a_400_and_nothing_is_written(studio: StudioServer) -> None:
    text = "# \ud800 a half character\n" + demo(studio)
    for path, body in [
        ("/api/save", {"path": "surrogate.mat", "text": text}),
        ("/api/format", {"text": text}),
        ("/api/seeds", {"text": text, "op": "pin"}),
        ("/api/layers", {"text": text, "op": "duplicate", "index": 1}),
        ("/api/edit", {"text": text, "request": "wider grout"}),
    ]:
        raw = json.dumps(body).encode()  # ensure_ascii: the surrogate travels as "\ud800"
        assert "surrogate" in one_line_error(studio.post(path, raw), 400)
    assert not (studio.root / "surrogate.mat").exists()
    pair = "# \U0001f600 a whole character\n" + demo(studio)  # a pair is fine
    assert studio.post("/api/check", {"text": pair}).json()["ok"] is True


@pytest.mark.parametrize("number", ["NaN", "Infinity", "-Infinity"])
def test_nan_and_infinity_are_not_whole_numbers(studio: StudioServer, number: str) -> None:
    text = json.dumps(demo(studio))
    for path, body in [
        ("/api/evaluate", f'{{"text": {text}, "size": {number}, "stream": "nan-test"}}'),
        ("/api/evaluate", f'{{"text": {text}, "size": 8, "seq": {number}, "stream": "nan-test"}}'),
        ("/api/layers", f'{{"text": {text}, "op": "move", "index": {number}, "to": 1}}'),
        ("/api/export.zip", f'{{"text": {text}, "size": 8, "program_seed": {number}}}'),
    ]:
        assert "whole number" in one_line_error(studio.post(path, body.encode()), 400)


def test_a_wrong_method_is_a_json_405(studio: StudioServer) -> None:
    for method, path in [("PUT", "/api/check"), ("DELETE", "/api/save"), ("POST", "/")]:
        reply = studio.request(method, path, b"{}")
        one_line_error(reply, 405)
        assert reply.headers.get("allow")


def test_odd_static_paths_are_404(studio: StudioServer) -> None:
    for path in ("/%00", "/static/a%00b.js", "/" + "a" * 300 + ".js", "/a" * 3000):
        one_line_error(studio.get(path, token=None), 404)


def test_paths_too_long_or_deep_are_a_400(studio: StudioServer) -> None:
    text = demo(studio)
    for rel in ("a" * 300 + ".mat", "a/" * 3000 + "x.mat", "d/" * 40 + "x.mat"):
        assert "too long" in one_line_error(
            studio.post("/api/save", {"path": rel, "text": text}), 400
        )
        assert "too long" in one_line_error(studio.get(f"/api/file?path={rel}"), 400)
    for out in ("b" * 300, "b/" * 2000, "c/" * 40):
        body = {"text": text, "size": 8, "out": out}
        assert "too long" in one_line_error(studio.post("/api/export", body), 400)
    assert not (studio.root / "b").exists() and not (studio.root / "c").exists()


def test_a_negative_last_event_id_replays_from_the_start(studio: StudioServer) -> None:
    from matloom.studio.jobs import Job

    job = Job("lasteventid1", "a prompt")
    job.emit("log", {"line": "one"})
    job.emit("done", {"text": "Material(Layer(1))", "name": "x"})
    jobs = studio.app.state.studio.jobs
    with jobs._lock:  # a finished run, without running one
        jobs._jobs[job.id] = job
    reply = studio.get(f"/api/jobs/{job.id}/events", headers={"Last-Event-ID": "-5"})
    assert reply.status == 200
    ids = [line for line in reply.body.decode().splitlines() if line.startswith("id:")]
    assert ids == ["id: 0", "id: 1"]
