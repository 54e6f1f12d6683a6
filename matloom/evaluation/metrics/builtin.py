"""Imports every built-in metric module so each registers its family (see :mod:`.base`).
Modules whose heavy imports (torch, transformers) are missing still register: their factory
raises :class:`~matloom.evaluation.metrics.base.MetricUnavailableError` when called."""

from __future__ import annotations

import matloom.evaluation.metrics.blip_score  # noqa: F401  BLIPScore (transformers)
import matloom.evaluation.metrics.clip_score  # noqa: F401  CLIPScore (open_clip)
import matloom.evaluation.metrics.judge  # noqa: F401  the MLLM judge (OpenAI-compatible)
import matloom.evaluation.metrics.material  # noqa: F401  seams, pbr, relight, size, authoring
import matloom.evaluation.metrics.vqa_score  # noqa: F401  VQAScore (CLIP-FlanT5)
