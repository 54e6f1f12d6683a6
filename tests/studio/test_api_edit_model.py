"""A model edit (/api/edit with the configured model) does not hold the engine while the model
answers: the 3D view's evaluations go on. The model is the authoring tests' scripted Chat
Completions server on 127.0.0.1, made to hang until released."""

from __future__ import annotations

import importlib.util
import os
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from .conftest import StudioServer
from .test_api import demo

CHAT = Path(__file__).resolve().parents[1] / "author" / "chat_server.py"


def _chat_server() -> Any:
    spec = importlib.util.spec_from_file_location("studio_api_chat_server", CHAT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def test_a_model_edit_does_not_block_evaluation(
    studio: StudioServer, monkeypatch: pytest.MonkeyPatch
) -> None:
    chat = _chat_server()
    config = Path(os.environ["MATLOOM_CONFIG"])
    before = config.read_text(encoding="utf-8")
    text = demo(studio)
    with chat.ChatServer(lambda body: '{"set": {}}') as server:
        server.inject(chat.Fault(hang=True))
        config.write_text(
            '[matloom]\nprofile = "local"\n\n[profiles.local]\n'
            f'model = "test-model"\nbase_url = "{server.base_url}"\n'
            'api_key_env = "MATLOOM_TEST_KEY"\n',
            encoding="utf-8",
        )
        monkeypatch.setenv("MATLOOM_TEST_KEY", "test-key")
        done: dict[str, Any] = {}
        edit = threading.Thread(
            target=lambda: done.update(
                reply=studio.post(
                    "/api/edit", {"text": text, "request": "wider grout", "model": True}
                )
            )
        )
        try:
            edit.start()
            assert server.state.hung.wait(30), "the edit never asked the model"
            t0 = time.monotonic()
            reply = studio.post(
                "/api/evaluate",
                {"text": text, "size": 32, "stream": "t-edit-model", "seq": 1},
                timeout=20,
            )
            assert reply.status == 200
            assert time.monotonic() - t0 < 15
        finally:
            server.release()
            edit.join(60)
            config.write_text(before, encoding="utf-8")
    assert "reply" in done  # the edit answered (whatever the model's reply made of it)
