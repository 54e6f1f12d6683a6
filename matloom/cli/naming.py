"""The default material name of `render`: the run's own name, else the file's stem.

`generate` and `render` record the material's name in the folder's `material.json`; a
`material.mat` re-rendered from such a folder keeps that name (engine exports named
`T_red_brick_wall_BC.png`, not `T_material_BC.png`, which would collide in an engine).
"""

from __future__ import annotations

from pathlib import Path

import click

from matloom.cli import params
from matloom.io.reading import read_json_file

#: A run folder's manifest is a few kilobytes; anything far larger is not one of ours.
_MANIFEST_MAX_BYTES = 4 * 1024 * 1024


def default_material_name(program_file: Path) -> str:
    """The name recorded beside ``program_file`` (a run folder's ``material.mat``), else the
    file's stem; always a valid ``--name``."""
    recorded = _recorded_name(program_file)
    if recorded is not None:
        try:
            return params.NAME.convert(recorded, None, None)
        except click.BadParameter:  # a recorded name with no letter or digit: use the stem
            pass
    return params.NAME.convert(program_file.stem, None, None)


def _recorded_name(program_file: Path) -> str | None:
    """``name`` from the regular, non-symlinked ``material.json`` in the same folder, when the
    program is that folder's ``material.mat``; None otherwise (never follows a symlink)."""
    if program_file.name != "material.mat":
        return None
    try:
        data = read_json_file(program_file.parent / "material.json", _MANIFEST_MAX_BYTES)
    except (OSError, ValueError):
        return None
    name = data.get("name") if isinstance(data, dict) else None
    return name if isinstance(name, str) and name else None
