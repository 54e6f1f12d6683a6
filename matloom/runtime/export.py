"""``export_maps``: maps evaluated already, written to a folder by the one render job."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from matloom.io.encode import Encoding
from matloom.io.export import ExportResult, preset_writers, select_maps
from matloom.runtime.job import RenderJob
from matloom.runtime.run import run_render
from matloom.runtime.sinks import FolderSink

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps


def export_maps(
    maps: MaterialMaps,
    out_dir: str | os.PathLike[str],
    *,
    float_format: str = "png",
    maps_subset: Sequence[str] | None = None,
    program_text: str | None = None,
    engine_version: str | None = None,
    extra_meta: dict[str, Any] | None = None,
    bits: int = 8,
    exr_precision: str = "half",
    normals: Sequence[str] = ("gl",),
    constants: bool = False,
    unit_m: float | None = None,
    presets: Sequence[str] = (),
    name: str = "material",
) -> ExportResult:
    """Write ``maps`` into the folder ``out_dir`` through a staged, locked install (the maps
    and ``material.json``; no program file, no preview).

    ``float_format``: "png" (default: PNG maps, float32 EXR for ior/height/emissive), "exr"
    (every map as EXR, ``exr_precision`` "half" or "float") or "png16" ("png" plus
    height16.png). ``bits``: 8 or 16 for every PNG map. ``normals``: "gl" and/or "dx"
    (``normal_gl`` / ``normal_dx`` files). ``constants``: constant maps become manifest values
    instead of files. ``unit_m``: metres per coordinate unit (physical size in the manifest and
    the presets). ``presets``: names from :data:`matloom.io.presets.PRESETS`, each written to
    its subfolder with files named ``<name>_...``.
    ``maps_subset``: names from :data:`~matloom.io.export.MAP_NAMES` to write (default: all,
    in that order); an unknown name raises ValueError before anything is written.
    ``program_text`` is hashed (SHA-256) into the manifest; ``extra_meta`` is stored under the
    manifest key "extra". MatLoom's files from a previous export into ``out_dir`` are
    replaced; any other file there is left alone, and one that would be overwritten raises
    :class:`matloom.io.outdir.OutputError` before anything changes.
    """
    # bad arguments fail before the folder is touched (a string is no list of names)
    encoding = Encoding(float_format, bits, exr_precision, tuple(normals), constants)
    select_maps(maps_subset)
    preset_writers(presets)
    job = RenderJob(
        program_text,
        maps.width,
        maps.height_px,
        encoding=encoding,
        presets=tuple(presets),
        unit_m=unit_m,
        name=name,
        map_names=None if maps_subset is None else tuple(maps_subset),
        previews=(),
        extra=extra_meta,
        write_program=False,
        engine_version=engine_version,
    )
    result = run_render(job, FolderSink(out_dir), maps=maps)
    root = result.root
    assert root is not None
    return ExportResult(
        out_dir=root,
        files={role: root / rel for role, rel in result.files.items()},
        manifest=result.manifest,
        nonfinite_counts=result.nonfinite_counts,
    )
