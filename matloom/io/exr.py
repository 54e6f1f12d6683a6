"""float32 OpenEXR writing and reading through the OpenEXR 3.x Python bindings.

Maps are stored losslessly as 32-bit float (ZIP compression): one channel ``Y`` for a (H, W)
map, or ``R``, ``G``, ``B`` for a (H, W, 3) map. NaN and +-inf are kept as they are.

Note: do not route ``.exr`` through imageio, which silently writes TIFF data under an ``.exr``
name; and OpenCV needs an environment variable to enable EXR at all.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import OpenEXR

from matloom.io.atomic import atomic_write_with

#: Header used for every file: scanline image, lossless ZIP compression.
_HEADER = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}


def _channels_for(values: np.ndarray) -> dict[str, np.ndarray]:
    """OpenEXR channel dict for a (H, W) or (H, W, 3) float32 array."""
    if values.ndim == 2:
        return {"Y": values}
    if values.ndim == 3 and values.shape[2] == 3:
        return {"RGB": values}
    raise ValueError(f"EXR maps must be (H, W) or (H, W, 3), got {values.shape}")


def write_exr(path: str | os.PathLike[str], values: np.ndarray) -> Path:
    """Write a (H, W) or (H, W, 3) map as a float32 EXR (atomically: temp file + rename)."""
    pixels = np.ascontiguousarray(values, dtype=np.float32)
    channels = _channels_for(pixels)

    def write(temp: Path) -> None:
        with OpenEXR.File(dict(_HEADER), channels) as exr_file:
            exr_file.write(os.fspath(temp))

    return atomic_write_with(path, write)


def read_exr(path: str | os.PathLike[str]) -> np.ndarray:
    """Read an EXR written by :func:`write_exr`: (H, W) for ``Y``, (H, W, 3) for RGB.

    Any other single channel is returned as (H, W); other layouts raise ValueError.
    """
    with OpenEXR.File(os.fspath(path)) as exr_file:
        channels = exr_file.channels()
        if "RGB" in channels:
            return np.array(channels["RGB"].pixels, dtype=np.float32)
        if len(channels) == 1:
            (channel,) = channels.values()
            return np.array(channel.pixels, dtype=np.float32)
    raise ValueError(f"{path}: unsupported EXR channel layout {sorted(channels)}")
