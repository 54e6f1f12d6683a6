"""A scripted chat model for tests and demos, registered as the ``scripted`` provider.

Scripts are registered by name with :func:`register_script` (replies are strings or functions
of the conversation), or read from a JSON file when the model id is a path to a ``.json`` list
of reply strings. Each call takes the next reply; a script that runs out raises
:class:`~matloom.author.llm.base.ModelError`. Every conversation the model saw is kept in
``calls`` so tests can assert on what was sent.
"""

from __future__ import annotations

import json
import threading
from collections.abc import Callable, Sequence
from pathlib import Path

from matloom.author.config import ModelSettings
from matloom.author.llm.base import ChatMessage, ChatReply, ModelError, register_provider

Reply = str | Callable[[Sequence[ChatMessage]], str]
_SCRIPTS: dict[str, ScriptedModel] = {}


class ScriptedModel:
    """Answers with scripted replies, in order; thread-safe."""

    def __init__(self, model_id: str, replies: Sequence[Reply], *, images: bool = True) -> None:
        self._model_id = model_id
        self._replies = list(replies)
        self._images = images
        self._lock = threading.Lock()
        self.calls: list[list[ChatMessage]] = []

    @property
    def model_id(self) -> str:
        return self._model_id

    @property
    def accepts_images(self) -> bool:
        return self._images

    def complete(self, messages: Sequence[ChatMessage]) -> ChatReply:
        with self._lock:
            index = len(self.calls)
            self.calls.append(list(messages))
            if index >= len(self._replies):
                raise ModelError(f"scripted model {self._model_id!r} ran out of replies")
            reply = self._replies[index]
        text = reply(messages) if callable(reply) else reply
        return ChatReply(text=text, model=self._model_id, seconds=0.0)


def register_script(
    model_id: str, replies: Sequence[Reply], *, images: bool = True
) -> ScriptedModel:
    """Register (or replace) the script answered for ``ModelSettings(provider="scripted", model=...)``."""
    model = ScriptedModel(model_id, replies, images=images)
    _SCRIPTS[model_id] = model
    return model


@register_provider("scripted")
def _make_scripted(settings: ModelSettings) -> ScriptedModel:
    if settings.model in _SCRIPTS:
        return _SCRIPTS[settings.model]
    path = Path(settings.model)
    if path.suffix == ".json" and path.exists():
        replies = json.loads(path.read_text(encoding="utf-8"))
        if not isinstance(replies, list) or not all(isinstance(r, str) for r in replies):
            raise ModelError(f"{path} must hold a JSON list of reply strings")
        return ScriptedModel(settings.model, replies, images=settings.accepts_images)
    raise ModelError(f"no script registered for scripted model {settings.model!r}")
