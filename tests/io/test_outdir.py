"""Output folders: ownership, staging, locking and cleanup (matloom.io.outdir)."""

from __future__ import annotations

import errno
import json
import os
from pathlib import Path

import numpy as np
import pytest

from matloom.io import outdir
from matloom.io.outdir import INDEX_NAME, LOCK_NAME, OutputError, OutputFolder, save_output_png


def visible(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))


def write_batch(folder: Path, files: dict[str, bytes], group: str = "g", marker: str | None = None):
    with OutputFolder(folder) as out, out.batch(group, marker=marker) as staging:
        for rel, data in files.items():
            (staging / rel).parent.mkdir(parents=True, exist_ok=True)
            (staging / rel).write_bytes(data)


def test_batch_installs_and_keeps_foreign_files(tmp_path: Path) -> None:
    (tmp_path / "notes.txt").write_text("mine")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "thesis.tex").write_text("precious")
    write_batch(tmp_path, {"a.png": b"1", "m.json": b"{}", "deep/x.bin": b"x"}, marker="m.json")
    assert visible(tmp_path) == ["a.png", "deep", "m.json", "notes.txt", "sub"]
    assert (tmp_path / "sub" / "thesis.tex").read_text() == "precious"
    index = json.loads((tmp_path / INDEX_NAME).read_text())
    assert sorted(index["files"]) == ["a.png", "deep/x.bin", "m.json"]
    assert not (tmp_path / LOCK_NAME).exists()


def test_second_batch_replaces_only_its_own_previous_files(tmp_path: Path) -> None:
    write_batch(tmp_path, {"a.png": b"1", "b.png": b"2"})
    (tmp_path / "user.txt").write_text("u")
    write_batch(tmp_path, {"a.png": b"3"})
    assert visible(tmp_path) == ["a.png", "user.txt"]
    assert (tmp_path / "a.png").read_bytes() == b"3"


def test_other_groups_are_kept(tmp_path: Path) -> None:
    write_batch(tmp_path, {"a.png": b"1"}, group="render")
    write_batch(tmp_path, {"report.json": b"{}"}, group="sweep")
    assert visible(tmp_path) == ["a.png", "report.json"]


def test_foreign_file_is_never_overwritten(tmp_path: Path) -> None:
    (tmp_path / "a.png").write_bytes(b"user's own")
    with pytest.raises(OutputError, match=r"a\.png, not written by MatLoom"):
        write_batch(tmp_path, {"a.png": b"new", "b.png": b"new"})
    assert (tmp_path / "a.png").read_bytes() == b"user's own"
    assert visible(tmp_path) == ["a.png"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(outdir.STAGING_PREFIX)]


def test_a_file_changed_since_matloom_wrote_it_is_foreign(tmp_path: Path) -> None:
    write_batch(tmp_path, {"a.png": b"1", "b.png": b"2"})
    (tmp_path / "a.png").write_bytes(b"edited by hand")
    with pytest.raises(OutputError, match="changed since"):
        write_batch(tmp_path, {"a.png": b"3"})
    assert (tmp_path / "a.png").read_bytes() == b"edited by hand"
    # a later batch without a.png must not delete it either
    write_batch(tmp_path, {"c.png": b"4"})
    assert (tmp_path / "a.png").read_bytes() == b"edited by hand"
    assert visible(tmp_path) == ["a.png", "c.png"]


def test_same_content_with_new_mtime_is_still_owned(tmp_path: Path) -> None:
    write_batch(tmp_path, {"a.png": b"1"})
    os.utime(tmp_path / "a.png", (1, 1))  # e.g. copied without preserving times
    write_batch(tmp_path, {"a.png": b"2"})
    assert (tmp_path / "a.png").read_bytes() == b"2"


def test_symlinks_are_foreign(tmp_path: Path) -> None:
    target = tmp_path / "elsewhere.txt"
    target.write_text("keep")
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.png").symlink_to(target)
    with pytest.raises(OutputError):
        write_batch(out, {"a.png": b"x"})
    assert target.read_text() == "keep" and (out / "a.png").is_symlink()


def test_output_path_that_is_a_file(tmp_path: Path) -> None:
    path = tmp_path / "file"
    path.write_text("keep")
    with pytest.raises(OutputError, match="is not a folder"):
        OutputFolder(path).open()
    assert path.read_text() == "keep"


def test_lock_excludes_a_second_writer(tmp_path: Path) -> None:
    with OutputFolder(tmp_path):
        with pytest.raises(OutputError, match="another MatLoom process"):
            OutputFolder(tmp_path).open()
    with OutputFolder(tmp_path):  # released on close
        pass


def test_stale_staging_and_temp_files_are_cleaned(tmp_path: Path) -> None:
    write_batch(tmp_path, {"a.png": b"1"})
    stale = tmp_path / f"{outdir.STAGING_PREFIX}123-abcdef12"
    stale.mkdir()
    (stale / outdir.STAGING_MARKER).write_bytes(b"")
    (stale / "big.exr").write_bytes(b"0" * 1000)
    temp = tmp_path / ".a.png.tmp-0123456789ab"
    temp.write_bytes(b"partial")
    lookalike = tmp_path / f"{outdir.STAGING_PREFIX}user"  # no marker: not ours
    lookalike.mkdir()
    foreign_temp = tmp_path / ".notes.txt.tmp-0123456789ab"  # not a MatLoom file name
    foreign_temp.write_bytes(b"?")
    with OutputFolder(tmp_path):
        pass
    assert not stale.exists() and not temp.exists()
    assert lookalike.exists() and foreign_temp.exists()


def test_a_temp_file_of_the_index_itself_is_cleaned(tmp_path: Path) -> None:
    # a run killed while saving the ownership index leaves its temporary copy behind
    write_batch(tmp_path, {"a.png": b"1"})
    temp = tmp_path / f".{outdir.INDEX_NAME}.tmp-af1f78c49efe"
    temp.write_bytes(b'{"partial')
    with OutputFolder(tmp_path):
        pass
    assert not temp.exists()


def test_old_sibling_staging_folder_is_cleaned(tmp_path: Path) -> None:
    out = tmp_path / "out"
    old = tmp_path / ".out.tmp-0123456789ab"  # MatLoom < 0.4 staged renders beside -o
    old.mkdir()
    (old / "basecolor.png").write_bytes(b"x")
    other = tmp_path / ".out.tmp-fedcba987654"
    other.mkdir()
    (other / "thesis.tex").write_text("not a render")
    with OutputFolder(out):
        pass
    assert not old.exists() and other.exists()


def test_interrupted_install_leaves_no_marker_and_is_recoverable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    write_batch(tmp_path, {"a.png": b"1", "m.json": b"old"}, marker="m.json")
    real_replace = os.replace
    calls = []

    def dying_replace(src, dst):  # noqa: ANN001
        calls.append(dst)
        if len(calls) == 2:  # the index journal went first; die after the first file
            raise KeyboardInterrupt
        real_replace(src, dst)

    monkeypatch.setattr(outdir.os, "replace", dying_replace)
    with pytest.raises(KeyboardInterrupt):
        write_batch(tmp_path, {"a.png": b"2", "m.json": b"new"}, marker="m.json")
    monkeypatch.setattr(outdir.os, "replace", real_replace)
    assert not (tmp_path / "m.json").exists()  # does not look complete
    write_batch(tmp_path, {"a.png": b"3", "m.json": b"newer"}, marker="m.json")
    assert (tmp_path / "m.json").read_bytes() == b"newer"


def test_injected_enospc_changes_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    write_batch(tmp_path, {"a.png": b"1"})
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def full(*args: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    with pytest.raises(OutputError, match="no space left on device"):
        with OutputFolder(tmp_path) as out, out.batch("g") as staging:
            (staging / "b.png").write_bytes(b"2")
            full()
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_write_bytes_is_checked_and_indexed(tmp_path: Path) -> None:
    (tmp_path / "record.json").write_text("user")
    with OutputFolder(tmp_path) as out:
        with pytest.raises(OutputError):
            out.write_bytes("record.json", b"{}")
        out.write_bytes("renders/p0.png", b"png")
        out.write_bytes("renders/p0.png", b"png2")
    assert (tmp_path / "record.json").read_text() == "user"
    index = json.loads((tmp_path / INDEX_NAME).read_text())
    assert list(index["files"]) == ["renders/p0.png"]


def test_remove_owned_keeps_changed_and_foreign(tmp_path: Path) -> None:
    write_batch(tmp_path, {"a.png": b"1", "b.png": b"2"})
    (tmp_path / "b.png").write_bytes(b"changed")
    (tmp_path / "c.txt").write_text("user")
    with OutputFolder(tmp_path) as out:
        assert out.remove_owned() == ["a.png"]
    assert visible(tmp_path) == ["b.png", "c.txt"]


def test_legacy_render_folder_is_adopted(tmp_path: Path) -> None:
    manifest = {"format": "matloom-material", "maps": [{"name": "ao", "file": "ao.png"}]}
    (tmp_path / "material.json").write_text(json.dumps(manifest))
    (tmp_path / "ao.png").write_bytes(b"old")
    (tmp_path / "notes.txt").write_text("user")
    write_batch(tmp_path, {"ao.png": b"new", "material.json": b"{}"}, group="render")
    assert (tmp_path / "ao.png").read_bytes() == b"new"
    assert (tmp_path / "notes.txt").read_text() == "user"


def test_single_png_output_replaces_only_its_own(tmp_path: Path) -> None:
    image = np.zeros((2, 3, 3), np.uint8)
    path = tmp_path / "preview.png"
    save_output_png(path, image)
    save_output_png(path, image + 1)  # MatLoom's own PNG: replaced
    photo = tmp_path / "photo.png"
    photo.write_bytes(b"\x89PNG\r\n\x1a\n" + b"\x00" * 40)  # a PNG MatLoom did not write
    with pytest.raises(OutputError, match="not written by MatLoom"):
        save_output_png(photo, image)
    with pytest.raises(OutputError, match="is a folder"):
        save_output_png(tmp_path, image)
