"""``/api/export`` and ``/api/export.zip``: exactly what ``matloom render`` writes.

The export dialog's options become one :class:`~matloom.runtime.job.RenderJob`, built as the
``render`` command builds it (the checked program, the encoding, presets, physical size, name,
map subset, AO radius, preview, program seed, and ``extra`` naming the source file), and run by
:func:`~matloom.runtime.run.run_render`: into a :class:`~matloom.runtime.sinks.FolderSink` inside
the workspace (the output folder's ownership rules apply: a file MatLoom did not write is never
replaced), or into a :class:`~matloom.runtime.sinks.MemorySink` zipped for download. So
``matloom render FILE -o OUT`` run in the workspace folder with the same options writes the same
bytes.
"""

from __future__ import annotations

import io
import re
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.engine.session import Session
from matloom.runtime.job import RenderJob
from matloom.studio.program import checked
from matloom.studio.protocol import (
    ApiError,
    need_str,
    opt_bool,
    opt_float,
    opt_int,
    opt_list,
    opt_str,
)
from matloom.studio.workspace import Workspace

#: ``normal`` option -> the conventions written (as ``render --normal``).
NORMALS = {"gl": ("gl",), "dx": ("dx",), "both": ("gl", "dx")}
#: Files not worth deflating in the zip (compressed already).
_STORED = (".png", ".exr", ".glb", ".ktx2", ".jpg")
_ZIP_TIME = (1980, 1, 1, 0, 0, 0)
_MANIFEST_MAX_BYTES = 4 * 1024 * 1024


@dataclass(frozen=True)
class ExportOptions:
    """The export dialog's options (``render``'s flags of the same names)."""

    job: RenderJob
    out: str | None


def material_name(given: str | None, source: str, workspace: Workspace) -> str:
    """``render``'s ``--name``: the given name, else the name recorded beside a run folder's
    ``material.mat``, else the source file's stem; letters, digits, ``_`` and ``-`` only."""
    if given is None or not given.strip():
        given = _recorded_name(source, workspace) or Path(source).stem or "material"
    text = re.sub(r"[^A-Za-z0-9_-]+", "_", given).strip("_")[:64]
    if not text:
        raise ApiError(400, f"'name' {given!r} has no letter or digit to name files with")
    return text


def _recorded_name(source: str, workspace: Workspace) -> str | None:
    from matloom.io.reading import read_json_file

    if Path(source).name != "material.mat":
        return None
    try:
        manifest = workspace.path(str(Path(source).parent / "material.json"), program=False)
        data = read_json_file(manifest, _MANIFEST_MAX_BYTES)
    except (ApiError, OSError, ValueError):
        return None
    name = data.get("name") if isinstance(data, dict) else None
    return name if isinstance(name, str) and name else None


def export_options(body: dict[str, Any], workspace: Workspace, *, folder: bool) -> ExportOptions:
    """The checked options of an export body (``out`` only with ``folder``)."""
    from matloom.io.encode import Encoding
    from matloom.io.export import MAP_NAMES
    from matloom.io.presets import PRESETS

    text = need_str(body, "text")
    out = need_str(body, "out", empty=False) if folder else None
    size = opt_int(body, "size", 512, 1, 8192)
    width = opt_int(body, "width", size, 1, 8192)
    height = opt_int(body, "height", size, 1, 8192)
    fmt = opt_str(body, "format", "png") or "png"
    normal = opt_str(body, "normal", "gl") or "gl"
    if normal not in NORMALS:
        raise ApiError(400, f"'normal' must be one of {', '.join(NORMALS)}")
    try:
        encoding = Encoding(
            fmt,
            opt_int(body, "bits", 8),
            opt_str(body, "exr_precision", "half") or "half",
            NORMALS[normal],
            opt_bool(body, "constants"),
        )
    except ValueError as err:
        raise ApiError(400, str(err)) from None
    presets = tuple(opt_list(body, "presets", str))
    unknown = [p for p in presets if p not in PRESETS]
    maps = opt_list(body, "maps", str)
    unknown += [m for m in maps if m not in MAP_NAMES]
    if unknown:
        raise ApiError(400, f"unknown preset or map(s): {', '.join(unknown)}")
    unit_m = opt_float(body, "unit_m")
    if unit_m is not None and unit_m <= 0:
        raise ApiError(400, f"'unit_m' must be > 0, got {unit_m:g}")
    ao_radius = opt_float(body, "ao_radius")
    source = opt_str(body, "source") or workspace.opened or "studio.mat"
    program = checked(text)
    job = RenderJob(
        program,
        width,
        height,
        tileable=opt_bool(body, "tileable"),
        stretch=opt_bool(body, "stretch"),
        encoding=encoding,
        presets=presets,
        unit_m=unit_m,
        name=material_name(opt_str(body, "name"), source, workspace),
        map_names=tuple(maps) if maps else None,
        ao_radius=ao_radius,
        previews=("preview",) if opt_bool(body, "preview", True) else (),
        program_seed=opt_int(body, "program_seed", 0),
        extra={"ao_radius_units": ao_radius, "source": source},
        source=source,
        source_text=text,
    )
    return ExportOptions(job, out)


def _run(job: RenderJob, sink: Any, session: Session) -> Any:
    from matloom.engine.limits import LimitError
    from matloom.io.outdir import OutputError
    from matloom.runtime.job import RenderJobError
    from matloom.runtime.run import run_render

    try:
        return run_render(job, sink, session)
    except RenderJobError as err:
        raise ApiError(422 if err.field in ("program", "program_unit_m") else 400, str(err),
                       field=err.field) from None  # fmt: skip
    except LimitError as err:
        raise ApiError(422, str(err)) from None
    except OutputError as err:
        raise ApiError(400, str(err)) from None


def export_folder(options: ExportOptions, workspace: Workspace, session: Session) -> dict:
    """Render into the folder ``options.out`` of the workspace (a worker runs this)."""
    from matloom.runtime.sinks import FolderSink

    assert options.out is not None
    target = workspace.folder(options.out)
    result = _run(options.job, FolderSink(target), session)
    return {
        "folder": workspace.rel(target),
        "files": sorted({"material.json", *result.manifest.get("files", {})}),
        "manifest": result.manifest,
        "notes": result.notes,
        "timings": {k: round(v * 1000, 1) for k, v in result.timings.items()},
    }


def export_zip(options: ExportOptions, session: Session) -> tuple[bytes, str]:
    """The same files as a zip (under a folder named after the material) and its file name."""
    from matloom.runtime.sinks import MemorySink

    sink = MemorySink()
    _run(options.job, sink, session)
    name = options.job.name
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        for rel, data in sink.files.items():
            info = zipfile.ZipInfo(f"{name}/{rel}", _ZIP_TIME)
            info.external_attr = 0o644 << 16
            stored = rel.lower().endswith(_STORED)
            info.compress_type = zipfile.ZIP_STORED if stored else zipfile.ZIP_DEFLATED
            archive.writestr(info, data)
    return buffer.getvalue(), f"{name}.zip"
