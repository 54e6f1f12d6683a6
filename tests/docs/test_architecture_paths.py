"""Every file or folder docs/architecture.md names exists: the "how to add" recipes touch the
files they say."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "architecture.md"
#: Folders a short path in the doc may be relative to (``kernels/abi.py`` is the engine's).
BASES = (
    "",
    "matloom",
    "matloom/engine",
    "matloom/author",
    "matloom/library",
    "matloom/io",
    "tests/engine",
)
PATH = re.compile(r"`([A-Za-z_][\w./*-]*(?:\.py|\.md|\.toml|/))[`.:]")


def _resolves(path: str) -> bool:
    if "/" not in path:  # a bare file name, in the row of its folder
        return any((ROOT / "matloom").rglob(path)) or any((ROOT / "tests").rglob(path))
    for base in BASES:
        candidate = ROOT / base / path
        if "*" in path:
            if any(candidate.parent.glob(candidate.name)):
                return True
        elif candidate.exists():
            return True
    return False


def test_the_architecture_doc_names_only_existing_files() -> None:
    named = sorted(set(PATH.findall(DOC.read_text(encoding="utf-8"))))
    assert len(named) > 40  # the doc does name the files
    missing = [path for path in named if not _resolves(path)]
    assert missing == []


def test_the_check_catches_a_missing_file() -> None:
    assert _resolves("runtime/sinks.py")
    assert not _resolves("runtime/no_such_module.py")
    assert not _resolves("no_such_module.py")
