"""`matloom gallery` keeps every prompt and stays linear (issue "Reliability" #12).

Ids ``a/b`` and ``a_b`` used to write the same files, so one entry was lost; a 200 KB prompt
took 20 s because its contact-sheet label was shortened one character at a time.
"""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from matloom.cli.main import cli
from matloom.library.gallery import GalleryEntry, _sheet_label, assign_file_ids


def _files(stem: str) -> set[str]:
    return {stem.casefold(), f"{stem}_tiled".casefold()}


def _assert_no_shared_files(stems: list[str]) -> None:
    seen: set[str] = set()
    for stem in stems:
        assert not (_files(stem) & seen), stem
        seen |= _files(stem)


def test_ids_that_sanitise_alike_get_distinct_deterministic_names() -> None:
    ids = ["a/b", "a_b", "a b", "A_B"]
    stems = assign_file_ids(ids)
    assert stems[1] == "a_b"  # an id that is already a safe name keeps it
    assert all(s.startswith(("a_b-", "A_B-")) for s in (stems[0], stems[2], stems[3]))
    _assert_no_shared_files(stems)
    assert assign_file_ids(ids) == stems  # deterministic
    assert assign_file_ids(["a_b", "a/b"]) == ["a_b", stems[0]]  # independent of order


def test_tiled_previews_reserved_and_empty_ids_do_not_collide() -> None:
    stems = assign_file_ids(["x", "x_tiled", "con", "", "..", "p001", "p001"])
    assert stems[0] == "x" and stems[1] != "x_tiled"  # x's tiled preview is x_tiled.png
    assert stems[2].startswith("con-") and stems[3] == "prompt" and stems[4] != "prompt"
    assert stems[5] == "p001" and stems[6].startswith("p001-")
    _assert_no_shared_files(stems)


def test_colliding_ids_both_appear_in_the_gallery(tmp_path: Path) -> None:
    prompts = tmp_path / "prompts.json"
    items = [{"id": "a/b", "text": "red brick wall"}, {"id": "a_b", "text": "mossy slate floor"}]
    prompts.write_text(json.dumps(items), encoding="utf-8")
    out = tmp_path / "g"
    result = CliRunner().invoke(cli, ["gallery", str(prompts), "-o", str(out), "--size", "16"])
    assert result.exit_code == 0, result.output
    rows = json.loads((out / "gallery.json").read_text(encoding="utf-8"))
    assert [r["prompt_id"] for r in rows] == ["a/b", "a_b"]
    assert rows[1]["id"] == "a_b" and rows[0]["id"] != rows[1]["id"]
    programs = {r["program_file"] for r in rows}
    assert len(programs) == 2 and all((out / p).is_file() for p in programs)
    texts = {(out / r["program_file"]).read_text(encoding="utf-8") for r in rows}
    assert len(texts) == 2  # two different materials, neither overwritten
    page = (out / "index.html").read_text(encoding="utf-8")
    assert "<b>a/b</b>" in page and "<b>a_b</b>" in page


def _entry(text: str) -> GalleryEntry:
    return GalleryEntry("p000", "", text, "r", [], 1, 0.0, "a.png", "b.png", "c.mat", "p000")


def test_sheet_label_is_bounded_before_fitting() -> None:
    text = "red brick wall with moss " * 8000  # 200 KB
    label = _sheet_label(_entry(text), 192)
    assert len(label) <= 192 + 3 and label.endswith("...")
    assert label.startswith("p000: red brick wall with moss red")
    assert _sheet_label(_entry("oak  planks\n"), 192) == "p000: oak planks"


def test_huge_prompt_label_is_cut_before_the_sheet_fits_it() -> None:
    import numpy as np

    from matloom.render.sheet import contact_sheet

    label = _sheet_label(_entry("x" * 200_000), 192)
    # fitting shortens one character at a time: a bounded label keeps it linear and cheap
    # (the unbounded 200 KB label took ~10 s)
    assert len(label) <= 192 + 3
    sheet = contact_sheet([np.zeros((8, 8, 3), np.uint8)], [label], 1, 192)
    assert sheet.shape[1] >= 8
