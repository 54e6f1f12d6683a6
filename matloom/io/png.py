"""PNG quantisation, writers (8-bit grey/RGB/RGBA, 16-bit grey) and a reader.

Quantisation reproduces the reference exporter byte for byte: clip to [0, 1], multiply by 255,
add 0.5 and truncate, all in float32 (round half up). Non-finite values never crash: +inf clips
to 255, -inf to 0, and NaN is written as **0** (the reference's float-to-uint8 cast of NaN is
undefined behaviour; 0 is what it produced on the fixture platform).

8-bit files are encoded here with numpy + zlib (the PNG container is a few fixed chunks; the
"Up" row filter is one vectorised subtraction), 16-bit grey with pypng (exact 16-bit samples,
big-endian as PNG requires). Pillow is not used for writing: importing it and initialising its
plugins costs ~30 ms, about 7 % of a whole ``matloom render --size 256`` process. Every writer
goes through :func:`matloom.io.atomic.atomic_write_bytes`.
"""

from __future__ import annotations

import io
import os
import struct
import zlib
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from matloom.io.atomic import atomic_write_bytes

#: zlib level for 8-bit PNGs: 1 (fastest), as OpenCV's default in the reference; the pixel
#: values never depend on it, only speed and file size (level 6 is ~25 % smaller, ~3x slower).
PNG_COMPRESS_LEVEL = 1
#: PNG colour types by number of channels (grey, RGB, RGBA).
_COLOUR_TYPES = {1: 0, 3: 2, 4: 6}
_SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Row filter "Up" (each byte minus the byte above, mod 256): smooth maps compress well.
_FILTER_UP = 2
#: Every PNG MatLoom writes says so in a standard ``tEXt`` chunk; this is how a later run knows
#: that an existing single file (``preview -o x.png``) is its own and may be replaced.
SOFTWARE_TEXT = b"Software\x00MatLoom"


def quantize_unit8(values: ArrayLike) -> np.ndarray:
    """Unit-range floats -> uint8: clip [0, 1], x255, +0.5, truncate (float32); NaN -> 0."""
    scaled = np.clip(np.asarray(values, dtype=np.float32), 0, 1)
    scaled *= np.float32(255)
    scaled += np.float32(0.5)
    np.copyto(scaled, 0, where=np.isnan(scaled))  # after clipping, NaN is the only non-finite
    return scaled.astype(np.uint8)


def quantize_unit16(values: ArrayLike) -> np.ndarray:
    """Unit-range floats -> uint16: clip [0, 1], x65535, +0.5, truncate (float64); NaN -> 0."""
    scaled = np.clip(np.asarray(values, dtype=np.float64), 0, 1)
    scaled *= 65535.0
    scaled += 0.5
    np.copyto(scaled, 0, where=np.isnan(scaled))
    return scaled.astype(np.uint16)


def _chunk(kind: bytes, data: bytes) -> bytes:
    """One PNG chunk: length, type, data, CRC-32 of type + data."""
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def encode_png8(pixels: np.ndarray, compress_level: int = PNG_COMPRESS_LEVEL) -> bytes:
    """Encode a uint8 array of shape (H, W), (H, W, 3) or (H, W, 4) as PNG bytes."""
    array = np.asarray(pixels)
    if array.dtype != np.uint8:
        raise TypeError(f"8-bit PNG needs uint8 pixels, got {array.dtype}")
    return encode_png(array, compress_level)


def encode_png(pixels: np.ndarray, compress_level: int = PNG_COMPRESS_LEVEL) -> bytes:
    """Encode a uint8 or uint16 array of shape (H, W), (H, W, 3) or (H, W, 4) as PNG bytes.

    16-bit samples are stored big-endian, as PNG requires; the "Up" filter subtracts the byte
    above, so it works the same on the byte rows of 16-bit images.
    """
    array = np.ascontiguousarray(pixels)
    if array.dtype not in (np.uint8, np.uint16):
        raise TypeError(f"PNG needs uint8 or uint16 pixels, got {array.dtype}")
    channels = 1 if array.ndim == 2 else array.shape[-1]
    if array.ndim not in (2, 3) or channels not in _COLOUR_TYPES:
        raise ValueError(f"PNG needs (H, W), (H, W, 3) or (H, W, 4), got {array.shape}")
    height, width = array.shape[:2]
    if height == 0 or width == 0:
        raise ValueError(f"PNG needs at least one pixel, got {array.shape}")
    depth = 8 * array.dtype.itemsize
    if depth == 16:
        array = array.astype(">u2")
    rows = array.view(np.uint8).reshape(height, width * channels * array.dtype.itemsize)
    filtered = np.empty((height, 1 + rows.shape[1]), np.uint8)
    filtered[:, 0] = _FILTER_UP
    filtered[0, 1:] = rows[0]
    np.subtract(rows[1:], rows[:-1], out=filtered[1:, 1:])  # uint8 arithmetic wraps mod 256
    header = struct.pack(">IIBBBBB", width, height, depth, _COLOUR_TYPES[channels], 0, 0, 0)
    return b"".join(
        (
            _SIGNATURE,
            _chunk(b"IHDR", header),
            _chunk(b"tEXt", SOFTWARE_TEXT),
            _chunk(b"IDAT", zlib.compress(filtered.tobytes(), compress_level)),
            _chunk(b"IEND", b""),
        )
    )


def encode_png16_grey(pixels: np.ndarray) -> bytes:
    """Encode a uint16 (H, W) array as a 16-bit greyscale PNG (pypng, exact samples)."""
    import png as pypng

    array = np.asarray(pixels)
    if array.dtype != np.uint16 or array.ndim != 2:
        raise ValueError(f"16-bit PNG needs a (H, W) uint16 array, got {array.dtype} {array.shape}")
    writer = pypng.Writer(width=array.shape[1], height=array.shape[0], greyscale=True, bitdepth=16)
    buffer = io.BytesIO()
    writer.write(buffer, array)
    data = buffer.getvalue()
    ihdr_end = len(_SIGNATURE) + 8 + 13 + 4  # signature + IHDR chunk (length, type, data, CRC)
    return data[:ihdr_end] + _chunk(b"tEXt", SOFTWARE_TEXT) + data[ihdr_end:]


def written_by_matloom(path: str | os.PathLike[str]) -> bool:
    """True when ``path`` is a PNG carrying MatLoom's ``Software`` text chunk before its pixels."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(1 << 16)
    except OSError:
        return False
    if not head.startswith(_SIGNATURE):
        return False
    offset = len(_SIGNATURE)
    while offset + 8 <= len(head):
        (length,) = struct.unpack(">I", head[offset : offset + 4])
        kind = head[offset + 4 : offset + 8]
        if kind in (b"IDAT", b"IEND"):
            return False
        if kind == b"tEXt" and head[offset + 8 : offset + 8 + length] == SOFTWARE_TEXT:
            return True
        offset += 12 + length
    return False


def write_grey8(path: str | os.PathLike[str], values: ArrayLike) -> Path:
    """Quantise a (H, W) unit-range map and write it as an 8-bit grey PNG."""
    pixels = quantize_unit8(values)
    if pixels.ndim != 2:
        raise ValueError(f"grey map must be (H, W), got {pixels.shape}")
    return atomic_write_bytes(path, encode_png8(pixels))


def write_rgb8(path: str | os.PathLike[str], values: ArrayLike) -> Path:
    """Quantise a (H, W, 3) unit-range map and write it as an 8-bit RGB PNG."""
    pixels = quantize_unit8(values)
    if pixels.ndim != 3 or pixels.shape[2] != 3:
        raise ValueError(f"RGB map must be (H, W, 3), got {pixels.shape}")
    return atomic_write_bytes(path, encode_png8(pixels))


def write_rgba8(path: str | os.PathLike[str], rgb: ArrayLike, alpha: ArrayLike) -> Path:
    """Quantise (H, W, 3) colour and (H, W) alpha, both unit range, into an 8-bit RGBA PNG."""
    colour = quantize_unit8(rgb)
    coverage = quantize_unit8(alpha)
    if colour.ndim != 3 or colour.shape[2] != 3 or coverage.shape != colour.shape[:2]:
        raise ValueError(f"RGBA needs (H, W, 3) + (H, W), got {colour.shape} + {coverage.shape}")
    pixels = np.concatenate([colour, coverage[..., None]], axis=2)
    return atomic_write_bytes(path, encode_png8(pixels))


def save_png(path: str | os.PathLike[str], img: np.ndarray) -> Path:
    """Write ``img`` (uint8 grey, RGB or RGBA) as a PNG, atomically (see :mod:`matloom.io.atomic`)."""
    array = np.asarray(img)
    if array.dtype != np.uint8:
        raise ValueError(f"PNG images must be uint8, got {array.dtype}")
    return atomic_write_bytes(path, encode_png8(array))


def write_grey16(path: str | os.PathLike[str], values: ArrayLike) -> Path:
    """Quantise a (H, W) unit-range map to 16 bits and write it as a 16-bit grey PNG."""
    return atomic_write_bytes(path, encode_png16_grey(quantize_unit16(values)))


def quantize(values: ArrayLike, bits: int) -> np.ndarray:
    """Unit-range floats -> uint8 (``bits=8``) or uint16 (``bits=16``), see the quantisers."""
    if bits == 8:
        return quantize_unit8(values)
    if bits == 16:
        return quantize_unit16(values)
    raise ValueError(f"bits must be 8 or 16, got {bits}")


def write_unit(path: str | os.PathLike[str], values: ArrayLike, bits: int = 8) -> Path:
    """Quantise a unit-range (H, W), (H, W, 3) or (H, W, 4) map and write it at ``bits``."""
    return atomic_write_bytes(path, encode_png(quantize(values, bits)))


def write_rgba(
    path: str | os.PathLike[str], rgb: ArrayLike, alpha: ArrayLike, bits: int = 8
) -> Path:
    """Quantise (H, W, 3) colour and (H, W) alpha, both unit range, into an RGBA PNG."""
    colour = quantize(rgb, bits)
    coverage = quantize(alpha, bits)
    if colour.ndim != 3 or colour.shape[2] != 3 or coverage.shape != colour.shape[:2]:
        raise ValueError(f"RGBA needs (H, W, 3) + (H, W), got {colour.shape} + {coverage.shape}")
    pixels = np.concatenate([colour, coverage[..., None]], axis=2)
    return atomic_write_bytes(path, encode_png(pixels))


def read_png(path: str | os.PathLike[str]) -> np.ndarray:
    """Read a PNG as (H, W) or (H, W, C) uint8/uint16 samples, exactly as stored (pypng)."""
    import png as pypng

    width, height, rows, info = pypng.Reader(filename=os.fspath(path)).asDirect()
    dtype = np.uint16 if info["bitdepth"] > 8 else np.uint8
    planes = info["planes"]
    pixels = np.vstack([np.asarray(row, dtype=dtype) for row in rows])
    pixels = pixels.reshape(height, width, planes)
    return pixels[..., 0] if planes == 1 else pixels
