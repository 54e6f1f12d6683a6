"""Output folders never read, adopt or delete anything outside themselves (issue 22, defect 1).

A symlinked sub-folder, a manifest or index naming paths through it or out of the folder, a
symlinked index or lock file: each once let MatLoom treat a user's file elsewhere as its own.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest

from matloom.io import outdir
from matloom.io.outdir import INDEX_NAME, LOCK_NAME, OutputError, OutputFolder


def write_batch(folder: Path, files: dict[str, bytes], group: str = "g") -> None:
    with OutputFolder(folder) as out, out.batch(group) as staging:
        for rel, data in files.items():
            (staging / rel).write_bytes(data)


@pytest.fixture
def victim(tmp_path: Path) -> Path:
    """A user's folder outside the output folder, holding a precious file."""
    folder = tmp_path / "documents"
    folder.mkdir()
    (folder / "thesis.docx").write_bytes(b"four years of work")
    return folder


@pytest.fixture
def out(tmp_path: Path, victim: Path) -> Path:
    """An output folder whose ``sub`` is a symlink to the user's documents."""
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "sub").symlink_to(victim)
    return folder


def index_listing(rel: str, data: bytes, group: str) -> str:
    digest = hashlib.sha256(data).hexdigest()
    entry = {"sha256": digest, "size": len(data), "mtime_ns": 0, "group": group}
    return json.dumps({"format": "matloom-files", "format_version": 1, "files": {rel: entry}})


def test_old_manifest_naming_a_file_through_a_symlink_is_not_adopted_or_deleted(
    out: Path, victim: Path, tmp_path: Path
) -> None:
    (tmp_path / "outside.txt").write_text("keep")
    listed = ["sub/thesis.docx", "../outside.txt", str(tmp_path / "outside.txt")]
    manifest = {"format": "matloom-material", "maps": [{"file": name} for name in listed]}
    (out / "material.json").write_text(json.dumps(manifest))
    write_batch(out, {"basecolor.png": b"new", "material.json": b"{}"}, group="render")
    assert (victim / "thesis.docx").read_bytes() == b"four years of work"
    assert (tmp_path / "outside.txt").read_text() == "keep"
    index = json.loads((out / INDEX_NAME).read_text())
    assert sorted(index["files"]) == ["basecolor.png", "material.json"]


def test_index_entry_through_a_symlink_with_the_right_hash_is_not_deleted(
    out: Path, victim: Path
) -> None:
    (out / INDEX_NAME).write_text(index_listing("sub/thesis.docx", b"four years of work", "g"))
    write_batch(out, {"a.png": b"1"})  # a new batch of group "g" drops g's old files
    assert (victim / "thesis.docx").read_bytes() == b"four years of work"
    (out / INDEX_NAME).write_text(index_listing("sub/thesis.docx", b"four years of work", "g"))
    with OutputFolder(out) as folder:
        assert not folder.owns("sub/thesis.docx")
        assert "sub/thesis.docx" not in folder.remove_owned()
    assert (victim / "thesis.docx").read_bytes() == b"four years of work"


def test_a_symlinked_index_is_not_read(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.png").write_bytes(b"the user's own a.png")
    elsewhere = tmp_path / "planted-index.json"
    elsewhere.write_text(index_listing("a.png", b"the user's own a.png", "g"))
    (out / INDEX_NAME).symlink_to(elsewhere)
    write_batch(out, {"b.png": b"2"})
    assert (out / "a.png").read_bytes() == b"the user's own a.png"
    with pytest.raises(OutputError, match="a.png, not written by MatLoom"):
        write_batch(out, {"a.png": b"3"})


def test_manifests_are_read_only_inside_the_folder(
    out: Path, victim: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (out / "maps").symlink_to(victim)
    manifest = {"format": "matloom-material", "maps": [{"file": "thesis.docx"}]}
    (victim / "material.json").write_text(json.dumps(manifest))
    (out / "renders").symlink_to(victim)
    (out / "record.json").write_text(json.dumps({"prompt": "p", "programs": []}))
    read: list[Path] = []
    real_read_json = outdir._read_json
    monkeypatch.setattr(outdir, "_read_json", lambda p: read.append(p) or real_read_json(p))
    write_batch(out, {"a.png": b"1"})
    assert read, "the index and manifests are read through _read_json"
    assert all(p.resolve().is_relative_to(out.resolve()) for p in read), read
    assert (victim / "thesis.docx").read_bytes() == b"four years of work"
    assert sorted(json.loads((out / INDEX_NAME).read_text())["files"]) == ["a.png", "record.json"]


def test_a_symlinked_lock_file_creates_nothing_elsewhere(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    target = tmp_path / "created-elsewhere"
    (out / LOCK_NAME).symlink_to(target)
    with pytest.raises(OutputError, match="symlink"):
        OutputFolder(out).open()
    assert not target.exists() and (out / LOCK_NAME).is_symlink()


def test_delete_walks_real_folders_only(out: Path, victim: Path) -> None:
    """A parent swapped for a symlink after the ownership check still stops the delete."""
    with OutputFolder(out) as folder:
        assert folder._unlink_inside("sub/thesis.docx") is False
    assert (victim / "thesis.docx").exists()


def test_old_sibling_staging_of_another_folder_is_kept(tmp_path: Path) -> None:
    other = tmp_path / ".out.x.tmp-0123456789ab"  # ".<name>.tmp-…" of a folder "out.x"
    other.mkdir()
    (other / "basecolor.png").write_bytes(b"x")
    with OutputFolder(tmp_path / "out"):
        pass
    assert (other / "basecolor.png").exists()
