"""The gallery writer (on the material library) and the `matloom gallery` command on a tiny
prompt file."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner
from PIL import Image

from matloom.cli.gallery_cmd import gallery_cmd
from matloom.library import author
from matloom.library.gallery import build_gallery, load_prompts


def _prompt_file(tmp_path: Path) -> Path:
    path = tmp_path / "prompts.json"
    path.write_text(
        json.dumps(
            {
                "prompts": [
                    {"id": "a-1", "source": "test", "text": "red brick wall"},
                    {"id": "b/2", "source": "test", "text": "mossy slate floor"},
                ]
            }
        ),
        encoding="utf-8",
    )
    return path


def test_load_prompts_accepts_objects_and_strings(tmp_path: Path) -> None:
    assert [p.id for p in load_prompts(_prompt_file(tmp_path))] == ["a-1", "b/2"]
    plain = tmp_path / "plain.json"
    plain.write_text(json.dumps(["oak planks"]), encoding="utf-8")
    assert [(p.id, p.text) for p in load_prompts(plain)] == [("p000", "oak planks")]


def test_build_gallery_writes_previews_programs_page_and_sheet(tmp_path: Path) -> None:
    out = tmp_path / "gallery"
    entries = build_gallery(load_prompts(_prompt_file(tmp_path)), out, size=64)
    expected = [author(p.text) for p in load_prompts(_prompt_file(tmp_path))]
    assert [e.entry for e in entries] == [r.entry for r in expected]
    assert entries[0].overlays == [] and entries[1].overlays == ["mossy"]
    for e in entries:
        assert Image.open(out / e.preview).size == (64, 64)
        assert Image.open(out / e.tiled).size == (64, 64)
        program = (out / e.program_file).read_text(encoding="utf-8")
        assert program == author(e.text).program + "\n"
        assert program.startswith(f"# library entry: {e.entry} ")
    page = (out / "index.html").read_text(encoding="utf-8")
    assert "red brick wall" in page and "b_2_tiled.png" in page and "Define(" in page
    assert f"entry: <code>{entries[1].entry}</code>" in page and "overlays: mossy" in page
    assert "candidates:" in page and "ignored:" in page  # the library's explanation
    assert Image.open(out / "contact_sheet.png").size[0] > 64
    rows = json.loads((out / "gallery.json").read_text(encoding="utf-8"))
    assert [(r["entry"], r["overlays"]) for r in rows] == [(e.entry, e.overlays) for e in entries]


def test_gallery_command(tmp_path: Path) -> None:
    out = tmp_path / "cli"
    result = CliRunner().invoke(
        gallery_cmd, [str(_prompt_file(tmp_path)), "-o", str(out), "--size", "32"]
    )
    assert result.exit_code == 0, result.output
    assert "2 materials" in result.output and "median program length" in result.output
    assert (out / "index.html").exists() and (out / "contact_sheet.png").exists()
