"""The final material of a run, installed in the folder layout ``matloom render`` writes.

``material.mat``, ``preview.png`` (the flat preview of the exported maps), the maps and
``material.json`` (listing every one of those files with its SHA-256) are staged and installed
as one batch of the run folder's :class:`~matloom.io.outdir.OutputFolder`, so the run folder is
also a render folder (``matloom blender RUN`` reads it): a folder without ``material.json`` is
one whose export did not finish, and files MatLoom did not write are never replaced or deleted.
The run's own files (``record.json``, ``renders/``) stay beside the batch.
"""

from __future__ import annotations

import re
import unicodedata
from typing import TYPE_CHECKING

from matloom.author.records import RecordStore

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps
    from matloom.engine.session import Session
    from matloom.runtime.job import RenderJob

#: The batch group of the final material (the group ``matloom render`` writes).
EXPORT_GROUP = "render"
#: Longest material name made from a prompt (whole words are kept).
NAME_CHARS = 48


def export_job(program: str, size: int, *, name: str = "material", prompt: str = "") -> RenderJob:
    """The render job of a run's final material: ``program`` at ``size`` x ``size`` with its
    preview, ``name`` in material.json, the prompt recorded as its source."""
    from matloom.runtime.job import RenderJob

    return RenderJob(
        program,
        size,
        size,
        name=name,
        extra={"source": "matloom generate", "prompt": prompt},
    )


def evaluate_for_export(program: str, size: int, *, session: Session | None = None) -> MaterialMaps:
    """``program``'s maps at ``size`` x ``size``, as the export evaluates them (the preview's
    shading counted in the memory budget), in ``session`` (default: the process's)."""
    from matloom.runtime.run import evaluate_job

    return evaluate_job(export_job(program, size), session)


def material_name(text: str) -> str:
    """A material name from a prompt or a library entry name: its ASCII letters and digits,
    lower case, words joined by ``_`` (``"Red brick, wet"`` -> ``red_brick_wet``), at most
    :data:`NAME_CHARS` characters; ``material`` when nothing is left."""
    ascii_text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    words = re.findall(r"[a-z0-9]+", ascii_text.lower())
    name = ""
    for word in words:
        longer = f"{name}_{word}" if name else word
        if len(longer) > NAME_CHARS:
            break
        name = longer
    return name or (words[0][:NAME_CHARS] if words else "material")


def export_final(
    store: RecordStore,
    program: str,
    size: int,
    maps: MaterialMaps | None = None,
    *,
    name: str = "material",
    session: Session | None = None,
) -> dict[str, str]:
    """Install the final ``program`` (evaluated at ``size``, unless its ``maps`` at that size
    are given) into the run folder; return the written files by role, relative to the folder
    (``program``, ``preview``, ``manifest`` and one per map). ``name`` is the material's name
    (``name`` in material.json, the prefix of engine export files). ``material.mat`` is
    written with the run's secrets redacted (material.json hashes the program itself). The
    engine work runs in ``session`` (default: the process's)."""
    from dataclasses import replace

    from matloom.runtime.run import run_render
    from matloom.runtime.sinks import FolderSink

    out = store.out
    if out is None:
        raise RuntimeError("the run folder is not open (RecordStore.attach)")
    job = export_job(program, size, name=name, prompt=store.record.prompt)
    job = replace(job, program_file_text=store.redactor().text(program + "\n"))
    result = run_render(job, FolderSink(out, group=EXPORT_GROUP), session, maps=maps)
    return result.files


def tileable_text(program: str) -> str:
    """``program`` with ``View(..., tileable=True)`` (canonical text)."""
    from matloom.lang import api
    from matloom.lang.tileable import make_tileable

    return api.format(make_tileable(api.parse(program)))
