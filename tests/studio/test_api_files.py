"""The studio's HTTP API against a real server (tests/studio/conftest.py): files, export (the
same bytes as ``matloom render``), the zip, generate's event stream and cancel, edit."""

from __future__ import annotations

import io
import json
import os
import time
import zipfile
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("starlette", reason="the studio needs the [studio] extra (starlette)")

DEMO = "black_ceramic_tiles.mat"
#: The conftest's server helper (tests/studio/conftest.py).
StudioServer = Any


def demo(studio: StudioServer) -> str:
    return (studio.root / DEMO).read_text(encoding="utf-8")


# ---------------------------------------------------------------------------- files
def test_save_is_atomic_inside_the_root_and_refuses_outside(
    studio: StudioServer, tmp_path: Path
) -> None:
    text = "# saved\nMaterial(Layer(1).roughness(0.4))"
    reply = studio.post("/api/save", {"path": "saved.mat", "text": text})
    assert reply.status == 200 and reply.json() == {"path": "saved.mat", "bytes": len(text) + 1}
    assert (studio.root / "saved.mat").read_text() == text + "\n"
    assert not [p for p in studio.root.iterdir() if ".tmp-" in p.name]  # no temporary left
    assert studio.get("/api/file?path=saved.mat").json()["text"] == text + "\n"
    assert "saved.mat" in studio.get("/api/session").json()["files"]
    (studio.root / "sub").mkdir(exist_ok=True)
    assert studio.post("/api/save", {"path": "sub/x.mat", "text": text}).status == 200
    for bad in ("../escape.mat", "/tmp/abs.mat", "sub/../../x.mat", "notes.txt", "nodir/x.mat"):
        reply = studio.post("/api/save", {"path": bad, "text": text})
        assert reply.status == 400, bad
        assert "error" in reply.json()
    assert not (studio.root.parent / "escape.mat").exists()
    # a symlink leaving the root is not followed, for writing or reading
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "victim.mat").write_text("Material(Layer(1))")
    link = studio.root / "link"
    if not link.exists():
        os.symlink(outside, link)
    reply = studio.post("/api/save", {"path": "link/victim.mat", "text": text})
    assert reply.status == 400 and "symlink" in reply.json()["error"]
    assert (outside / "victim.mat").read_text() == "Material(Layer(1))"
    assert studio.get("/api/file?path=link/victim.mat").status == 400
    assert studio.get("/api/file?path=missing.mat").status == 404
    assert "link/victim.mat" not in studio.get("/api/session").json()["files"]


# ---------------------------------------------------------------------------- export
def _files(folder: Path) -> dict[str, bytes]:
    """Every file MatLoom delivers in ``folder`` (not its hidden index or lock)."""
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not any(part.startswith(".") for part in p.relative_to(folder).parts)
    }


def test_export_writes_the_bytes_matloom_render_writes(
    studio: StudioServer, monkeypatch: pytest.MonkeyPatch
) -> None:
    from click.testing import CliRunner

    from matloom.cli.main import cli

    options = {"size": 64, "presets": ["gltf"], "unit_m": 0.5}
    reply = studio.post("/api/export", {"text": demo(studio), "out": "exports/a", **options})
    assert reply.status == 200, reply.body
    result = reply.json()
    assert result["folder"] == "exports/a"
    assert (
        "material.json" in result["files"] and result["manifest"]["name"] == "black_ceramic_tiles"
    )
    monkeypatch.chdir(studio.root)
    run = CliRunner().invoke(
        cli,
        ["render", DEMO, "-o", "exports/cli", "--size", "64", "--preset", "gltf", "--unit-m",
         "0.5"],
    )  # fmt: skip
    assert run.exit_code == 0, run.output
    studio_files = _files(studio.root / "exports" / "a")
    assert studio_files == _files(studio.root / "exports" / "cli")
    assert set(result["files"]) <= set(studio_files)
    # the output folder's rules: a file MatLoom did not write is never replaced
    (studio.root / "exports" / "mine").mkdir()
    (studio.root / "exports" / "mine" / "material.json").write_text("{}")
    refused = studio.post("/api/export", {"text": demo(studio), "out": "exports/mine", "size": 16})
    assert refused.status == 400
    assert (studio.root / "exports" / "mine" / "material.json").read_text() == "{}"
    outside = studio.post("/api/export", {"text": demo(studio), "out": "../out", "size": 16})
    assert outside.status == 400
    bad = studio.post("/api/export", {"text": demo(studio), "out": "x", "presets": ["nope"]})
    assert bad.status == 400


def test_export_zip_holds_the_same_files(studio: StudioServer) -> None:
    body = {"text": demo(studio), "size": 64, "presets": ["gltf"], "unit_m": 0.5}
    folder = studio.post("/api/export", {**body, "out": "exports/z"})
    assert folder.status == 200
    reply = studio.post("/api/export.zip", body)
    assert reply.status == 200 and reply.headers["content-type"] == "application/zip"
    assert "black_ceramic_tiles.zip" in reply.headers["content-disposition"]
    with zipfile.ZipFile(io.BytesIO(reply.body)) as archive:
        zipped = {
            name.split("/", 1)[1]: archive.read(name)
            for name in archive.namelist()
            if not name.endswith("/")
        }
    assert zipped == _files(studio.root / "exports" / "z")


# ---------------------------------------------------------------------------- author
def _events(studio: StudioServer, job: str) -> list[tuple[str, dict]]:
    reply = studio.get(f"/api/jobs/{job}/events?token={studio.token}", token=None, timeout=120)
    assert reply.status == 200 and reply.headers["content-type"].startswith("text/event-stream")
    events = []
    for block in reply.body.decode().split("\n\n"):
        fields = dict(line.split(": ", 1) for line in block.splitlines() if ": " in line)
        if "event" in fields:
            events.append((fields["event"], json.loads(fields["data"])))
    return events


def test_generate_offline_streams_rounds_to_done(studio: StudioServer) -> None:
    reply = studio.post("/api/generate", {"prompt": "black ceramic tiles"})
    assert reply.status == 200, reply.body
    events = _events(studio, reply.json()["job"])
    kinds = [k for k, _ in events]
    assert kinds[-1] == "done" and "round" in kinds and "log" in kinds
    first_round = next(d for k, d in events if k == "round")
    assert first_round["round"] == 0 and first_round["preview_png_b64"]
    done = events[-1][1]
    assert "Material(" in done["text"]
    checked = studio.post("/api/check", {"text": done["text"]}).json()
    assert checked["ok"] is True


def test_generate_cancel_ends_the_stream(studio: StudioServer) -> None:
    job = studio.post("/api/generate", {"prompt": "weathered red brick wall"}).json()["job"]
    cancel = studio.post(f"/api/jobs/{job}/cancel", {}).json()
    events = _events(studio, job)
    if cancel["cancelled"]:
        assert events[-1] == ("error", {"error": "cancelled"})
    else:  # it finished first
        assert events[-1][0] == "done"
    # while the cancelled run's thread stops, a new run waits (409), never runs beside it
    deadline = time.monotonic() + 120
    while True:
        again = studio.post("/api/generate", {"prompt": "weathered red brick wall"})
        if again.status != 409 or time.monotonic() > deadline:
            break
        assert "still stopping" in again.json()["error"]
        time.sleep(0.2)
    assert again.status == 200, again.body
    assert _events(studio, again.json()["job"])[-1][0] == "done"
    assert studio.post("/api/jobs/nope/cancel", {}).status == 404
    assert studio.post("/api/generate", {"prompt": ""}).status == 400
    assert studio.post("/api/generate", {"prompt": "x", "model": True}).status == 400


def test_edit_offline_wider_grout(studio: StudioServer) -> None:
    text = demo(studio)
    reply = studio.post("/api/edit", {"text": text, "request": "wider grout"})
    assert reply.status == 200, reply.body
    result = reply.json()
    assert result["text"] != text and result["diff"].startswith("--- before")
    assert result["report"]["mode"] == "rules" and result["report"]["changed"]
    assert "mortar" in result["report"]["changed"][0]["address"]
    refused = studio.post("/api/edit", {"text": text, "request": "make it sing"})
    assert refused.status == 422 and refused.json()["parameters"]
