"""Content-addressed cells written atomically: a cell's files are staged in a hidden sibling
folder and renamed into ``root/key`` in one step, so a reader (or a rerun) sees a whole cell or
none, and a task that runs twice (a killed worker's retry) leaves one copy."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import uuid
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any


def content_key(*parts: Any) -> str:
    """A stable 16-hex-digit address of JSON-able ``parts`` (prompt, system spec, seed, version)."""
    blob = json.dumps(parts, sort_keys=True, ensure_ascii=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()[:16]


def commit_cell(root: Path, key: str, write: Callable[[Path], dict[str, Any]]) -> dict[str, Any]:
    """Run ``write(stage_dir)`` and rename the stage to ``root/key``; return its summary.

    The summary is also written as ``cell.json`` inside the cell. If ``root/key`` already exists
    (another attempt finished first) the staged copy is discarded and the existing summary
    returned, so the cell is written exactly once.
    """
    root = Path(root)
    final = root / key
    if final.is_dir():
        return json.loads((final / "cell.json").read_text(encoding="utf-8"))
    stage = root / f".stage-{key}-{uuid.uuid4().hex[:8]}"
    stage.mkdir(parents=True)
    try:
        summary = write(stage)
        (stage / "cell.json").write_text(json.dumps(summary, indent=2, sort_keys=True), "utf-8")
        try:
            os.rename(stage, final)
        except OSError:
            if not final.is_dir():
                raise
            return json.loads((final / "cell.json").read_text(encoding="utf-8"))
        return summary
    finally:
        if stage.exists():
            shutil.rmtree(stage, ignore_errors=True)


def remove_stale_stages(root: Path, keys: Sequence[str]) -> list[str]:
    """Remove the staging folders of ``keys`` under ``root`` that attempts which died left
    behind (a killed worker's half-written cell); return their names. Call it only when no
    attempt at those keys can still be running (after a run)."""
    root = Path(root)
    if not root.is_dir():
        return []
    wanted = {f".stage-{key}-" for key in keys}
    removed = []
    for child in sorted(root.iterdir()):
        name = child.name
        if name.startswith(".stage-") and name[:-8] in wanted and child.is_dir():
            if not child.is_symlink():
                shutil.rmtree(child, ignore_errors=True)
                removed.append(name)
    return removed
