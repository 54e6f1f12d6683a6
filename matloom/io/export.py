"""Write a material's maps to a folder, with the reference's file names and encodings.

The 14 maps (in this order, see :data:`MAP_NAMES`; one per channel of the registry, from
:mod:`matloom.vocab.layout`, then normal and AO) and their files:

* ``basecolor.png``: 8-bit RGBA; RGB = linear -> sRGB of ``basecolor_linear``, A = coverage;
* ``metallic``, ``roughness``, ``sheen``, ``coat``, ``transmission``, ``subsurface``,
  ``anisotropy``, ``ao`` ``.png``: 8-bit grey;
* ``anisotropy_angle.png``: 8-bit grey of (angle mod 180) / 180 (the direction is axial), plus
  ``anisotropy_angle.exr`` with the blended degrees (float32, unreduced);
* ``normal_gl.png``: 8-bit RGB, n * 0.5 + 0.5, OpenGL convention (+Y up); on request also
  ``normal_dx.png`` (DirectX, green = 1 - OpenGL green);
* ``ior.exr``, ``height.exr`` (one float32 channel) and ``emissive.exr`` (float32 linear RGB,
  unclipped).

Every map is written on every render, whether or not the program writes its channel (a
channel no layer writes gives its default, e.g. a constant 0 angle): the folder's file list
depends only on the options, never on the program, and ``--maps`` picks a subset.

``bits=16`` writes every PNG map at 16 bits; ``float_format="exr"`` writes every map as EXR
(half by default, ``exr_precision="float"`` for float32); ``constants=True`` records constant
maps as manifest values instead of files (see :mod:`matloom.io.encode`). ``presets`` add
engine and interchange files in subfolders (:mod:`matloom.io.presets`), ``unit_m`` (metres
per coordinate unit) gives the physical size.

With ``float_format="png16"`` the height is also written as ``height16.png`` (16-bit grey,
normalised to its finite min/max, which ``material.json`` records). A ``material.json``
manifest describes every file and lists each with its SHA-256. :func:`write_maps` and
:func:`write_manifest` write into a staging folder; the render job
(:func:`matloom.runtime.run.run_render`) delivers it through a sink, for a folder an
:class:`matloom.io.outdir.OutputFolder` batch, so a failing export never leaves a
complete-looking folder, never damages a previous one and never touches a file MatLoom did not
write.

Non-finite values never crash the export: in 8-bit maps NaN becomes 0 and +-inf clips, EXR
keeps them, and the counts per map are returned and recorded.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from matloom.engine.maps import MaterialMaps
from matloom.engine.tiling import manifest_entry as tiling_entry
from matloom.io import png as png_io
from matloom.io.atomic import atomic_write_bytes
from matloom.io.encode import FLOAT_FORMATS as FLOAT_FORMATS
from matloom.io.encode import Encoding, file_names, write_map
from matloom.io.encode import periodic_unit as periodic_unit
from matloom.vocab.layout import LAYOUT, MapSpec

#: Name of the manifest written into every export folder.
MANIFEST_NAME = "material.json"
#: File written next to ``height.exr`` when ``float_format="png16"``.
HEIGHT_PNG16_NAME = "height16.png"
#: Format identifier and version of ``material.json``.
MANIFEST_FORMAT = ("matloom-material", 1)


#: Every exported map, in the reference's order: one row per channel of the registry (its
#: encoding, colour space and meaning come from :mod:`matloom.vocab.layout`), then normal and AO.
MAP_SPECS: tuple[MapSpec, ...] = LAYOUT.maps
#: Names accepted by ``maps_subset`` (and the CLI's ``--maps``), in export order.
MAP_NAMES: tuple[str, ...] = tuple(spec.name for spec in MAP_SPECS)


def select_maps(names: Sequence[str] | None) -> tuple[MapSpec, ...]:
    """The specs for ``names`` in export order (all when None); unknown names raise ValueError."""
    if names is None:
        return MAP_SPECS
    if isinstance(names, str):
        raise TypeError("maps_subset must be a sequence of map names, not a string")
    unknown = sorted(set(names) - set(MAP_NAMES))
    if unknown:
        raise ValueError(f"unknown map name(s) {unknown}; valid names: {', '.join(MAP_NAMES)}")
    wanted = set(names)
    return tuple(spec for spec in MAP_SPECS if spec.name in wanted)


def planned_files(
    maps_subset: Sequence[str] | None,
    float_format: str,
    preview: bool = False,
    encoding: Encoding | None = None,
) -> list[str]:
    """The file names a render with these options may write (to check the folder up front;
    preset files are checked by the batch install)."""
    enc = encoding or Encoding(float_format=float_format)
    names = [name for spec in select_maps(maps_subset) for name in file_names(spec, enc)]
    names += [MANIFEST_NAME, "material.mat"]
    if float_format == "png16" and (maps_subset is None or "height" in maps_subset):
        names.append(HEIGHT_PNG16_NAME)
    if preview:
        names.append("preview.png")
    return names


#: The largest seam ratio of a map that counts as tiling (docs/tileable.md: a visible seam
#: gives 2 to 50, maps that repeat exactly stay below it away from pattern lines on the View's
#: edge; the examples and the tileable library entries reach at most 1.2 at 512 x 512).
SEAM_BOUND = 2.0


def tiling_fields(maps: MaterialMaps, specs: Sequence[MapSpec]) -> dict[str, Any]:
    """The manifest's tiling fields of a render (:func:`matloom.engine.tiling.manifest_entry`)
    with ``tileable`` true only when every exported map's seam ratio is within
    :data:`SEAM_BOUND`; otherwise false, and ``tileable_reason`` names the maps over it (a
    tileable View whose content does not repeat, W009/W010, shows as such a seam)."""
    fields = tiling_entry(maps, specs)
    over = {k: v for k, v in fields.get("seam_ratio", {}).items() if not v <= SEAM_BOUND}
    if over:
        worst = sorted(over.items(), key=lambda kv: (-kv[1] if kv[1] == kv[1] else 0.0, kv[0]))
        listed = ", ".join(f"{name} {ratio:g}" for name, ratio in worst)
        fields["tileable"] = False
        fields["tileable_reason"] = (
            f"the maps do not repeat seamlessly: seam ratio over {SEAM_BOUND:g} for {listed}"
        )
    return fields


@dataclass
class ExportResult:
    """What :func:`write_maps` wrote (and :func:`matloom.runtime.export.export_maps` returns).

    ``files`` maps each written map name (plus ``"<name>_float"`` for a map's float copy,
    ``"height16"`` and ``"manifest"``) to its final path; ``nonfinite_counts`` holds, per map
    name, how many source values were NaN or +-inf (only maps with at least one).
    """

    out_dir: Path
    files: dict[str, Path]
    manifest: dict[str, Any]
    nonfinite_counts: dict[str, int] = field(default_factory=dict)

    @property
    def manifest_path(self) -> Path:
        return self.out_dir / MANIFEST_NAME


def _default_engine_version() -> str:
    """The package's ``__version__``. Read from :mod:`matloom._version`, not from
    ``importlib.metadata``, which costs about 50 ms of CLI start-up."""
    from matloom._version import __version__

    return __version__


# --------------------------------------------------------------------------------------------
# Per-map statistics


def _finite_range(values: np.ndarray) -> dict[str, float] | None:
    """Finite min/max of ``values`` (None when no value is finite)."""
    finite = np.isfinite(values)
    if not finite.any():
        return None
    low = np.min(values, where=finite, initial=np.inf)
    high = np.max(values, where=finite, initial=-np.inf)
    return {"min": float(low), "max": float(high)}


def _nonfinite(values: np.ndarray) -> int:
    return int(values.size - np.count_nonzero(np.isfinite(values)))


def _map_stats(maps: MaterialMaps, spec: MapSpec) -> dict[str, Any]:
    """Value ranges and non-finite counts of the arrays a map is made from."""
    sources = {name: np.asarray(getattr(maps, name)) for name in spec.sources}
    primary = sources[spec.sources[0]]
    stats: dict[str, Any] = {
        "value_range": _finite_range(primary),
        "nonfinite_values": sum(_nonfinite(values) for values in sources.values()),
    }
    if len(sources) > 1:
        stats["source_ranges"] = {name: _finite_range(v) for name, v in sources.items()}
    return stats


# --------------------------------------------------------------------------------------------
# Writers


def _write_height_png16(height: np.ndarray, folder: Path) -> dict[str, Any]:
    """Write height16.png normalised to the finite min/max; returns its manifest entry.

    value = (height - min) / (max - min) quantised to 16 bits (0 everywhere for a flat
    height); NaN -> 0, +inf -> 65535, -inf -> 0.
    """
    values = np.asarray(height, dtype=np.float64)
    value_range = _finite_range(values) or {"min": 0.0, "max": 0.0}
    low, high = value_range["min"], value_range["max"]
    span = high - low
    if span > 0:
        with np.errstate(invalid="ignore"):
            unit = (values - low) / span
    else:
        unit = np.where(np.isposinf(values), 1.0, 0.0)
    png_io.write_grey16(folder / HEIGHT_PNG16_NAME, unit)
    return {
        "file": HEIGHT_PNG16_NAME,
        "encoding": "png16-grey",
        "min": low,
        "max": high,
        "units": "coordinate units",
        "decode": "height = min + value / 65535 * (max - min)",
    }


# --------------------------------------------------------------------------------------------
# Manifest


def _manifest(
    maps: MaterialMaps,
    selected: Sequence[MapSpec],
    map_entries: dict[str, dict[str, Any]],
    program_text: str | None,
    engine_version: str,
    unit_m: float | None = None,
) -> dict[str, Any]:
    """The material.json content (without the optional extras)."""
    view = maps.view
    dx, dy = view.texel_size(maps.width, maps.height_px)
    square = abs(dx - dy) <= 1e-6 * max(dx, dy)
    nonfinite = {name: e["nonfinite_values"] for name, e in map_entries.items()}
    return {
        "format": MANIFEST_FORMAT[0],
        "format_version": MANIFEST_FORMAT[1],
        "engine_version": engine_version,
        "program_sha256": (
            hashlib.sha256(program_text.encode("utf-8")).hexdigest()
            if program_text is not None
            else None
        ),
        "width": maps.width,
        "height": maps.height_px,
        "view": {"x1": view.x1, "y1": view.y1, "x2": view.x2, "y2": view.y2},
        "texel_size": {"dx": dx, "dy": dy},
        "square_texels": square,
        "units": "coordinate units (positions, sizes and heights share one unit)",
        "physical_size": physical_size(maps, unit_m),
        "orientation": "row 0 is the top of the image (largest Y); column 0 is the smallest X",
        "n_layers": maps.n_layers,
        "quantisation_8bit": "clip [0, 1], x255, +0.5, truncate (float32); NaN -> 0",
        "maps": [{"name": spec.name, **map_entries[spec.name]} for spec in selected],
        "nonfinite_values": {name: n for name, n in nonfinite.items() if n},
    }


def _json_safe(value: Any) -> Any:
    """Replace non-finite floats (not valid JSON) by their names, recursively."""
    if isinstance(value, float) and not np.isfinite(value):
        return "nan" if np.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, dict):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    return value


# --------------------------------------------------------------------------------------------
# Entry point


def physical_size(maps: MaterialMaps, unit_m: float | None) -> dict[str, Any] | None:
    """The real-world size of the maps for ``unit_m`` metres per coordinate unit (None when
    unknown): the View's width and height, the texel size and density, and the factor that
    turns heights into metres; ``unit_m`` overrides the program's ``View(..., unit_m=...)``)."""
    view = maps.view
    if unit_m is None:
        unit_m = view.unit_m
    if unit_m is None:
        return None
    width_m = abs(view.x2 - view.x1) * unit_m
    height_m = abs(view.y2 - view.y1) * unit_m
    return {
        "unit_m": unit_m,
        "width_m": width_m,
        "height_m": height_m,
        "texel_m": {"x": width_m / maps.width, "y": height_m / maps.height_px},
        "texels_per_m": maps.width / width_m if width_m > 0 else None,
        "height_scale_m": unit_m,
        "note": "height map values x height_scale_m = displacement in metres",
    }


def write_maps(
    maps: MaterialMaps,
    folder: Path,
    *,
    final_dir: Path | None = None,
    float_format: str = "png",
    maps_subset: Sequence[str] | None = None,
    program_text: str | None = None,
    engine_version: str | None = None,
    extra_meta: dict[str, Any] | None = None,
    encoding: Encoding | None = None,
    unit_m: float | None = None,
    presets: Sequence[str] = (),
    name: str = "material",
) -> ExportResult:
    """Encode the maps into ``folder`` (a staging folder) and build the manifest.

    The manifest is returned, not written: other files may join the folder before
    :func:`write_manifest` lists them all. ``final_dir`` is where the files will be installed
    (the paths in the result point there). ``encoding`` (default: ``float_format`` with 8-bit
    PNGs) decides the map files; each of ``presets`` (names from
    :data:`matloom.io.presets.PRESETS`) writes its subfolder, named files ``<name>_...``.
    """
    enc = encoding or Encoding(float_format=float_format)
    if unit_m is None:  # the program's View(..., unit_m=...) unless the caller overrides it
        unit_m = maps.view.unit_m
    selected = select_maps(maps_subset)
    writers = preset_writers(presets)
    version = engine_version if engine_version is not None else _default_engine_version()
    final = folder if final_dir is None else final_dir
    entries: dict[str, dict[str, Any]] = {}
    files: dict[str, Path] = {}
    for spec in selected:
        written, override = write_map(maps, spec, folder, enc)
        if written:
            files[spec.name] = final / written[0]
        for extra in written[1:]:
            key = f"{spec.name}_float" if extra == spec.float_file else f"{spec.name}_{extra}"
            files[key] = final / extra
        described = spec.describe()
        if enc.all_exr or not written:
            described.pop("float_file", None)
            described.pop("float_encoding", None)
        entries[spec.name] = {**described, **override, **_map_stats(maps, spec)}
    manifest = _manifest(maps, selected, entries, program_text, version, unit_m)
    manifest.update(tiling_fields(maps, selected))  # tileable renders: seam ratios
    manifest["encoding"] = {
        "float_format": enc.float_format,
        "bits": enc.bits,
        "exr_precision": enc.exr_precision if enc.all_exr else "float",
        "normal_conventions": list(enc.normals),
        "constants_as_values": enc.constants,
    }
    if enc.float_format == "png16" and "height" in entries:
        manifest["height_png16"] = _write_height_png16(maps.height, folder)
        files["height16"] = final / HEIGHT_PNG16_NAME
    if writers:
        from matloom.io.presets.common import PresetInput

        source = PresetInput(maps, name=name, unit_m=unit_m, bits=enc.bits)
        manifest["presets"] = {}
        for preset, writer in writers.items():
            (folder / preset).mkdir(exist_ok=True)
            manifest["presets"][preset] = writer(source, folder / preset)
            files[f"preset:{preset}"] = final / preset
    manifest["name"] = name  # the prefix of engine export files; `render` reuses it
    if extra_meta:
        manifest["extra"] = dict(extra_meta)
    manifest = _json_safe(manifest)
    files["manifest"] = final / MANIFEST_NAME
    return ExportResult(
        out_dir=final,
        files=files,
        manifest=manifest,
        nonfinite_counts=dict(manifest["nonfinite_values"]),
    )


def preset_writers(presets: Sequence[str]) -> dict[str, Any]:
    """The writer of each requested preset (unknown names raise ValueError; the writers'
    modules are imported when one is called)."""
    if not presets:
        return {}
    if isinstance(presets, str):
        raise TypeError("presets must be a sequence of preset names, not a string")
    from matloom.io.presets import PRESETS

    unknown = sorted(set(presets) - set(PRESETS))
    if unknown:
        raise ValueError(f"unknown preset(s) {unknown}; valid presets: {', '.join(PRESETS)}")
    return {p: PRESETS[p].write for p in dict.fromkeys(presets)}


def write_manifest(result: ExportResult, folder: Path) -> None:
    """Write ``material.json`` into ``folder``, listing every file there with its SHA-256.

    The list is what this render wrote; a reader can check that a folder is complete and
    unmixed by comparing it with the files.
    """
    from matloom.io.outdir import STAGING_MARKER, file_sha256

    listed = {
        p.relative_to(folder).as_posix(): file_sha256(p)
        for p in sorted(folder.rglob("*"))
        if p.is_file() and p.name not in (STAGING_MARKER, MANIFEST_NAME)
    }
    result.manifest["files"] = listed
    text = json.dumps(result.manifest, indent=2, allow_nan=False, default=str) + "\n"
    atomic_write_bytes(folder / MANIFEST_NAME, text.encode("utf-8"))


def check_unit_m(unit_m: float | None) -> None:
    """Raise ValueError unless ``unit_m`` is None or a finite number > 0."""
    if unit_m is not None and not (isinstance(unit_m, (int, float)) and 0 < unit_m < float("inf")):
        raise ValueError(f"unit_m must be a finite number of metres > 0, got {unit_m!r}")
