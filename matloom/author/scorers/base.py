"""Text-image scorers: the batched interface, the registry and deterministic test scorers.

A scorer maps a batch of uint8 RGB images and a text to one score per image (higher = better
match, 0..100 for the built-ins). Scorers are found by name so the seed sweep can re-create
them inside worker processes: ``get_scorer(name)`` (:mod:`.lookup`) returns a cached
instance per process.

Names:

* ``mobileclip2``: the paper's MobileCLIP2-S2 (open_clip, tag ``dfndr2b``), template
  "A photo of {prompt}";
* ``open_clip:MODEL:PRETRAINED``: any open_clip model; PRETRAINED is a tag found in the local
  cache or a path to a weights file;
* ``test-brightness``, ``test-colour``, ``test-constant``: deterministic, dependency-free
  scorers for tests and demos.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Sequence
from typing import Protocol, runtime_checkable

import numpy as np


class ScorerUnavailableError(RuntimeError):
    """The scorer cannot be loaded here; the message says how to make it available."""


@runtime_checkable
class TextImageScorer(Protocol):
    """Batched text-image similarity."""

    @property
    def name(self) -> str:
        """Registry name that re-creates this scorer (used by sweep worker processes)."""
        ...

    def score(self, images: Sequence[np.ndarray], text: str) -> np.ndarray:
        """One float score per (H, W, 3) uint8 image for ``text`` (the raw prompt)."""
        ...


ScorerFactory = Callable[[str], TextImageScorer]
_FACTORIES: dict[str, ScorerFactory] = {}
_PREFIX_FACTORIES: dict[str, ScorerFactory] = {}


def register_scorer(name: str, factory: ScorerFactory, *, prefix: bool = False) -> None:
    """Register ``factory(name) -> scorer`` for ``name`` (or for every ``name:...`` if prefix)."""
    (_PREFIX_FACTORIES if prefix else _FACTORIES)[name] = factory


def factory_for(name: str) -> ScorerFactory | None:
    """The factory registered for ``name`` (or for its ``prefix:`` family); None if none."""
    factory = _FACTORIES.get(name)
    if factory is None and ":" in name:
        factory = _PREFIX_FACTORIES.get(name.split(":", 1)[0])
    return factory


def registered_names() -> list[str]:
    """Registered names so far (prefix families shown as ``prefix:...``)."""
    return sorted(_FACTORIES) + sorted(f"{p}:..." for p in _PREFIX_FACTORIES)


# ----------------------------------------------------------------------------- test scorers


def _luminance(image: np.ndarray) -> float:
    rgb = np.asarray(image, dtype=np.float64)[..., :3]
    return float((rgb @ np.array([0.2126, 0.7152, 0.0722])).mean())


class BrightnessScorer:
    """Mean Rec.709 luminance in 0..100; ignores the text. Deterministic."""

    name = "test-brightness"

    def score(self, images: Sequence[np.ndarray], text: str) -> np.ndarray:
        return np.array([_luminance(img) / 255.0 * 100.0 for img in images], dtype=np.float64)


def text_colour(text: str) -> np.ndarray:
    """A deterministic RGB target (0..255) derived from the SHA-256 of ``text``."""
    digest = hashlib.sha256(text.encode("utf-8")).digest()
    return np.array(list(digest[:3]), dtype=np.float64)


class ColourScorer:
    """100 minus the mean distance of the image's mean colour to a colour hashed from the text."""

    name = "test-colour"

    def score(self, images: Sequence[np.ndarray], text: str) -> np.ndarray:
        target = text_colour(text)
        out = []
        for img in images:
            mean = np.asarray(img, dtype=np.float64)[..., :3].reshape(-1, 3).mean(axis=0)
            out.append(100.0 - float(np.abs(mean - target).mean()) / 2.55)
        return np.array(out, dtype=np.float64)


class ConstantScorer:
    """Always 50: every candidate ties (exercises earliest-wins tie breaking)."""

    name = "test-constant"

    def score(self, images: Sequence[np.ndarray], text: str) -> np.ndarray:
        return np.full(len(images), 50.0)


register_scorer("test-brightness", lambda name: BrightnessScorer())
register_scorer("test-colour", lambda name: ColourScorer())
register_scorer("test-constant", lambda name: ConstantScorer())
