"""Text-to-material authoring: the LLM pipeline (generate, repair, critique, select, seed search).

Quick API::

    from matloom.author import AuthorConfig, ModelSettings, author_material
    config = AuthorConfig(generator=ModelSettings(model="gpt-5.6-luna"), variants=200)
    result = author_material("weathered red brick wall", "runs/brick", config)
    print(result.program)

With ``AuthorConfig()`` (no generator) the offline author is used: the material library
(:func:`matloom.library.author`, see docs/library.md).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from matloom.author.config import AuthorConfig, ModelSettings

if TYPE_CHECKING:
    from matloom.author.pipeline import AuthoringError, ProgressEvent, RunResult, author_material

_LAZY = {
    "author_material": "matloom.author.pipeline",
    "AuthoringError": "matloom.author.pipeline",
    "ProgressEvent": "matloom.author.pipeline",
    "RunResult": "matloom.author.pipeline",
    "author_batch": "matloom.author.batch",
    "read_prompts": "matloom.author.batch",
}


def __getattr__(name: str) -> Any:
    """Import the pipeline lazily (keeps `import matloom.author.config` light)."""
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(name)


__all__ = [
    "AuthorConfig",
    "AuthoringError",
    "ModelSettings",
    "ProgressEvent",
    "RunResult",
    "author_batch",
    "author_material",
    "read_prompts",
]
