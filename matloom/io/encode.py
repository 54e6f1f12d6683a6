"""How each map of the default output is encoded: file names, bit depth, EXR precision,
normal conventions and constant maps (:class:`Encoding`), and the writer of one map.

* ``float_format="png"`` (default): [0, 1] maps and colours as PNG at ``bits`` (8 or 16), the
  unbounded maps (ior, height, emissive) and float copies as float32 EXR;
* ``float_format="exr"``: every map as EXR, ``exr_precision`` ``"half"`` (default) or
  ``"float"``: base colour as linear RGBA (alpha = coverage), normals as the raw unit vector,
  the anisotropy angle in unreduced degrees (no PNG, no copy);
* ``float_format="png16"``: ``"png"`` plus ``height16.png`` (kept for older scripts).

Normals are written in each convention of ``normals``: ``normal_gl`` (OpenGL, +Y up) and/or
``normal_dx`` (DirectX, green = 1 - OpenGL green). With ``constants=True`` a map whose every
texel has one finite value is recorded in ``material.json`` as ``"constant"`` instead of a file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from matloom.engine.colour import linear_to_srgb
from matloom.engine.maps import MaterialMaps
from matloom.io import exr as exr_io
from matloom.io import png as png_io
from matloom.io.atomic import atomic_write_bytes
from matloom.vocab.layout import MapSpec

#: Values of :attr:`Encoding.float_format`.
FLOAT_FORMATS: tuple[str, ...] = ("png", "exr", "png16")
#: Normal-map conventions and the file-name suffix each one gets.
NORMAL_CONVENTIONS: dict[str, str] = {"gl": "normal_gl", "dx": "normal_dx"}
BITS: tuple[int, ...] = (8, 16)
EXR_PRECISIONS: tuple[str, ...] = ("half", "float")


@dataclass(frozen=True)
class Encoding:
    """Options that decide the files of the default output (see the module docstring)."""

    float_format: str = "png"
    bits: int = 8
    exr_precision: str = "half"
    normals: tuple[str, ...] = ("gl",)
    constants: bool = False

    def __post_init__(self) -> None:
        if self.float_format not in FLOAT_FORMATS:
            raise ValueError(
                f"float_format must be one of {FLOAT_FORMATS}, got {self.float_format!r}"
            )
        if self.bits not in BITS:
            raise ValueError(f"bits must be 8 or 16, got {self.bits!r}")
        if self.exr_precision not in EXR_PRECISIONS:
            raise ValueError(f"exr_precision must be 'half' or 'float', got {self.exr_precision!r}")
        if not self.normals or set(self.normals) - set(NORMAL_CONVENTIONS):
            raise ValueError(f"normals must be a non-empty subset of {sorted(NORMAL_CONVENTIONS)}")

    @property
    def all_exr(self) -> bool:
        return self.float_format == "exr"

    @property
    def exr_encoding(self) -> str:
        return "exr-half" if self.exr_precision == "half" else "exr-float32"


def is_normal(spec: MapSpec) -> bool:
    return spec.writer == "normal8"


def file_names(spec: MapSpec, enc: Encoding) -> list[str]:
    """The files ``spec`` is written to with ``enc`` (the main file first)."""
    if is_normal(spec):
        ext = ".exr" if enc.all_exr else ".png"
        return [NORMAL_CONVENTIONS[c] + ext for c in enc.normals]
    if enc.all_exr:
        return [f"{spec.name}.exr"]
    return list(spec.file_names)


def constant_value(maps: MaterialMaps, spec: MapSpec) -> float | list[float] | None:
    """The value of a map whose every texel of every source is one finite value, else None."""
    values: list[float] = []
    for name in spec.sources:
        array = np.asarray(getattr(maps, name))
        flat = array.reshape(array.shape[0] * array.shape[1], -1)
        first = flat[0]
        if not np.all(np.isfinite(first)) or not np.all(flat == first):
            return None
        values.extend(float(v) for v in first)
    return values[0] if len(values) == 1 else values


def _srgb(linear: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        return linear_to_srgb(np.asarray(linear, dtype=np.float32))


def periodic_unit(values: np.ndarray, period: float) -> np.ndarray:
    """(values mod period) / period in [0, 1], computed in float64 (a negative value wraps to
    the top of the range; NaN and +-inf give NaN, which the PNG writers store as 0)."""
    with np.errstate(invalid="ignore"):
        return np.mod(np.asarray(values, dtype=np.float64), period) / period


def encoded_normal(normal: np.ndarray) -> np.ndarray:
    """n * 0.5 + 0.5 (OpenGL), float32."""
    return np.asarray(normal, dtype=np.float32) * np.float32(0.5) + np.float32(0.5)


def normal_pixels(normal: np.ndarray, convention: str, bits: int) -> np.ndarray:
    """The PNG samples of a normal map: OpenGL n * 0.5 + 0.5 quantised; ``dx`` inverts the
    green samples (max - g), so DirectX green = 1 - OpenGL green exactly, sample for sample."""
    pixels = png_io.quantize(encoded_normal(normal), bits)
    if convention == "dx":
        pixels[..., 1] = np.iinfo(pixels.dtype).max - pixels[..., 1]
    return pixels


def _write_png(path: Path, spec: MapSpec, sources: list[np.ndarray], bits: int) -> None:
    if bits == 8:  # the reference's writers, byte for byte
        if spec.writer == "srgb8-alpha":
            png_io.write_rgba8(path, _srgb(sources[0]), sources[1])
        elif spec.writer == "srgb8":
            png_io.write_rgb8(path, _srgb(sources[0]))
        elif spec.writer == "grey8":
            png_io.write_grey8(path, sources[0])
        elif spec.writer == "periodic8" and spec.period:
            png_io.write_grey8(path, periodic_unit(sources[0], spec.period))
        else:
            raise ValueError(f"map {spec.name!r}: unknown writer {spec.writer!r}")
        return
    if spec.writer == "srgb8-alpha":
        png_io.write_rgba(path, _srgb(sources[0]), sources[1], bits)
    elif spec.writer == "srgb8":
        png_io.write_unit(path, _srgb(sources[0]), bits)
    elif spec.writer == "grey8":
        png_io.write_unit(path, sources[0], bits)
    elif spec.writer == "periodic8" and spec.period:
        png_io.write_unit(path, periodic_unit(sources[0], spec.period), bits)
    else:
        raise ValueError(f"map {spec.name!r}: unknown writer {spec.writer!r}")


def write_map(
    maps: MaterialMaps, spec: MapSpec, folder: Path, enc: Encoding
) -> tuple[list[str], dict[str, Any]]:
    """Write one map into ``folder``; returns its file names and manifest fields that differ
    from ``spec.describe()`` (encoding, files of both normal conventions, a constant)."""
    entry: dict[str, Any] = {}
    if enc.constants:
        value = constant_value(maps, spec)
        if value is not None:
            return [], {"file": None, "constant": value, "encoding": "constant"}
    names = file_names(spec, enc)
    sources = [np.asarray(getattr(maps, name)) for name in spec.sources]
    if is_normal(spec):
        entry["files"] = dict(zip(enc.normals, names))
        entry["file"] = names[0]
        entry["convention"] = "OpenGL (+Y up)" if enc.normals[0] == "gl" else "DirectX (-Y)"
        entry["meaning"] = (
            "tangent-space normal; normal_gl: OpenGL convention (+Y up), normal_dx: DirectX "
            "convention (green = 1 - OpenGL green)"
            + ("; raw unit vector" if enc.all_exr else ", encoded n * 0.5 + 0.5")
        )
        for convention, name in zip(enc.normals, names):
            if enc.all_exr:
                raw = np.array(sources[0], dtype=np.float32)
                if convention == "dx":
                    raw[..., 1] = -raw[..., 1]
                exr_io.write_exr(folder / name, raw, enc.exr_precision)
            elif enc.bits == 8 and convention == "gl":
                png_io.write_rgb8(folder / name, encoded_normal(sources[0]))
            else:
                pixels = normal_pixels(sources[0], convention, enc.bits)
                atomic_write_bytes(folder / name, png_io.encode_png(pixels))
        entry["encoding"] = enc.exr_encoding if enc.all_exr else f"png{enc.bits}-rgb"
        return names, entry
    if enc.all_exr:
        values = sources[0]
        if spec.writer == "srgb8-alpha":
            values = np.concatenate([values, sources[1][..., None]], axis=2)
            entry["colour_space"] = "linear Rec.709 (RGB); alpha is linear coverage"
        elif spec.writer == "srgb8":
            entry["colour_space"] = "linear Rec.709"
        exr_io.write_exr(folder / names[0], values, enc.exr_precision)
        entry.update(file=names[0], encoding=enc.exr_encoding)
        if spec.period:
            entry["decode"] = "float samples hold the blended degrees unreduced"
        return names, entry
    if spec.writer == "exr":
        exr_io.write_exr(folder / names[0], sources[0])
    else:
        _write_png(folder / names[0], spec, sources, enc.bits)
        if enc.bits == 16:
            entry["encoding"] = spec.encoding.replace("png8", "png16")
            if spec.decode:
                entry["decode"] = spec.decode.replace("/ 255", "/ 65535").replace(
                    "255 = ", "65535 = "
                )
    if spec.float_file:
        exr_io.write_exr(folder / spec.float_file, np.asarray(sources[0], dtype=np.float32))
    return names, entry
