"""Blender jobs: what the worker inside Blender needs, as plain JSON.

A job names the maps (absolute paths, Blender colour spaces, constants), the surface geometry
(plane size and displacement scale, in metres when the manifest has a physical size), the
layouts from :mod:`matloom.blender.layouts` with their cameras already placed, the packed
ORM / mask map a preset wrote (:mod:`matloom.blender.packed`), and the output paths. Sources
are a program file (rendered here with the core into a temporary staged folder that
:meth:`Source.cleanup` removes) or a folder exported by ``matloom render``.
"""

from __future__ import annotations

import json
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.blender.layouts import COMMON, LAYOUTS, camera_for_view, layout_json
from matloom.blender.listed import UnlistedFileError, listed_file
from matloom.blender.packed import PackedTextureError, packed_texture
from matloom.blender.tempdirs import TempDir
from matloom.io.atomic import atomic_write_bytes
from matloom.io.reading import read_json_file

JOB_FORMAT = "matloom-blender-job"
JOB_VERSION = 1
MANIFEST = "material.json"
#: What ``--save-material-only`` writes (the material alone, marked as an asset).
MATERIAL_BLEND = "material.blend"

#: Principled BSDF input for each scalar map (the reference's wiring).
SCALAR_INPUTS: dict[str, str] = {
    "metallic": "Metallic",
    "roughness": "Roughness",
    "sheen": "Sheen Weight",
    "coat": "Coat Weight",
    "transmission": "Transmission Weight",
    "subsurface": "Subsurface Weight",
    "anisotropy": "Anisotropic",
    "ior": "IOR",
}
#: Fixed: the reference falls back to IOR 1.0 when there is no ior map.
DEFAULT_IOR = 1.5
DISPLACEMENT_MODES = ("true", "bump", "off")


class BlenderJobError(Exception):
    """A source or option that cannot become a job; the message is one line for the user."""


class ProgramSourceError(BlenderJobError):
    """A program with errors; ``diagnostics`` is the formatted report (exit status 2)."""

    def __init__(self, diagnostics: str) -> None:
        super().__init__(diagnostics)
        self.diagnostics = diagnostics


@dataclass
class Source:
    """A material ready for Blender: its maps folder and manifest."""

    name: str
    path: str
    maps_dir: Path
    manifest: dict[str, Any]
    temp_dir: TempDir | None = None

    def cleanup(self) -> None:
        """Remove the temporary folder this source rendered into (only that one)."""
        if self.temp_dir is not None:
            self.temp_dir.remove()
            self.temp_dir = None


@dataclass
class RenderOptions:
    layouts: tuple[str, ...] = ("flat",)
    size: int = 512
    samples: int | None = None
    views: str = "1"
    displacement: str = "true"
    save: str | None = None
    save_material_only: bool = False
    device: str = "auto"
    extra: dict[str, Any] = field(default_factory=dict)

    def validate(self) -> None:
        bad = [name for name in self.layouts if name not in LAYOUTS]
        if bad or not self.layouts:
            raise BlenderJobError(f"unknown layout {', '.join(bad)}; choose flat, staged or both")
        if self.displacement not in DISPLACEMENT_MODES:
            raise BlenderJobError("--displacement must be true, bump or off")
        if self.views not in ("1", "all"):
            raise BlenderJobError("--views must be 1 or all")
        if self.save is not None and not _BLEND_NAME.match(self.save):
            raise BlenderJobError(
                f"--save {self.save!r}: give a file name ending in .blend (no folders); it is "
                "written into the output folder"
            )
        # compared without case: on macOS and Windows the two names are one file too
        if self.save_material_only and (self.save or "").lower() == MATERIAL_BLEND.lower():
            raise BlenderJobError(
                f"--save {self.save} and --save-material-only would both write "
                f"{MATERIAL_BLEND}: give --save another name"
            )


#: A real manifest is tens of kilobytes; a huge one is not read into memory.
_MANIFEST_MAX_BYTES = 50_000_000
_BLEND_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*\.blend$")
_NAME = re.compile(r"[^A-Za-z0-9_-]+")


def material_name(path: str) -> str:
    """A file-name-safe material name from a source path."""
    stem = Path(os.path.normpath(path)).name
    if stem.endswith(".mat"):
        stem = stem[:-4]
    return _NAME.sub("_", stem).strip("_") or "material"


# ------------------------------------------------------------------------ sources


def read_manifest(folder: Path) -> dict[str, Any]:
    """The ``material.json`` of an exported folder, checked; :class:`BlenderJobError` if not."""
    manifest_path = folder / MANIFEST
    if manifest_path.is_symlink():  # never read a manifest from outside the folder
        raise BlenderJobError(
            f"{manifest_path} is a symlink; MatLoom reads only files inside the folder"
        )
    if not manifest_path.is_file():
        raise BlenderJobError(
            f"{folder} has no {MANIFEST}: not a complete folder exported by `matloom render` "
            "(export one with `matloom render PROGRAM -o DIR`, or pass the program file)"
        )
    try:  # no symlink followed even if one appears after the check above; size-capped
        data = read_json_file(manifest_path, _MANIFEST_MAX_BYTES)
    except (OSError, ValueError) as err:
        raise BlenderJobError(f"cannot read {manifest_path}: {err}") from None
    if not isinstance(data, dict) or data.get("format") != "matloom-material":
        raise BlenderJobError(f"{manifest_path} is not a MatLoom material manifest")
    if not isinstance(data.get("maps"), list):
        raise BlenderJobError(f"{manifest_path} lists no maps")
    return data


def check_source(path: str) -> None:
    """Fail early (one line) for a missing path, a folder that is no export, or one whose
    manifest names a file Blender may not read (:mod:`matloom.blender.listed`)."""
    target = Path(path)
    if target.is_dir():
        folder = target.absolute()
        manifest = read_manifest(folder)
        material_maps(manifest, folder)
        try:
            packed_texture(manifest, folder)
        except PackedTextureError as err:
            raise BlenderJobError(str(err)) from None
    elif not target.is_file():
        raise BlenderJobError(f"{path}: no such program file or folder")


def load_source(
    path: str, *, size: int = 512, unit_m: float | None = None, program_seed: int = 0
) -> Source:
    """A folder exported by ``matloom render``, or a program file rendered now at ``size``."""
    target = Path(path)
    name = material_name(path)
    if target.is_dir():
        folder = target.absolute()
        return Source(name, path, folder, read_manifest(folder))
    if not target.is_file():
        raise BlenderJobError(f"{path}: no such program file or folder")
    temp = TempDir()  # marked and locked: a killed run's folder is removed by the next run
    try:
        folder = temp.path / "maps"
        _render_program(target, folder, size, unit_m, program_seed, name)
        return Source(name, path, folder, read_manifest(folder), temp)
    except BaseException:
        temp.remove()
        raise


def _render_program(
    path: Path, out: Path, size: int, unit_m: float | None, program_seed: int, name: str
) -> None:
    """Render the program file ``path`` into ``out`` as ``render`` would (the maps and
    material.json: no preview, no program file); notes on stderr."""
    from matloom.engine.limits import LimitError
    from matloom.lang.api import analyse
    from matloom.lang.diagnostics import format_diagnostics
    from matloom.runtime.job import RenderJob, RenderJobError
    from matloom.runtime.run import run_render
    from matloom.runtime.sinks import FolderSink

    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise BlenderJobError(f"cannot read {path}: {err}") from None
    program, diags = analyse(text)
    errors = [d for d in diags if d.is_error]
    if program is None or errors:
        raise ProgramSourceError(format_diagnostics(errors, str(path)))
    job = RenderJob(
        program,
        size,
        size,
        unit_m=unit_m,
        name=name,
        previews=(),
        program_seed=program_seed,
        extra={"source": str(path)},
        source=str(path),
        source_text=text,
        write_program=False,
    )
    try:
        run_render(job, FolderSink(out), notify=lambda line: print(line, file=sys.stderr))
    except (RenderJobError, LimitError) as err:
        raise BlenderJobError(str(err)) from None


# ------------------------------------------------------------------------ maps


def blender_colour_space(description: str) -> str:
    """Blender's colour space for a manifest ``colour_space`` text."""
    text = description.lower()
    if text.startswith("srgb"):
        return "sRGB"
    if text.startswith("linear rgb"):
        return "Linear Rec.709"
    return "Non-Color"


def material_maps(manifest: dict[str, Any], folder: Path) -> dict[str, dict[str, Any]]:
    """Per map: ``file`` (absolute, or None for a constant), ``colour_space``, ``constant`` and
    for some maps how to decode them (``scale``, ``flip_green``, ``alpha``)."""
    out: dict[str, dict[str, Any]] = {}
    for entry in manifest["maps"]:
        if not isinstance(entry, dict) or not isinstance(entry.get("name"), str):
            continue
        name = entry["name"]
        item: dict[str, Any] = {
            "file": None,
            "colour_space": blender_colour_space(str(entry.get("colour_space", ""))),
            "constant": entry.get("constant"),
        }
        file = entry.get("file")
        if name == "normal":
            files = entry.get("files") or {}
            if isinstance(files, dict) and files.get("gl"):
                file = files["gl"]
            elif isinstance(files, dict) and files.get("dx"):
                file, item["flip_green"] = files["dx"], True
        if name == "anisotropy_angle":
            # degrees -> Blender's rotation (1 = 360 degrees); the float copy is unreduced
            if entry.get("float_file"):
                file, item["scale"] = entry["float_file"], 1.0 / 360.0
            else:
                item["scale"] = 180.0 / 360.0  # the 8-bit map stores angle / 180
            item["colour_space"] = "Non-Color"
        if name == "basecolor":
            item["alpha"] = "png8-rgba" in str(entry.get("encoding", "")) or "alpha" in str(
                entry.get("colour_space", "")
            )
        if isinstance(file, str) and file:
            try:
                item["file"] = str(listed_file(folder, file, manifest))
            except UnlistedFileError as err:
                raise BlenderJobError(str(err)) from None
        elif item["constant"] is None:
            continue
        out[name] = item
    return out


def surface(manifest: dict[str, Any]) -> dict[str, Any]:
    """The material's plane and displacement scale.

    Without a physical size the plane is 2 units wide (the reference's default plane) and a
    height of one coordinate unit displaces by ``2 / span`` (the reference's ``2/region_span``).
    Fixed: with a physical size the plane is built in metres and the Displacement node's scale
    is the manifest's ``height_scale_m`` (metres per unit), so the saved material is right at
    real-world scale; the object is scaled uniformly to fit the layout.
    """
    view = manifest.get("view") or {}
    span_x = abs(float(view.get("x2", 1.0)) - float(view.get("x1", 0.0))) or 1.0
    span_y = abs(float(view.get("y2", 1.0)) - float(view.get("y1", 0.0))) or span_x
    physical = manifest.get("physical_size")
    if isinstance(physical, dict) and physical.get("width_m") and physical.get("height_scale_m"):
        width, height = float(physical["width_m"]), float(physical["height_m"])
        scale = float(physical["height_scale_m"])
        return {
            "physical": True,
            "size": [width, height],
            "object_scale": 2.0 / max(width, height),
            "displacement_scale": scale,
            "midlevel": 0.0,
        }
    aspect = span_y / span_x
    size = [2.0, 2.0 * aspect] if aspect <= 1 else [2.0 / aspect, 2.0]
    return {
        "physical": False,
        "size": size,
        "object_scale": 1.0,
        "displacement_scale": 2.0 / max(span_x, span_y),
        "midlevel": 0.0,
    }


# ------------------------------------------------------------------------ jobs


def render_names(options: RenderOptions) -> list[tuple[str, int, str]]:
    """(layout, view, file name) of every image the options ask for."""
    names = []
    for layout_name in options.layouts:
        layout = LAYOUTS[layout_name]
        n = layout.n_views if options.views == "all" else 1
        for view in range(n):
            suffix = f"_view-{view}" if options.views == "all" else ""
            names.append((layout_name, view, f"{layout.file_stem}{suffix}.png"))
    return names


def planned_files(options: RenderOptions) -> list[str]:
    files = [name for _, _, name in render_names(options)]
    if options.save:
        files.append(options.save)
    if options.save_material_only:
        files.append(MATERIAL_BLEND)
    return files


def build_job(source: Source, options: RenderOptions, out_dir: Path) -> dict[str, Any]:
    """The JSON job for ``source``: every output goes into ``out_dir``."""
    options.validate()
    try:
        packed = packed_texture(source.manifest, source.maps_dir)
    except PackedTextureError as err:
        raise BlenderJobError(str(err)) from None
    geometry = surface(source.manifest)
    half_extent = max(geometry["size"]) / 2.0 * geometry["object_scale"]
    layouts = {}
    for layout_name in options.layouts:
        data = layout_json(LAYOUTS[layout_name])
        data["samples"] = options.samples or data["samples"]
        data["resolution"] = options.size
        layouts[layout_name] = data
    renders = []
    for layout_name, view, file_name in render_names(options):
        layout = LAYOUTS[layout_name]
        renders.append(
            {
                "layout": layout_name,
                "view": view,
                "camera": camera_for_view(layout, view, half_extent),
                "world_turn_deg": layout.world_turn_deg[view % len(layout.world_turn_deg)],
                "output": str(out_dir / file_name),
            }
        )
    return {
        "format": JOB_FORMAT,
        "version": JOB_VERSION,
        "name": source.name,
        "source": source.path,
        "maps_dir": str(source.maps_dir),
        "maps": material_maps(source.manifest, source.maps_dir),
        "packed": packed,
        "defaults": {"ior": DEFAULT_IOR},
        "scalar_inputs": SCALAR_INPUTS,
        "surface": geometry,
        "displacement": options.displacement,
        "common": layout_json(COMMON),  # type: ignore[arg-type]
        "layouts": layouts,
        "renders": renders,
        "device": options.device,
        "save_blend": str(out_dir / options.save) if options.save else None,
        "save_material": str(out_dir / MATERIAL_BLEND) if options.save_material_only else None,
    }


def write_job(job: dict[str, Any], path: Path) -> Path:
    return atomic_write_bytes(path, (json.dumps(job, indent=1) + "\n").encode("utf-8"))
