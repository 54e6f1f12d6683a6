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
from matloom.author.views import RENDER_LOCK

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps

#: The batch group of the final material (the group ``matloom render`` writes).
EXPORT_GROUP = "render"
#: Longest material name made from a prompt (whole words are kept).
NAME_CHARS = 48


def evaluate_for_export(program: str, size: int) -> MaterialMaps:
    """``program``'s maps at ``size`` x ``size``, as the export evaluates them (the preview's
    shading counted in the memory budget)."""
    from matloom.engine.evaluate import evaluate
    from matloom.engine.limits import Usage

    return evaluate(program, size, size, usage=Usage(preview_tile=1))


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
) -> dict[str, str]:
    """Install the final ``program`` (evaluated at ``size``, unless its ``maps`` at that size
    are given) into the run folder; return the written files by role, relative to the folder
    (``program``, ``preview``, ``manifest`` and one per map). ``name`` is the material's name
    (``name`` in material.json, the prefix of engine export files)."""
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.export import MANIFEST_NAME, write_manifest, write_maps
    from matloom.io.png import save_png
    from matloom.render.preview import shade

    out = store.out
    if out is None:
        raise RuntimeError("the run folder is not open (RecordStore.attach)")
    with RENDER_LOCK:
        if maps is None:
            maps = evaluate_for_export(program, size)
        preview = shade(maps)
    text = store.redactor().text(program + "\n")
    with out.batch(EXPORT_GROUP, marker=MANIFEST_NAME) as staging:
        result = write_maps(
            maps,
            staging,
            final_dir=out.path,
            program_text=program,
            extra_meta={"source": "matloom generate", "prompt": store.record.prompt},
            name=name,
        )
        result.manifest["name"] = name
        atomic_write_bytes(staging / "material.mat", text.encode("utf-8"))
        save_png(staging / "preview.png", preview)
        write_manifest(result, staging)
    files = {"program": "material.mat", "preview": "preview.png"}
    for role, path in result.files.items():
        files[role] = path.relative_to(out.path).as_posix()
    return files


def tileable_text(program: str) -> str:
    """``program`` with ``View(..., tileable=True)`` (canonical text)."""
    import matloom
    from matloom.lang.tileable import make_tileable

    return matloom.format(make_tileable(matloom.parse(program)))
