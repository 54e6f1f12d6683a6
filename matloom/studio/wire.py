"""The maps wire format (``application/x-matloom-maps``, docs/studio-api.md): evaluated maps
as binary arrays, not base64 PNGs.

::

    b"MLMP" | uint32 LE N | N bytes of UTF-8 JSON header | payloads (each 4-byte aligned)

Each map is quantised by the code the exporter uses, so the studio shows what ``matloom render``
writes: base colour through the sRGB conversion and the PNG writers' 8-bit quantisation
(:func:`matloom.io.png.quantize_unit8`), the normal as the OpenGL ``n * 0.5 + 0.5``
(:func:`matloom.io.encode.encoded_normal`), ORM and emission as the presets pack them
(:class:`matloom.io.presets.common.PresetInput`: R AO, G roughness, B metallic; emission as an
sRGB texture times ``emissive_scale``), the anisotropy angle as its periodic 8-bit map. The
height and ior travel as float32. Row 0 is the top row.
"""

from __future__ import annotations

import json
import struct
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from matloom.engine.maps import ARRAY_FIELDS, MaterialMaps
from matloom.io.encode import encoded_normal, periodic_unit
from matloom.io.png import quantize_unit8
from matloom.io.presets.common import PresetInput

MAGIC = b"MLMP"
MEDIA_TYPE = "application/x-matloom-maps"
#: Scalar channels sent as u8 x 1 only when the program writes them (its map varies or differs
#: from the channel's default, as the presets decide).
OPTIONAL_U8 = ("alpha", "sheen", "coat", "transmission", "subsurface", "anisotropy")
#: Every ``MaterialMaps`` field may be asked for as float32 (``channels`` of the request): it
#: travels as ``raw:<field>``, for the inspector's value under the cursor.
RAW_PREFIX = "raw:"


@dataclass(frozen=True)
class Payload:
    """One map of the body: its name, the array (uint8 or float32, C order) and encoding."""

    name: str
    array: np.ndarray
    encoding: str

    @property
    def dtype(self) -> str:
        return "u8" if self.array.dtype == np.uint8 else "f32"

    @property
    def channels(self) -> int:
        return 1 if self.array.ndim == 2 else int(self.array.shape[2])


def _f32(values: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(values, dtype="<f4")


def map_payloads(
    maps: MaterialMaps, raw: Iterable[str] = (), extra: Mapping[str, np.ndarray] | None = None
) -> tuple[list[Payload], dict[str, Any]]:
    """The payloads of ``maps`` (see the module docstring) and header facts about them
    (``emissive_scale``, ``height_range``). ``raw``: ``MaterialMaps`` fields sent as float32;
    ``extra``: more uint8 images by name (e.g. the lit preview)."""
    src = PresetInput(maps)
    out = [
        Payload("basecolor", quantize_unit8(src.basecolor_srgb), "srgb"),
        Payload("normal", quantize_unit8(encoded_normal(maps.normal)), "normal-gl"),
        Payload("orm", quantize_unit8(src.orm), "linear"),
    ]
    emissive = src.emissive
    scale = 0.0
    if emissive is None:
        out.append(Payload("emissive", np.zeros((*maps.alpha.shape, 3), np.uint8), "srgb"))
    else:
        out.append(Payload("emissive", quantize_unit8(emissive[0]), "srgb"))
        scale = emissive[1]
    out.append(Payload("height", _f32(maps.height), "units"))
    for name in OPTIONAL_U8:
        if src.used(name):
            out.append(Payload(name, quantize_unit8(getattr(maps, name)), "linear"))
    if src.used("anisotropy_angle"):
        period = _angle_period()
        values = quantize_unit8(periodic_unit(maps.anisotropy_angle, period))
        out.append(Payload("anisotropy_angle", values, f"degrees/{period:g}"))
    if src.used("ior"):
        out.append(Payload("ior", _f32(maps.ior), "linear"))
    for name in raw:
        out.append(Payload(RAW_PREFIX + name, _f32(getattr(maps, name)), "raw"))
    for name, image in (extra or {}).items():
        out.append(Payload(name, np.ascontiguousarray(image, dtype=np.uint8), "srgb"))
    return out, {"emissive_scale": scale, "height_range": list(src.height_range)}


def _angle_period() -> float:
    from matloom.engine.tiling import map_periods

    return map_periods().get("anisotropy_angle", 180.0)


def check_raw(names: Iterable[str]) -> list[str]:
    """The requested float32 fields, each a ``MaterialMaps`` array field; ValueError else."""
    names = list(dict.fromkeys(names))
    unknown = [n for n in names if n not in ARRAY_FIELDS]
    if unknown:
        raise ValueError(
            f"unknown channel(s) {', '.join(unknown)}; choose from {', '.join(ARRAY_FIELDS)}"
        )
    return names


def pack(header: dict[str, Any], payloads: list[Payload]) -> bytes:
    """The body: magic, header length, header (with each map's ``offset`` and ``length``,
    offsets from the start of the body, multiples of 4), then the payloads."""
    entries = []
    for p in payloads:
        entries.append(
            {
                "name": p.name,
                "dtype": p.dtype,
                "channels": p.channels,
                "offset": 0,
                "length": int(p.array.nbytes),
                "encoding": p.encoding,
            }
        )
    # the offsets depend on the header's length, which depends on the offsets' digits: lay
    # the payloads out after a header padded to a fixed guess, growing it until it fits
    guess = 256 + 160 * len(entries)
    while True:
        start = _align(8 + guess)
        offset = start
        for entry in entries:
            entry["offset"] = offset
            offset = _align(offset + entry["length"])
        text = json.dumps({**header, "maps": entries}, separators=(",", ":"), allow_nan=False)
        raw = text.encode("utf-8")
        if len(raw) <= guess:
            break
        guess = len(raw) + 64
    parts: list[bytes | memoryview] = [MAGIC, struct.pack("<I", len(raw)), raw]
    at = 8 + len(raw)
    for entry, p in zip(entries, payloads):
        parts.append(b"\0" * (entry["offset"] - at))
        parts.append(memoryview(np.ascontiguousarray(p.array)).cast("B"))
        at = entry["offset"] + entry["length"]
    parts.append(b"\0" * (offset - at))
    return b"".join(parts)  # one copy of every payload


def _align(n: int) -> int:
    return (n + 3) & ~3


def unpack(body: bytes) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
    """The header and the maps of a body (for tests and tools): uint8 or float32 arrays of
    shape (H, W) or (H, W, C)."""
    if body[:4] != MAGIC:
        raise ValueError("not a MatLoom maps body")
    (n,) = struct.unpack("<I", body[4:8])
    header = json.loads(body[8 : 8 + n].decode("utf-8"))
    h, w = header["height"], header["width"]
    maps: dict[str, np.ndarray] = {}
    for m in header["maps"]:
        dtype = np.uint8 if m["dtype"] == "u8" else np.dtype("<f4")
        a = np.frombuffer(body, dtype=dtype, count=m["length"] // np.dtype(dtype).itemsize,
                          offset=m["offset"])  # fmt: skip
        maps[m["name"]] = a.reshape((h, w) if m["channels"] == 1 else (h, w, m["channels"]))
    return header, maps
