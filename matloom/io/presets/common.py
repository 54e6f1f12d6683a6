"""What every preset reads: :class:`PresetInput`, the maps of one render with the derived
textures presets share (ORM packing, normals in either convention, normalised height, scaled
emissive), constant detection and the physical size; and :class:`PresetFiles`, which writes a
preset's PNGs and records them for ``material.json``.

Constant maps are never written as files by a preset: the value goes into the manifest (and
into the material file as a factor, where the target has one).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from matloom.engine.colour import linear_to_srgb
from matloom.engine.maps import MaterialMaps
from matloom.io import png as png_io
from matloom.io.atomic import atomic_write_bytes
from matloom.vocab.layout import LAYOUT
from matloom.vocab.packing import ORM


def identifier(name: str) -> str:
    """``name`` as an identifier valid in USD (prim names) and MaterialX (element names):
    ``[A-Za-z_][A-Za-z0-9_]*``. Other characters become ``_`` and a leading digit gets an
    ``m`` before it, so ``01_bricks`` -> ``m01_bricks`` and ``-lead`` -> ``_lead`` (file names
    keep the name as given)."""
    text = re.sub(r"[^A-Za-z0-9_]", "_", name)
    return "m" + text if not text or text[0].isdigit() else text


#: float32 rounding steps (of the value's magnitude) a map may spread over and still count as
#: one value: compositing layers that all write ior 1.5 leaves 1.4999999 .. 1.5000001, which
#: a texture would store as one grey level.
_ROUNDING_ULPS = 8


def _constant(array: np.ndarray) -> float | list[float] | None:
    """The value of an array whose texels all hold one finite value, up to float32 rounding
    (:data:`_ROUNDING_ULPS`); a list for colours. Presets write such a map as a value."""
    flat = np.asarray(array).reshape(array.shape[0] * array.shape[1], -1)
    first = flat[0]
    if not np.all(np.isfinite(first)):
        return None
    if np.all(flat == first):
        return float(first[0]) if flat.shape[1] == 1 else [float(v) for v in first]
    with np.errstate(invalid="ignore"):  # float64: the spread of huge float32 values is finite
        low, high = flat.min(axis=0).astype(np.float64), flat.max(axis=0).astype(np.float64)
    if not (np.all(np.isfinite(low)) and np.all(np.isfinite(high))):
        return None
    tolerance = _ROUNDING_ULPS * np.finfo(np.float32).eps * np.maximum(np.abs(low), np.abs(high))
    if np.any(high - low > tolerance):
        return None
    value = flat.astype(np.float64).mean(axis=0).astype(np.float32)
    return float(value[0]) if flat.shape[1] == 1 else [float(v) for v in value]


#: The physical side lengths (metres) a render may declare: the presets store the swatch's size
#: as float32 (glTF positions, MaterialX and USD inputs), and a size beyond these bounds is a
#: typo (``--unit-m 1e308``), not a material.
PHYSICAL_SIDE_M: tuple[float, float] = (1e-9, 1e9)
#: The largest magnitude a float32 input of a document is given (just under float32's maximum).
FLOAT32_LIMIT = 3.4e38


def physical_size_problem(unit_m: float, view_size: tuple[float, float]) -> str | None:
    """Why ``unit_m`` metres per unit cannot describe a View of ``view_size`` units (None: it
    can): each side in metres must lie within :data:`PHYSICAL_SIDE_M`."""
    low, high = PHYSICAL_SIDE_M
    for side in view_size:
        metres = side * unit_m
        if not low <= metres <= high:
            return (
                f"unit_m {unit_m:g} makes the swatch {metres:g} m wide ({side:g} units); "
                f"a physical size must be {low:g} to {high:g} m"
            )
    return None


def unit_m_override_note(
    unit_m: float | None, program_unit_m: float | None, view_width: float
) -> str | None:
    """The note said when ``unit_m`` (a flag) replaces a different ``unit_m`` of the program's
    View (None when nothing is replaced). The library's entries round their unit_m to 6 digits:
    within that, it is the same size."""
    if unit_m is None or program_unit_m is None:
        return None
    if math.isclose(unit_m, program_unit_m, rel_tol=1e-4, abs_tol=1e-6):
        return None
    return (
        f"note: --unit-m {unit_m:g} replaces the program's View unit_m={program_unit_m:g}"
        f" (the swatch is {view_width * unit_m:g} m wide instead of "
        f"{view_width * program_unit_m:g} m)"
    )


def float32_input(value: float, what: str, notes: list[str]) -> float:
    """``value`` for a float32 input of a document (MaterialX, USD): beyond float32 it is
    clamped to +-:data:`FLOAT32_LIMIT` (NaN to 0) and ``notes`` says so."""
    if -FLOAT32_LIMIT <= value <= FLOAT32_LIMIT:
        return value
    clamped = 0.0 if value != value else float(np.copysign(FLOAT32_LIMIT, value))
    notes.append(f"{what} {value:.6g} is beyond float32: written as {clamped:.6g}")
    return clamped


def _finite(values: np.ndarray, fill: float = 0.0) -> np.ndarray:
    return np.where(np.isfinite(values), values, np.float32(fill)).astype(np.float32)


@dataclass
class PresetInput:
    """The maps of one render as presets see them (see the module docstring).

    ``name`` prefixes the file names; ``unit_m`` is metres per coordinate unit (None: unknown);
    ``bits`` is the PNG depth of the colour and data maps (base colour, ORM or mask, normals,
    emissive, single channels) of every preset but glTF, whose viewers read 8-bit textures;
    the height, ior and angle textures are 16-bit whatever it says.
    """

    maps: MaterialMaps
    name: str = "material"
    unit_m: float | None = None
    bits: int = 8

    @property
    def identifier(self) -> str:
        """The name as an identifier for names inside documents (:func:`identifier`)."""
        return identifier(self.name)

    # ---------------------------------------------------------------- channel use

    def constant(self, map_field: str) -> float | list[float] | None:
        """The constant value of a ``MaterialMaps`` field, or None when it varies."""
        return self._constants.setdefault(
            map_field, _constant(np.asarray(getattr(self.maps, map_field)))
        )

    def used(self, channel: str) -> bool:
        """True when the program uses ``channel``: its map varies or differs from the default."""
        layout = LAYOUT[channel]
        value = self.constant(layout.field)
        if value is None:
            return True
        default = layout.default
        if layout.field == "emissive_linear":
            return bool(np.any(np.asarray(value) != 0))
        if isinstance(default, tuple):
            default = list(default[:3])
        return value != default

    @cached_property
    def _constants(self) -> dict[str, float | list[float] | None]:
        return {}

    # ---------------------------------------------------------------- derived textures

    @cached_property
    def basecolor_srgb(self) -> np.ndarray:
        with np.errstate(invalid="ignore"):
            return linear_to_srgb(np.asarray(self.maps.basecolor_linear, dtype=np.float32))

    @property
    def opaque(self) -> bool:
        return self.constant("alpha") == 1.0

    @cached_property
    def orm(self) -> np.ndarray:
        """(H, W, 3): R = AO, G = roughness, B = metallic (:data:`~matloom.vocab.packing.ORM`,
        the glTF, Unreal and Godot packing)."""
        m = self.maps
        return np.stack([m.ao, m.roughness, m.metallic], axis=2).astype(np.float32)

    @property
    def orm_constant(self) -> bool:
        return all(self.constant(f) is not None for f in ("ao", "roughness", "metallic"))

    def normal(self, convention: str, bits: int = 8) -> np.ndarray:
        """PNG samples of the normal in ``convention`` ("gl" or "dx": green = max - OpenGL
        green)."""
        from matloom.io.encode import normal_pixels

        return normal_pixels(self.maps.normal, convention, bits)

    @property
    def flat(self) -> bool:
        """True when the height is constant (the normal map is flat, nothing to displace)."""
        return self.constant("height") is not None

    @cached_property
    def height_range(self) -> tuple[float, float]:
        values = np.asarray(self.maps.height, dtype=np.float64)
        finite = values[np.isfinite(values)]
        return (float(finite.min()), float(finite.max())) if finite.size else (0.0, 0.0)

    @cached_property
    def height_unit(self) -> np.ndarray:
        """The height normalised to [0, 1] over its finite range (0 when flat)."""
        low, high = self.height_range
        values = np.asarray(self.maps.height, dtype=np.float64)
        if high <= low:
            return np.zeros(values.shape, np.float64)
        with np.errstate(invalid="ignore"):
            return (values - low) / (high - low)

    def height_entry(self, file: str) -> dict[str, Any]:
        """Manifest entry of a normalised 16-bit height file, with its scale in metres."""
        low, high = self.height_range
        entry: dict[str, Any] = {
            "file": file,
            "encoding": "png16-grey",
            "min": low,
            "max": high,
            "decode": "height = min + value / 65535 * (max - min) (coordinate units)",
        }
        if self.unit_m is not None:
            entry.update(
                min_m=low * self.unit_m,
                max_m=high * self.unit_m,
                displacement_scale_m=(high - low) * self.unit_m,
            )
        return entry

    @cached_property
    def emissive(self) -> tuple[np.ndarray, float] | None:
        """(sRGB texture in [0, 1], scale) with linear emission = scale x decode(texture);
        None when nothing emits."""
        linear = _finite(np.asarray(self.maps.emissive_linear), 0.0)
        linear = np.maximum(linear, 0)
        scale = float(linear.max()) if linear.size else 0.0
        if scale <= 0:
            return None
        with np.errstate(invalid="ignore"):
            return linear_to_srgb(linear / np.float32(scale)), scale

    # ---------------------------------------------------------------- size

    @property
    def view_size(self) -> tuple[float, float]:
        v = self.maps.view
        return abs(v.x2 - v.x1), abs(v.y2 - v.y1)

    @property
    def size_m(self) -> tuple[float, float] | None:
        if self.unit_m is None:
            return None
        w, h = self.view_size
        return w * self.unit_m, h * self.unit_m

    @property
    def quad_size(self) -> tuple[float, float]:
        """The preview quad's size in metres: the physical size, else 1 m wide."""
        if self.size_m is not None:
            return self.size_m
        w, h = self.view_size
        return 1.0, (h / w if w > 0 else 1.0)

    def physical(self) -> dict[str, Any]:
        """The physical-size record shared by the presets' metadata."""
        if self.unit_m is None:
            return {"unit_m": None, "note": "physical size unknown: pass --unit-m / unit_m="}
        width_m, height_m = self.size_m or (0.0, 0.0)
        low, high = self.height_range
        return {
            "unit_m": self.unit_m,
            "width_m": width_m,
            "height_m": height_m,
            "displacement_scale_m": (high - low) * self.unit_m,
            "height_min_m": low * self.unit_m,
        }


@dataclass
class PresetFiles:
    """Writes one preset's files into its folder and collects its manifest entry."""

    folder: Path
    files: dict[str, dict[str, Any]] = field(default_factory=dict)
    values: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    png_bytes: dict[str, bytes] = field(default_factory=dict)

    def png(self, role: str, file: str, pixels: np.ndarray, bits: int = 8, **info: Any) -> str:
        """Quantise unit-range ``pixels`` at ``bits`` (integer samples are written as they are)
        and write them as ``file``."""
        if pixels.dtype not in (np.uint8, np.uint16):
            pixels = png_io.quantize(pixels, bits)
        data = png_io.encode_png(pixels)
        bits = 8 * pixels.dtype.itemsize
        self.png_bytes[file] = data
        atomic_write_bytes(self.folder / file, data)
        self.files[role] = {"file": file, "encoding": f"png{bits}", **info}
        return file

    def write_text(self, role: str, file: str, text: str, **info: Any) -> str:
        atomic_write_bytes(self.folder / file, text.encode("utf-8"))
        self.files[role] = {"file": file, **info}
        return file

    def write_bytes(self, role: str, file: str, data: bytes, **info: Any) -> str:
        atomic_write_bytes(self.folder / file, data)
        self.files[role] = {"file": file, **info}
        return file

    def entry(self, src: PresetInput, **extra: Any) -> dict[str, Any]:
        out: dict[str, Any] = {
            "folder": self.folder.name,
            "files": self.files,
            "constant_values": self.values,
            "physical_size": src.physical(),
            **extra,
        }
        if self.notes:
            out["notes"] = self.notes
        return out


SRGB = "sRGB"
LINEAR = "linear (non-color)"


def write_basecolor(src: PresetInput, out: PresetFiles, file: str, bits: int = 8) -> str | None:
    """The base colour (sRGB; RGBA with coverage as alpha unless opaque), or its constant."""
    colour = src.constant("basecolor_linear")
    if colour is not None and src.opaque:
        out.values["basecolor_linear"] = colour
        out.values["basecolor_srgb"] = [float(v) for v in linear_to_srgb(np.asarray(colour))]
        return None
    pixels = src.basecolor_srgb
    if not src.opaque:
        pixels = np.concatenate([pixels, src.maps.alpha[..., None]], axis=2)
    return out.png("basecolor", file, pixels, bits, colour_space=SRGB, alpha="coverage")


def write_normal(
    src: PresetInput, out: PresetFiles, file: str, convention: str, bits: int = 8
) -> str | None:
    if src.flat:
        out.values["normal"] = [0.0, 0.0, 1.0]
        return None
    meaning = "OpenGL (+Y up)" if convention == "gl" else "DirectX (green = 1 - OpenGL green)"
    return out.png(
        "normal", file, src.normal(convention, bits), bits, colour_space=LINEAR, convention=meaning
    )


def write_orm(src: PresetInput, out: PresetFiles, file: str, bits: int = 8) -> str | None:
    if src.orm_constant:
        for f in ("ao", "roughness", "metallic"):
            out.values[f] = src.constant(f)
        return None
    return out.png(ORM.role, file, src.orm, bits, colour_space=LINEAR, channels=ORM.description)


def write_height(src: PresetInput, out: PresetFiles, file: str) -> str | None:
    if src.flat:
        out.values["height"] = src.constant("height")
        return None
    out.png("height", file, src.height_unit, 16, colour_space=LINEAR)
    out.files["height"].update(src.height_entry(file))
    return file


def write_emissive(src: PresetInput, out: PresetFiles, file: str, bits: int = 8) -> str | None:
    emissive = src.emissive
    if emissive is None:
        return None
    texture, scale = emissive
    colour = src.constant("emissive_linear")
    if colour is not None:
        out.values["emissive_linear"] = colour
        return None
    out.png("emissive", file, texture, bits, colour_space=SRGB, strength=scale)
    return file


#: A varying ior is stored as a 16-bit PNG of (ior - 1) / IOR_SPAN (ior 1 .. 1 + IOR_SPAN).
IOR_SPAN = 2.0


def write_ior(src: PresetInput, out: PresetFiles, file: str) -> str:
    """A varying ior as a 16-bit PNG of (ior - 1) / 2 (ior 1..3; readers rescale it)."""
    unit = (np.asarray(src.maps.ior, dtype=np.float64) - 1.0) / IOR_SPAN
    out.png("ior", file, unit, 16, colour_space=LINEAR, decode="ior = 1 + 2 * value / 65535")
    if float(np.nanmax(np.asarray(src.maps.ior))) > 1.0 + IOR_SPAN:
        out.notes.append("the ior texture clips ior above 3")
    return file
