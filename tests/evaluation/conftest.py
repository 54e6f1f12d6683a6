"""Fixtures shared by the evaluation tests: the authoring tests' scripted Chat Completions server
(tests/author/chat_server.py, loaded by path: these tests are not a package) and a config file
whose profile ``scripted`` and settings preset ``tiny`` point at it."""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

CHAT = Path(__file__).resolve().parents[1] / "author" / "chat_server.py"

#: Settings of a cheap model run: no critique rounds, no scorer, tiny renders.
TINY_SETTINGS = (
    '[settings.tiny]\nbase = "paper"\nrounds = 0\nscorer = "none"\nvariants = 0\n'
    "critique_size = 32\nselect_size = 32\nsweep_size = 32\nexport_size = 32\n"
    "stats_grid = 16\n"
)


@pytest.fixture(scope="session")
def chat_module() -> Any:
    """The module of the scripted server (``ChatServer``, ``Fault``)."""
    name = "evaluation_chat_server"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, CHAT)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


@pytest.fixture
def scripted_config() -> Callable[[Path, str], Path]:
    """``write(path, base_url)``: a config file with profile ``scripted`` on that server and the
    settings preset ``tiny``."""

    def write(path: Path, base_url: str) -> Path:
        path.write_text(
            f'[profiles.scripted]\nmodel = "scripted-model"\nbase_url = "{base_url}"\n'
            f"max_retries = 0\ntimeout_s = 20\n\n{TINY_SETTINGS}",
            encoding="utf-8",
        )
        return path

    return write
