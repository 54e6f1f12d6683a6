"""The shipped studio assets (matloom/studio/static/) are built from studio-web/ sources.

build.mjs records a hash of the sources in build-info.json; this test recomputes it the same way
and fails when a source changed without `make studio-build`, so the package never ships a
front end older than its TypeScript.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
WEB = ROOT / "studio-web"
STATIC = ROOT / "matloom" / "studio" / "static"


def _files(folder: Path) -> list[Path]:
    out: list[Path] = []
    for path in sorted(folder.iterdir(), key=lambda p: p.name):
        out.extend(_files(path) if path.is_dir() else [path])
    return out


def source_hash() -> str:
    """The hash build.mjs writes: each source file's relative path and bytes, in its order."""
    digest = hashlib.sha256()
    for path in [*_files(WEB / "src"), WEB / "package-lock.json", WEB / "build.mjs"]:
        digest.update(path.relative_to(WEB).as_posix().encode() + b"\0")
        digest.update(path.read_bytes())
        digest.update(b"\0")
    return digest.hexdigest()


def test_shipped_assets_match_the_sources() -> None:
    info = json.loads((STATIC / "build-info.json").read_text(encoding="utf-8"))
    assert info["source_sha256"] == source_hash(), (
        "matloom/studio/static is stale against studio-web/: run `make studio-build`"
    )


def test_shipped_assets_are_complete_and_load_nothing_remote() -> None:
    for name in ("index.html", "app.js", "app.css"):
        assert (STATIC / name).is_file(), name
    html = (STATIC / "index.html").read_text(encoding="utf-8")
    js = (STATIC / "app.js").read_text(encoding="utf-8")
    for text in (html, js):
        assert "cdn." not in text and "unpkg.com" not in text and "jsdelivr" not in text
    assert "http://" not in html and "https://" not in html
