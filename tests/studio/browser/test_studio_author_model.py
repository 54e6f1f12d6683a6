"""The author box with a configured model: rounds stream to the page while the run goes on,
and Cancel stops it. The model is a scripted Chat Completions server on 127.0.0.1 (the
authoring tests' own), named in a matloom.toml given to the studio through MATLOOM_CONFIG."""

from __future__ import annotations

import importlib.util
import json
import os
import shutil
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from matloom.author.prompts.system import FEW_SHOT_EXAMPLES

from .conftest import DEMO, ROOT, open_page, shot, start_studio, stop_studio


def _chat_server() -> Any:
    """The authoring tests' scripted Chat Completions server (tests/author/chat_server.py)."""
    path = ROOT / "tests" / "author" / "chat_server.py"
    spec = importlib.util.spec_from_file_location("studio_chat_server", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the class is made
    spec.loader.exec_module(module)
    return module


def _reply(body: dict[str, Any]) -> str:
    """A valid program for the generator, a critique (as JSON) for the critic."""
    first = body["messages"][0]["content"]
    system = first if isinstance(first, str) else " ".join(p.get("text", "") for p in first)
    if "critic" in system:
        return json.dumps(
            {"match_score": 55, "differences": ["too dark"], "suggestions": ["raise basecolor"]}
        )
    turns = sum(m["role"] == "assistant" for m in body["messages"])
    program = FEW_SHOT_EXAMPLES[turns % len(FEW_SHOT_EXAMPLES)].program()
    return f"<material>\n{program}\n</material>"


pytestmark = pytest.mark.browser


@pytest.fixture
def model_studio(tmp_path: Path) -> Iterator[tuple[str, Any]]:
    pytest.importorskip("starlette", reason="the studio needs the [studio] extra")
    chat = _chat_server()
    with chat.ChatServer(_reply) as server:
        # the first model answer at once, then each one slowly: the run is mid-way for seconds
        server.inject(chat.Fault(), *[chat.Fault(delay=2.5) for _ in range(12)])
        config = tmp_path / "matloom.toml"
        config.write_text(
            '[matloom]\nprofile = "local"\n\n[profiles.local]\n'
            f'model = "test-vision-model"\nbase_url = "{server.base_url}"\n'
            'api_key_env = "MATLOOM_TEST_KEY"\n',
            encoding="utf-8",
        )
        root = tmp_path / "ws"
        root.mkdir()
        shutil.copy(DEMO, root / DEMO.name)
        env = {**os.environ, "MATLOOM_CONFIG": str(config), "MATLOOM_TEST_KEY": "test-key"}
        running = start_studio(root / DEMO.name, env)
        try:
            yield running.url, server
        finally:
            stop_studio(running)


def test_a_model_run_streams_rounds_and_cancel_stops_it(browser: Any, model_studio: Any) -> None:
    url, server = model_studio
    page = open_page(browser, url)
    try:
        page.locator('[data-testid="tab-author"]').click()
        use_model = page.locator('[data-testid="author-model"]')
        assert use_model.is_enabled(), "the page does not know a model is configured"
        use_model.check()
        page.locator('[data-testid="author-prompt"]').fill("black shiny ceramic floor tiles")
        page.locator('[data-testid="author-run"]').click()
        page.locator('[data-testid="author-rounds"] img').first.wait_for(timeout=60_000)
        cancel = page.locator('[data-testid="author-cancel"]')
        assert cancel.is_enabled(), "the run ended before it could be seen mid-way"
        shot(page, "studio-author")
        asked = len(server.requests)
        cancel.click()
        page.locator('[data-testid="author-status"]').get_by_text("cancelled").wait_for(
            timeout=30_000
        )
        time.sleep(3)
        # at most the request in flight when cancelled completes; no new round starts
        assert len(server.requests) <= asked + 1
        assert "test-key" not in page.content()
    finally:
        page.close()
