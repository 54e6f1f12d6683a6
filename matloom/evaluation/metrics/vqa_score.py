"""VQAScore (Lin et al. 2024) with CLIP-FlanT5, rebuilt from ``transformers`` parts.

The paper scores with t2v_metrics' ``clip-flant5-xxl``; t2v_metrics itself pins torch 2.5.1,
transformers 4.49 and numpy 1.26, which do not install beside this project's pins, so the model
is assembled here from the same pieces t2v_metrics' ``CLIPT5ForConditionalGeneration`` holds,
reading the same checkpoint:

* the vision tower: ``CLIPVisionModel`` (``mm_vision_tower`` in the checkpoint's config,
  ``openai/clip-vit-large-patch14-336``), features of layer ``mm_vision_select_layer`` (-2)
  without the CLS token (``patch``); the checkpoint's ``vision_tower.vision_tower.*`` tensors
  replace the tower's when present, as ``from_pretrained`` does there;
* the projector ``mm_projector`` (``mlp2x_gelu``: Linear, GELU, Linear), from the checkpoint;
* the language model: ``T5ForConditionalGeneration`` with the checkpoint's T5 tensors; the
  tokenizer from ``google/flan-t5-xxl`` (or the checkpoint folder when it has one);
* the input: ``SYSTEM_MSG + " USER: <image>\\n" + question + " ASSISTANT: "`` with question
  ``Does this figure show "{prompt}"? Please answer yes or no.``; each text chunk is tokenised
  on its own (so ``</s>`` ends the chunk before the image, as there) and the projected image
  patches replace ``<image>``; images are padded to a square with the processor's mean colour;
* the score: the answer ``Yes`` tokenised with ``</s>`` as labels, ``exp(-mean cross-entropy)``
  over the full vocabulary, i.e. the geometric mean of P("Yes") and P(``</s>`` | "Yes"),
  times 100. bfloat16 on CUDA as there; float32 on the CPU.

What differs: no t2v_metrics code runs (a checkpoint whose tensors are laid out otherwise fails
with a clear error), and batches are scored with right-padded inputs (masked, as there).

Names: ``vqa`` (``zhiqiulin/clip-flant5-xxl`` from the local cache) or ``vqa:SOURCE`` (a
folder or a cached repo id such as ``zhiqiulin/clip-flant5-xl``); options ``tokenizer`` and
``vision_tower`` override where those come from.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path
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
)

FAMILY = "vqa"
DEFAULT_SOURCE = "zhiqiulin/clip-flant5-xxl"
#: Tokenizers t2v_metrics pairs with its checkpoints (the checkpoints ship none).
TOKENIZERS = {
    "zhiqiulin/clip-flant5-xxl": "google/flan-t5-xxl",
    "zhiqiulin/clip-flant5-xl": "google/flan-t5-xl",
}
SYSTEM_MSG = (
    "A chat between a curious user and an artificial intelligence assistant. The assistant "
    "gives helpful, detailed, and polite answers to the user's questions."
)
QUESTION = 'Does this figure show "{}"? Please answer yes or no.'
ANSWER = "Yes"
IMAGE_TOKEN = "<image>"
PROJECTOR_PREFIX = "mm_projector."
VISION_PREFIX = "vision_tower.vision_tower."
CLIP_PREFIX = "vision_model."
#: Image-text pairs per forward pass.
BATCH = 8


def format_question(prompt: str) -> str:
    """The t5_chat conversation CLIP-FlanT5 was tuned on, around the VQAScore question."""
    return f"{SYSTEM_MSG} USER: {IMAGE_TOKEN}\n{QUESTION.format(prompt)} ASSISTANT: "


class VqaScore:
    """100 * P("Yes" | image, question about the prompt) from CLIP-FlanT5."""

    def __init__(
        self,
        source: str = DEFAULT_SOURCE,
        *,
        tokenizer: str | None = None,
        vision_tower: str | None = None,
        layouts: Sequence[str] = DEFAULT_LAYOUTS,
        device: str | None = None,
        prefix: str = FAMILY,
    ) -> None:
        torch, transformers = import_torch_transformers()
        self._torch = torch
        self.source = source
        self.device = pick_device(torch, device)
        self._dtype = torch.bfloat16 if self.device.startswith("cuda") else torch.float32
        path = resolve_local(source, "VQAScore (CLIP-FlanT5)")
        config = _read_config(path)
        tensors = _extra_tensors(torch, path, (PROJECTOR_PREFIX, VISION_PREFIX))
        try:
            with quiet_loading(transformers):
                self._load(transformers, path, config, tensors, tokenizer, vision_tower)
        except MetricUnavailableError:
            raise
        except (OSError, ValueError, KeyError, RuntimeError) as err:
            raise MetricUnavailableError(
                f"VQAScore: cannot load a CLIP-FlanT5 model from {path}: {err}"
            ) from None
        self._layouts = tuple(layouts)
        self._prefix = prefix

    def _load(
        self,
        transformers: Any,
        path: Path,
        config: dict[str, Any],
        tensors: dict[str, Any],
        tokenizer: str | None,
        vision_tower: str | None,
    ) -> None:
        torch = self._torch
        t5_config = transformers.T5Config.from_dict(
            {k: v for k, v in config.items() if k not in ("model_type", "architectures")}
        )
        self._t5 = transformers.T5ForConditionalGeneration.from_pretrained(
            path, config=t5_config, local_files_only=True, dtype=self._dtype
        )
        vpath = resolve_local(vision_tower or config["mm_vision_tower"], "CLIP vision tower")
        self._image_processor = transformers.CLIPImageProcessor.from_pretrained(
            vpath, local_files_only=True
        )
        self._vision = transformers.CLIPVisionModel.from_pretrained(
            vpath, local_files_only=True, dtype=self._dtype
        )
        vision_state = _match_prefix(_strip(tensors, VISION_PREFIX), self._vision.state_dict())
        if vision_state:
            self._vision.load_state_dict(vision_state, strict=True)
        self._projector = _build_projector(torch, config)
        self._projector.load_state_dict(_strip(tensors, PROJECTOR_PREFIX), strict=True)
        self._projector.to(self._dtype)
        self._select_layer = int(config.get("mm_vision_select_layer", -2))
        self._select = str(config.get("mm_vision_select_feature", "patch"))
        if self._select not in ("patch", "cls_patch"):
            raise ValueError(f"unknown mm_vision_select_feature {self._select!r}")
        tpath = tokenizer or _default_tokenizer(path, self.source)
        self._tokenizer = transformers.AutoTokenizer.from_pretrained(
            resolve_local(tpath, "Flan-T5 tokenizer"), local_files_only=True
        )
        for module in (self._t5, self._vision, self._projector):
            module.to(self.device).eval()

    @property
    def name(self) -> str:
        return FAMILY if self.source == DEFAULT_SOURCE else f"{FAMILY}:{self.source}"

    @property
    def layouts(self) -> tuple[str, ...]:
        return self._layouts

    def _encode_images(self, images: Sequence[Any]) -> Any:
        mean = tuple(int(x * 255) for x in self._image_processor.image_mean)
        square = [_expand_to_square(img, mean) for img in images]
        pixels = self._image_processor(square, return_tensors="pt")["pixel_values"]
        hidden = self._vision(
            pixels.to(self.device, self._dtype), output_hidden_states=True
        ).hidden_states[self._select_layer]
        if self._select == "patch":
            hidden = hidden[:, 1:]
        return self._projector(hidden)

    def _input_embeds(self, texts: Sequence[str], image_features: Any) -> tuple[Any, Any]:
        torch = self._torch
        embed = self._t5.get_input_embeddings()
        rows = []
        for text, features in zip(texts, image_features, strict=True):
            before, after = format_question(text).split(IMAGE_TOKEN)
            ids = [self._ids(before), self._ids(after)]
            rows.append(torch.cat([embed(ids[0]), features, embed(ids[1])], dim=0))
        length = max(row.shape[0] for row in rows)
        width = rows[0].shape[1]
        batch = torch.zeros(len(rows), length, width, dtype=rows[0].dtype, device=self.device)
        mask = torch.zeros(len(rows), length, dtype=torch.long, device=self.device)
        for i, row in enumerate(rows):
            batch[i, : row.shape[0]] = row
            mask[i, : row.shape[0]] = 1
        return batch, mask

    def _ids(self, text: str) -> Any:
        ids = self._tokenizer(text).input_ids
        return self._torch.tensor(ids, dtype=self._torch.long, device=self.device)

    def score_images(self, images: Sequence[Any], texts: Sequence[str]) -> np.ndarray:
        """100 * P("Yes") of each PIL image with the text at the same index."""
        if not images:
            return np.zeros(0)
        torch = self._torch
        with torch.no_grad():
            embeds, mask = self._input_embeds(texts, self._encode_images(images))
            labels = self._ids(ANSWER).unsqueeze(0).repeat(len(images), 1)
            logits = self._t5(inputs_embeds=embeds, attention_mask=mask, labels=labels).logits
            logp = torch.log_softmax(logits.float(), dim=-1)
            token_logp = logp.gather(-1, labels.unsqueeze(-1)).squeeze(-1)
            probs = token_logp.mean(dim=1).exp()
        return probs.cpu().numpy().astype(np.float64) * 100.0

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        return score_layouts(samples, self._layouts, self._prefix, self.score_images, BATCH)


def _read_config(path: Path) -> dict[str, Any]:
    file = path / "config.json"
    try:
        config = json.loads(file.read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        raise MetricUnavailableError(f"VQAScore: no CLIP-FlanT5 config at {file}: {err}") from None
    missing = [k for k in ("mm_vision_tower", "mm_hidden_size", "d_model") if k not in config]
    if missing:
        raise MetricUnavailableError(
            f"VQAScore: {file} is not a CLIP-FlanT5 config (missing {', '.join(missing)})"
        )
    return config


def _default_tokenizer(path: Path, source: str) -> str:
    if (path / "tokenizer_config.json").is_file():
        return str(path)
    if source in TOKENIZERS:
        return TOKENIZERS[source]
    raise MetricUnavailableError(
        f"VQAScore: {path} holds no tokenizer; pass the option tokenizer=FOLDER_OR_REPO "
        "(google/flan-t5-xxl for the CLIP-FlanT5 checkpoints)"
    )


def _weight_files(path: Path) -> list[Path]:
    for index_name in ("model.safetensors.index.json", "pytorch_model.bin.index.json"):
        index = path / index_name
        if index.is_file():
            weight_map = json.loads(index.read_text(encoding="utf-8"))["weight_map"]
            names = {
                file
                for key, file in weight_map.items()
                if key.startswith((PROJECTOR_PREFIX, VISION_PREFIX))
            }
            return [path / name for name in sorted(names)]
    for single in ("model.safetensors", "pytorch_model.bin"):
        if (path / single).is_file():
            return [path / single]
    raise MetricUnavailableError(f"VQAScore: no model weights in {path}")


def _extra_tensors(torch: Any, path: Path, prefixes: tuple[str, ...]) -> dict[str, Any]:
    """The checkpoint's projector and vision-tower tensors (only the shards holding them)."""
    out: dict[str, Any] = {}
    for file in _weight_files(path):
        if file.suffix == ".safetensors":
            from safetensors import safe_open

            with safe_open(str(file), framework="pt") as handle:
                for key in handle.keys():  # noqa: SIM118 - safe_open is not a mapping
                    if key.startswith(prefixes):
                        out[key] = handle.get_tensor(key)
        else:
            state = torch.load(file, map_location="cpu", weights_only=True, mmap=True)
            out.update({k: v for k, v in state.items() if k.startswith(prefixes)})
    if not any(key.startswith(PROJECTOR_PREFIX) for key in out):
        raise MetricUnavailableError(f"VQAScore: no {PROJECTOR_PREFIX}* tensors in {path}")
    return out


def _strip(tensors: Mapping[str, Any], prefix: str) -> dict[str, Any]:
    return {k[len(prefix) :]: v for k, v in tensors.items() if k.startswith(prefix)}


def _match_prefix(state: dict[str, Any], target: Mapping[str, Any]) -> dict[str, Any]:
    """``state`` with the ``vision_model.`` prefix added or removed to match ``target``'s keys.

    The checkpoint was saved by transformers 4 (``vision_model.embeddings...``); transformers 5
    names the same tensors without the prefix."""
    ours = any(k.startswith(CLIP_PREFIX) for k in target)
    theirs = any(k.startswith(CLIP_PREFIX) for k in state)
    if theirs and not ours:
        return {k.removeprefix(CLIP_PREFIX): v for k, v in state.items()}
    if ours and not theirs:
        return {CLIP_PREFIX + k: v for k, v in state.items()}
    return state


def _build_projector(torch: Any, config: Mapping[str, Any]) -> Any:
    """LLaVA's projector: ``linear`` or ``mlp{N}x_gelu`` from mm_hidden_size to d_model."""
    kind = str(config.get("mm_projector_type", "linear"))
    width, out = int(config["mm_hidden_size"]), int(config["d_model"])
    if kind == "linear":
        return torch.nn.Sequential(torch.nn.Linear(width, out))
    if kind.startswith("mlp") and kind.endswith("x_gelu") and kind[3:-6].isdigit():
        layers: list[Any] = [torch.nn.Linear(width, out)]
        for _ in range(1, int(kind[3:-6])):
            layers += [torch.nn.GELU(), torch.nn.Linear(out, out)]
        return torch.nn.Sequential(*layers)
    raise ValueError(f"unknown mm_projector_type {kind!r}")


def _expand_to_square(img: Any, colour: tuple[int, ...]) -> Any:
    from PIL import Image

    width, height = img.size
    if width == height:
        return img
    side = max(width, height)
    canvas = Image.new(img.mode, (side, side), colour)
    canvas.paste(img, ((side - width) // 2, (side - height) // 2))
    return canvas


def make_vqa_score(name: str, options: Mapping[str, Any]) -> VqaScore:
    """``vqa`` or ``vqa:SOURCE`` (options: tokenizer, vision_tower, layouts, device, prefix)."""
    source = name.split(":", 1)[1] if ":" in name else DEFAULT_SOURCE
    if not source:
        raise MetricUnavailableError(f"bad metric name {name!r}; use vqa or vqa:FOLDER_OR_REPO")
    return VqaScore(
        source,
        tokenizer=options.get("tokenizer"),
        vision_tower=options.get("vision_tower"),
        layouts=layouts_option(options),
        device=options.get("device"),
        prefix=str(options.get("prefix", FAMILY)),
    )


register_metric(FAMILY, make_vqa_score)
