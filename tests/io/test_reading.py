"""Files named by a folder MatLoom did not make are read without following a symlink out."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from matloom.author.records import RECORD_NAME, RecordStore
from matloom.io.reading import UnsafeReadError, read_json_file, read_regular_bytes


def test_a_regular_file_is_read(tmp_path: Path) -> None:
    (tmp_path / "a.json").write_text('{"x": 1}')
    assert read_json_file(tmp_path / "a.json", 100) == {"x": 1}


def test_a_symlink_is_refused_even_to_a_readable_file(tmp_path: Path) -> None:
    secret = tmp_path / "secret.json"
    secret.write_text('{"token": "s3cret"}')
    (tmp_path / "link.json").symlink_to(secret)
    with pytest.raises(UnsafeReadError, match="symlink"):
        read_regular_bytes(tmp_path / "link.json", 1000)


def test_a_fifo_and_an_oversized_file_are_refused(tmp_path: Path) -> None:
    os.mkfifo(tmp_path / "pipe")  # opening it normally would block forever
    with pytest.raises(UnsafeReadError, match="regular"):
        read_regular_bytes(tmp_path / "pipe", 1000)
    (tmp_path / "big").write_bytes(b"x" * 101)
    with pytest.raises(UnsafeReadError, match="larger"):
        read_regular_bytes(tmp_path / "big", 100)


def test_a_run_record_is_not_read_through_a_symlink(tmp_path: Path) -> None:
    elsewhere = tmp_path / "elsewhere.json"
    elsewhere.write_text(json.dumps({"prompt": "x"}))
    run = tmp_path / "run"
    run.mkdir()
    (run / RECORD_NAME).symlink_to(elsewhere)
    with pytest.raises(OSError, match="symlink"):
        RecordStore.load(run)
