"""``POST /api/blender`` against a real server (tests/studio/conftest.py): the flat and staged
Blender renders come back as PNGs of the asked size. The renders need Blender or the bpy module
(``MATLOOM_BLENDER_PYTHON``, ``make blender-venv``: see docs/blender.md) and skip without one;
the refusals run everywhere."""

from __future__ import annotations

import struct
from typing import Any

import pytest

pytest.importorskip("starlette", reason="the studio needs the [studio] extra (starlette)")

DEMO = "black_ceramic_tiles.mat"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: The conftest's server helper (tests/studio/conftest.py).
StudioServer = Any


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == PNG_SIGNATURE and data[12:16] == b"IHDR"
    width, height = struct.unpack(">II", data[16:24])
    return width, height


@pytest.fixture(scope="module")
def with_blender(studio: StudioServer) -> StudioServer:
    """The studio server, skipping the test where Blender (or bpy) is not available."""
    from matloom.blender.runner import BlenderError, find_blender

    try:
        find_blender()
    except BlenderError as err:
        pytest.skip(f"no Blender or bpy here ({err})")
    assert studio.get("/api/session").json()["blender"] is True
    return studio


@pytest.mark.blender
@pytest.mark.slow
@pytest.mark.parametrize("mode", ["flat", "staged"])
def test_blender_renders_a_png_of_the_asked_size(with_blender: StudioServer, mode: str) -> None:
    text = (with_blender.root / DEMO).read_text(encoding="utf-8")
    reply = with_blender.post("/api/blender", {"text": text, "mode": mode, "size": 96}, timeout=600)
    assert reply.status == 200, reply.body[:300]
    assert reply.headers["content-type"] == "image/png"
    assert png_size(reply.body) == (96, 96)


def test_blender_refusals_are_one_line(
    studio: StudioServer, monkeypatch: pytest.MonkeyPatch
) -> None:
    state = studio.app.state.studio
    monkeypatch.setattr(state, "blender", True)  # refused before Blender is ever run
    text = (studio.root / DEMO).read_text(encoding="utf-8")
    for body, status in [
        ({"text": text, "mode": "sideways"}, 400),
        ({"text": text, "mode": "flat", "size": 8}, 400),
        ({"text": text, "mode": "flat", "size": 4096}, 400),
        ({"text": "Material(Layer(1).roughness(", "mode": "flat"}, 422),
        ({"mode": "flat"}, 400),
    ]:
        reply = studio.post("/api/blender", body)
        assert reply.status == status, (body, reply.body)
        assert "\n" not in reply.json()["error"]
    monkeypatch.setattr(state, "blender", False)
    reply = studio.post("/api/blender", {"text": text, "mode": "flat"})
    assert reply.status == 404 and "Blender is not available" in reply.json()["error"]
