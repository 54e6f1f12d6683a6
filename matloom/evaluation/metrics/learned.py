"""What the learned text-image metrics (CLIPScore, BLIPScore, VQAScore) share.

Weights are only read locally: a folder or file path, or a Hugging Face repo id already in the
local cache (``HF_HOME``/``~/.cache/huggingface``). ``HF_HUB_OFFLINE=1`` and
``TRANSFORMERS_OFFLINE=1`` are set (unless the user set them) before the heavy imports, so a
missing model fails at once with instructions instead of trying a download.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from matloom.evaluation.metrics.base import MetricUnavailableError, Sample

#: Image layouts scored by default: the quick preview and the paper's two Blender layouts.
DEFAULT_LAYOUTS = ("quick", "flat", "staged")
#: How to install what these metrics import.
INSTALL_HINT = (
    "install the metrics extra: pip install 'matloom[metrics]' (or make metrics-venv: "
    "torch, open_clip_torch, transformers)"
)


def set_offline() -> None:
    """Forbid hub downloads in this process unless the user chose otherwise."""
    os.environ.setdefault("HF_HUB_OFFLINE", "1")
    os.environ.setdefault("TRANSFORMERS_OFFLINE", "1")


def import_torch_transformers() -> tuple[Any, Any]:
    """``(torch, transformers)``, offline, or :class:`MetricUnavailableError` saying how."""
    set_offline()
    try:
        import torch
        import transformers
    except ImportError as err:
        raise MetricUnavailableError(f"{err}; {INSTALL_HINT}") from None
    return torch, transformers


@contextmanager
def quiet_loading(transformers: Any) -> Iterator[None]:
    """Silence transformers' per-tensor load reports and progress bars, then restore them."""
    log = transformers.utils.logging
    level, bars = log.get_verbosity(), log.is_progress_bar_enabled()
    log.set_verbosity_error()
    log.disable_progress_bar()
    try:
        yield
    finally:
        log.set_verbosity(level)
        if bars:
            log.enable_progress_bar()


def pick_device(torch: Any, device: str | None) -> str:
    """The device asked for, else CUDA when present, else the CPU."""
    return device or ("cuda" if torch.cuda.is_available() else "cpu")


def download_hint(repo: str, what: str) -> str:
    """How to put ``repo`` into the local cache (or a folder) on a machine with internet access."""
    return (
        f"the {what} weights ({repo}) are not on this machine. On a machine with internet "
        f"access run:\n  huggingface-cli download {repo}\n(or: hf download {repo}), then copy "
        "~/.cache/huggingface/hub (or set HF_HOME) to this machine, or download into a folder "
        f"(--local-dir DIR) and pass that folder instead of {repo}."
    )


def resolve_local(source: str, what: str) -> Path:
    """A local folder/file for ``source``: an existing path, or a repo id in the local cache."""
    path = Path(source).expanduser()
    if path.exists():
        return path
    looks_like_repo = source.count("/") == 1 and not source.startswith((".", "/", "~"))
    if not looks_like_repo:
        raise MetricUnavailableError(f"{what}: no such file or folder: {source}")
    set_offline()
    try:
        from huggingface_hub import snapshot_download
    except ImportError as err:
        raise MetricUnavailableError(f"{err}; {INSTALL_HINT}") from None
    try:
        return Path(snapshot_download(source, local_files_only=True))
    except Exception:  # noqa: BLE001 - the hub raises several kinds; all mean "not cached"
        raise MetricUnavailableError(download_hint(source, what)) from None


def load_rgb(path: Path) -> Any:
    """The image at ``path`` as a PIL RGB image (alpha dropped)."""
    from PIL import Image

    try:
        with Image.open(path) as img:
            return img.convert("RGB")
    except (OSError, ValueError) as err:
        raise MetricUnavailableError(f"cannot read image {path}: {err}") from None


def score_layouts(
    samples: Sequence[Sample],
    layouts: Sequence[str],
    prefix: str,
    score_batch: Callable[[list[Any], list[str]], Sequence[float]],
    batch: int,
) -> list[dict[str, float]]:
    """Per sample ``{prefix.layout: score}`` for each layout it has an image of.

    ``score_batch(images, texts)`` scores equal-length lists of PIL images and prompts."""
    out: list[dict[str, float]] = [{} for _ in samples]
    pairs = list(_pairs(samples, layouts))
    for start in range(0, len(pairs), batch):
        chunk = pairs[start : start + batch]
        images = [load_rgb(path) for _, _, path, _ in chunk]
        scores = score_batch(images, [text for _, _, _, text in chunk])
        for (index, layout, _, _), value in zip(chunk, scores, strict=True):
            out[index][f"{prefix}.{layout}"] = float(value)
    return out


def _pairs(
    samples: Sequence[Sample], layouts: Sequence[str]
) -> Iterator[tuple[int, str, Path, str]]:
    for index, sample in enumerate(samples):
        for layout in layouts:
            path = sample.images.get(layout)
            if path is not None:
                yield index, layout, Path(path), sample.prompt


def layouts_option(options: Mapping[str, Any]) -> tuple[str, ...]:
    """The ``layouts`` option (a sequence or a comma-separated string), else the defaults."""
    value = options.get("layouts", DEFAULT_LAYOUTS)
    if isinstance(value, str):
        value = [part.strip() for part in value.split(",") if part.strip()]
    return tuple(value)


def to_scores(values: Any) -> np.ndarray:
    """A float64 array on [0, 100] from a tensor of probabilities or similarities in [0, 1]."""
    return np.clip(np.asarray(values, dtype=np.float64), 0.0, 1.0) * 100.0
