"""BLIPScore: BLIP-2 image-text matching (ITM) through ``transformers``, as the paper reports it.

score = 100 * softmax(ITM logits)[match] on [0, 100]: the Q-Former attends over the image and
the prompt together and its ITM head classifies the pair as match / no match. This is LAVIS'
``blip2`` ``pretrain`` ITM model (t2v_metrics' ``blip2-itm``) whose Hugging Face port is
``Salesforce/blip2-itm-vit-g`` (``Blip2ForImageTextRetrieval`` + ``Blip2Processor``); the
prompt is tokenised to at most 35 tokens as LAVIS/t2v_metrics do (longer prompts are cut).

Names: ``blip`` (the default repo) or ``blip:SOURCE`` with SOURCE a folder holding a saved
model and processor (``save_pretrained``/``huggingface-cli download --local-dir``) or a repo
id already in the local Hugging Face cache. Nothing is downloaded.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from matloom.evaluation.metrics.base import MetricUnavailableError, Sample, register_metric
from matloom.evaluation.metrics.learned import (
    DEFAULT_LAYOUTS,
    import_torch_transformers,
    layouts_option,
    pick_device,
    quiet_loading,
    resolve_local,
    score_layouts,
    to_scores,
)

FAMILY = "blip"
DEFAULT_SOURCE = "Salesforce/blip2-itm-vit-g"
#: LAVIS' and t2v_metrics' text length for the ITM pass.
MAX_TEXT_TOKENS = 35
#: Image-text pairs per forward pass.
BATCH = 16


class BlipScore:
    """BLIP-2 ITM match probability of each sample's images and its prompt."""

    def __init__(
        self,
        source: str = DEFAULT_SOURCE,
        *,
        layouts: Sequence[str] = DEFAULT_LAYOUTS,
        device: str | None = None,
        prefix: str = FAMILY,
    ) -> None:
        torch, transformers = import_torch_transformers()
        path = resolve_local(source, "BLIPScore (BLIP-2 ITM)")
        self._torch = torch
        self.device = pick_device(torch, device)
        dtype = torch.float16 if self.device.startswith("cuda") else torch.float32
        try:
            with quiet_loading(transformers):
                self._processor = transformers.Blip2Processor.from_pretrained(
                    path, local_files_only=True
                )
                net = transformers.Blip2ForImageTextRetrieval.from_pretrained(
                    path, local_files_only=True, dtype=dtype
                )
        except (OSError, ValueError) as err:
            raise MetricUnavailableError(
                f"BLIPScore: cannot load a BLIP-2 ITM model from {path}: {err}"
            ) from None
        self._model = net.to(self.device).eval()
        self._dtype = dtype
        self.source = source
        self._layouts = tuple(layouts)
        self._prefix = prefix

    @property
    def name(self) -> str:
        return FAMILY if self.source == DEFAULT_SOURCE else f"{FAMILY}:{self.source}"

    @property
    def layouts(self) -> tuple[str, ...]:
        return self._layouts

    def score_images(self, images: Sequence[Any], texts: Sequence[str]) -> np.ndarray:
        """100 * P(match) of each PIL image with the text at the same index."""
        if not images:
            return np.zeros(0)
        torch = self._torch
        pixels = self._processor.image_processor(list(images), return_tensors="pt")
        tokens = self._processor.tokenizer(
            list(texts),
            padding="max_length",
            truncation=True,
            max_length=MAX_TEXT_TOKENS,
            return_tensors="pt",
        )
        with torch.no_grad():
            out = self._model(
                pixel_values=pixels["pixel_values"].to(self.device, self._dtype),
                input_ids=tokens["input_ids"].to(self.device),
                attention_mask=tokens["attention_mask"].to(self.device),
                use_image_text_matching_head=True,
            )
            probs = torch.softmax(out.logits_per_image.float(), dim=1)[:, 1]
        return to_scores(probs.cpu().numpy())

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        return score_layouts(samples, self._layouts, self._prefix, self.score_images, BATCH)


def make_blip_score(name: str, options: Mapping[str, Any]) -> BlipScore:
    """``blip`` or ``blip:SOURCE`` (options: ``layouts``, ``device``, ``prefix``)."""
    source = name.split(":", 1)[1] if ":" in name else DEFAULT_SOURCE
    if not source:
        raise MetricUnavailableError(f"bad metric name {name!r}; use blip or blip:FOLDER_OR_REPO")
    return BlipScore(
        source,
        layouts=layouts_option(options),
        device=options.get("device"),
        prefix=str(options.get("prefix", FAMILY)),
    )


register_metric(FAMILY, make_blip_score)
