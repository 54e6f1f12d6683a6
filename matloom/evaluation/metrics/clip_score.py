"""CLIPScore (Hessel et al. 2021) through open_clip, as the paper reports it.

score = max(100 * cos(E_image, E_text), 0) on [0, 100], text = the raw prompt (no template;
open_clip's tokenizer truncates it to the model's 77 tokens), as torchmetrics' ``CLIPScore``
computes it. The paper used torchmetrics' default ``openai/clip-vit-large-patch14``, which is
open_clip's ``ViT-L-14`` with the ``openai`` weights: the default here.

Names: ``clip`` (the default) or ``clip:MODEL:WEIGHTS`` with MODEL an open_clip model name and
WEIGHTS a weights file (``.safetensors``/``.bin``/``.pt`` state dict) or a pretrained tag
already in the local Hugging Face cache. Loading reuses the author's open_clip scorer
(:mod:`matloom.author.scorers.openclip`), offline.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from matloom.author.scorers.base import ScorerUnavailableError
from matloom.evaluation.metrics.base import MetricUnavailableError, Sample, register_metric
from matloom.evaluation.metrics.learned import INSTALL_HINT, layouts_option, score_layouts

FAMILY = "clip"
DEFAULT_MODEL = "ViT-L-14"
DEFAULT_WEIGHTS = "openai"
#: Images per forward pass.
BATCH = 32
#: A WEIGHTS part ending so (or holding a path separator) is a file, not a pretrained tag.
WEIGHT_SUFFIXES = (".safetensors", ".bin", ".pt", ".pth")


def weights_hint(model: str, weights: str) -> str:
    """How to make open_clip weights available on a machine without a hub connection."""
    return (
        f"CLIPScore: the weights of {model} ({weights}) are not in the local cache. On a "
        "machine with internet access run:\n"
        f'  HF_HUB_OFFLINE=0 python -c "import open_clip; '
        f"open_clip.create_model_and_transforms('{model}', pretrained='{weights}')\"\n"
        "then copy ~/.cache/huggingface/hub (or set HF_HOME) to this machine, or pass a "
        f"weights file: clip:{model}:/path/to/open_clip_model.safetensors"
    )


class ClipScore:
    """CLIPScore of each sample's images against its prompt."""

    def __init__(
        self,
        model: str = DEFAULT_MODEL,
        weights: str = DEFAULT_WEIGHTS,
        *,
        layouts: Sequence[str] = ("quick", "flat", "staged"),
        device: str | None = None,
        prefix: str = FAMILY,
    ) -> None:
        from matloom.author.scorers.openclip import OpenClipScorer

        is_path = os.path.sep in weights or weights.endswith(WEIGHT_SUFFIXES)
        if is_path and not Path(weights).expanduser().is_file():
            raise MetricUnavailableError(f"CLIPScore: no such weights file: {weights}")
        if not is_path:
            _check_cached(model, weights)
        try:
            self._scorer = OpenClipScorer(
                model,
                str(Path(weights).expanduser()) if is_path else weights,
                template="{prompt}",
                device=device,
            )
        except ScorerUnavailableError as err:
            text = str(err)
            if "not available" in text:
                raise MetricUnavailableError(
                    f"CLIPScore: {text.split(';')[0]}; {INSTALL_HINT}"
                ) from None
            if is_path:
                raise MetricUnavailableError(f"CLIPScore: {text}") from None
            raise MetricUnavailableError(weights_hint(model, weights)) from None
        self.model = model
        self.weights = weights
        self._layouts = tuple(layouts)
        self._prefix = prefix

    @property
    def name(self) -> str:
        if (self.model, self.weights) == (DEFAULT_MODEL, DEFAULT_WEIGHTS):
            return FAMILY
        return f"{FAMILY}:{self.model}:{self.weights}"

    @property
    def layouts(self) -> tuple[str, ...]:
        return self._layouts

    def score_images(self, images: Sequence[Any], texts: Sequence[str]) -> np.ndarray:
        """CLIPScore of each PIL image against the text at the same index."""
        out = np.zeros(len(images))
        for text in dict.fromkeys(texts):
            idx = [i for i, t in enumerate(texts) if t == text]
            arrays = [np.asarray(images[i].convert("RGB")) for i in idx]
            out[idx] = self._scorer.score(arrays, text)
        return out

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        return score_layouts(samples, self._layouts, self._prefix, self.score_images, BATCH)


def _check_cached(model: str, tag: str) -> None:
    """Fail fast, without the network and before building the model (long for large towers),
    when the weights of ``tag`` are not in the local Hugging Face cache."""
    from matloom.author.scorers.openclip import _import_open_clip

    try:
        open_clip, _ = _import_open_clip()
    except ScorerUnavailableError as err:
        raise MetricUnavailableError(
            f"CLIPScore: {str(err).split(';')[0]}; {INSTALL_HINT}"
        ) from None
    cfg = open_clip.get_pretrained_cfg(model, tag)
    if not cfg:
        known = ", ".join(open_clip.list_pretrained_tags_by_model(model)) or "none"
        raise MetricUnavailableError(
            f"CLIPScore: open_clip knows no weights {tag!r} for {model} (tags: {known}); "
            "pass a weights file instead: clip:MODEL:/path/to/weights.safetensors"
        )
    hub = cfg.get("hf_hub", "")
    if not hub:
        return  # an URL-only tag: open_clip's own (offline-guarded) loading reports it
    from huggingface_hub import try_to_load_from_cache

    repo, filename = os.path.split(hub)
    names = [open_clip.pretrained.HF_WEIGHTS_NAME] if not filename else [filename]
    names = [*open_clip.pretrained._get_safe_alternatives(names[0]), *names]
    if not any(isinstance(try_to_load_from_cache(repo, name), str) for name in names):
        raise MetricUnavailableError(weights_hint(model, tag))


def make_clip_score(name: str, options: Mapping[str, Any]) -> ClipScore:
    """``clip`` or ``clip:MODEL:WEIGHTS`` (options: ``layouts``, ``device``, ``prefix``)."""
    parts = name.split(":", 2)
    if len(parts) == 1:
        model, weights = DEFAULT_MODEL, DEFAULT_WEIGHTS
    elif len(parts) == 3 and parts[1] and parts[2]:
        model, weights = parts[1], parts[2]
    else:
        raise MetricUnavailableError(
            f"bad metric name {name!r}; use clip or clip:MODEL:WEIGHTS (a cached tag or a file)"
        )
    return ClipScore(
        model,
        weights,
        layouts=layouts_option(options),
        device=options.get("device"),
        prefix=str(options.get("prefix", FAMILY)),
    )


register_metric(FAMILY, make_clip_score)
