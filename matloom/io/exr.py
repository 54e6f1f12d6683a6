"""OpenEXR writing and reading through the OpenEXR 3.x Python bindings.

Maps are stored as 32-bit float (lossless, the default) or 16-bit half float
(``precision="half"``), ZIP compression: one channel ``Y`` for a (H, W) map, ``R``, ``G``,
``B`` for a (H, W, 3) map and ``R``, ``G``, ``B``, ``A`` for a (H, W, 4) map. NaN and +-inf are
kept as they are (in half, finite values beyond 65504 become +-inf).

Note: do not route ``.exr`` through imageio, which silently writes TIFF data under an ``.exr``
name; and OpenCV needs an environment variable to enable EXR at all.
"""

from __future__ import annotations

import errno
import io
import os
from pathlib import Path

import numpy as np
import OpenEXR

from matloom.io.atomic import atomic_write_bytes, atomic_write_with

#: Header used for every file: scanline image, lossless ZIP compression.
_HEADER = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}


def _channels_for(values: np.ndarray) -> dict[str, np.ndarray]:
    """OpenEXR channel dict for a (H, W), (H, W, 3) or (H, W, 4) array."""
    if values.ndim == 2:
        return {"Y": values}
    if values.ndim == 3 and values.shape[2] == 3:
        return {"RGB": values}
    if values.ndim == 3 and values.shape[2] == 4:
        return {"RGBA": values}
    raise ValueError(f"EXR maps must be (H, W), (H, W, 3) or (H, W, 4), got {values.shape}")


#: ``precision`` values of :func:`write_exr` and their sample types.
PRECISIONS: dict[str, type] = {"float": np.float32, "half": np.float16}


def write_exr(path: str | os.PathLike[str], values: np.ndarray, precision: str = "float") -> Path:
    """Write a (H, W), (H, W, 3) or (H, W, 4) map as a float32 (``"float"``) or half
    (``"half"``) EXR, atomically (temp file + rename).

    The library encodes into memory and :func:`~matloom.io.atomic.atomic_write_bytes` writes
    the bytes, so a failing write (a full disk) raises OSError like every other file MatLoom
    writes: the library's own file writes report it as a RuntimeError, or not at all when the
    failure comes at close (a truncated file)."""
    if precision not in PRECISIONS:
        raise ValueError(f"EXR precision must be one of {sorted(PRECISIONS)}, got {precision!r}")
    with np.errstate(over="ignore", invalid="ignore"):
        pixels = np.ascontiguousarray(values, dtype=PRECISIONS[precision])
    stream = io.BytesIO()
    with OpenEXR.File(dict(_HEADER), _channels_for(pixels)) as exr_file:
        try:
            exr_file.write(stream)
        except TypeError:  # bindings that write only to a file name (no streams)
            return atomic_write_with(path, lambda temp: _write_named(exr_file, temp))
    return atomic_write_bytes(path, stream.getvalue())


def _write_named(exr_file: OpenEXR.File, temp: Path) -> None:
    """The library writing ``temp`` itself; its write errors become OSError."""
    try:
        exr_file.write(os.fspath(temp))
    except RuntimeError as err:
        raise OSError(errno.EIO, f"the EXR could not be written ({err})") from None


def read_exr(path: str | os.PathLike[str]) -> np.ndarray:
    """Read an EXR written by :func:`write_exr`: (H, W) for ``Y``, (H, W, 3) for RGB.

    Any other single channel is returned as (H, W); other layouts raise ValueError.
    """
    with OpenEXR.File(os.fspath(path)) as exr_file:
        channels = exr_file.channels()
        for name in ("RGBA", "RGB"):
            if name in channels:
                return np.array(channels[name].pixels, dtype=np.float32)
        if len(channels) == 1:
            (channel,) = channels.values()
            return np.array(channel.pixels, dtype=np.float32)
    raise ValueError(f"{path}: unsupported EXR channel layout {sorted(channels)}")
