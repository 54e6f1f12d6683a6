"""The studio in a real browser: the acceptance list of issue 25, item 11."""

from __future__ import annotations

import io
import json
import shutil
import subprocess
import urllib.request
from typing import Any

import numpy as np
import pytest
from PIL import Image

from matloom.studio.permalink import decode

from .conftest import ROOT, Studio, open_page, shot, start_studio, stop_studio

pytestmark = pytest.mark.browser

MORTAR = "define:tileMask.Bricks.mortar"


def canvas(page: Any, testid: str = "viewer-canvas") -> np.ndarray:
    png = page.locator(f'[data-testid="{testid}"]').screenshot()
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def shown_seq(page: Any) -> int:
    return int(page.evaluate("window.matloomStudio.lastShownAt.seq"))


def wait_full_shown(page: Any, after: int) -> None:
    """Wait until a full pass newer than seq ``after`` is drawn in the 3D view."""
    page.wait_for_function(
        "(after) => { const s = window.matloomStudio; const m = s.store.maps;"
        " return m && m.header.pass === 'full' && m.header.seq > after"
        " && s.lastShownAt.seq >= m.header.seq && s.lastRefinedAt.seq >= m.header.seq"
        " && document.querySelector("
        "'[data-testid=status]').textContent.includes('ready'); }",
        arg=after,
        timeout=60_000,
    )


def editor_text(page: Any) -> str:
    return str(page.evaluate("window.matloomStudio.store.text"))


def select_in_editor(page: Any, needle: str) -> None:
    """Put the editor's selection on the first ``needle`` (then real key presses replace it)."""
    page.evaluate(
        "(needle) => { const v = window.matloomStudio.editor; const i ="
        " v.state.doc.toString().indexOf(needle); if (i < 0) throw new Error(needle);"
        " v.focus(); v.dispatch({selection: {anchor: i, head: i + needle.length}}); }",
        needle,
    )


def test_page_loads_the_demo_and_draws_it_in_3d(page: Any) -> None:
    assert "Bricks(" in editor_text(page)
    img = canvas(page)
    assert img.std() > 8, "the 3D canvas is blank"
    assert page.evaluate("window.matloomStudio.frames") > 0
    shot(page, "studio-editor-3d")


def test_an_error_is_shown_at_its_line_and_column_and_fixing_it_redraws(page: Any) -> None:
    before = canvas(page)
    seq = shown_seq(page)
    select_in_editor(page, "mortar=0.02")
    page.keyboard.type("mortar=0.0x")
    item = page.locator('[data-testid="diag-list"] li').first
    item.wait_for(timeout=30_000)
    text = editor_text(page)
    offset = text.index("mortar=0.0x")
    line = text.count("\n", 0, offset) + 1
    assert int(item.get_attribute("data-line")) == line
    col = int(item.get_attribute("data-col"))
    line_start = text.rfind("\n", 0, offset) + 1
    assert offset - line_start + 1 <= col <= offset - line_start + len("mortar=0.0x") + 1
    select_in_editor(page, "mortar=0.0x")
    page.keyboard.type("mortar=0.09")
    wait_full_shown(page, seq)
    # The checker is debounced apart from rendering, so the list may clear just after the frame.
    page.wait_for_function(
        "() => document.querySelectorAll('[data-testid=diag-list] li').length === 0",
        timeout=30_000,
    )
    after = canvas(page)
    assert np.abs(after - before).mean() > 0.5, "fixing the error did not change the 3D view"


def drag_slider(page: Any, address: str, fraction: float) -> None:
    slider = page.locator(f'[data-testid="slider-{address}"]')
    slider.scroll_into_view_if_needed()
    box = slider.bounding_box()
    assert box is not None
    y = box["y"] + box["height"] / 2
    page.mouse.move(box["x"] + 2, y)
    page.mouse.down()
    for k in range(1, 9):
        page.mouse.move(box["x"] + 2 + (box["width"] - 4) * fraction * k / 8, y)
        page.wait_for_timeout(30)
    page.mouse.up()


def test_a_slider_drag_changes_text_and_view_and_undo_redo_restore_both(page: Any) -> None:
    text0, img0, seq = editor_text(page), canvas(page), shown_seq(page)
    drag_slider(page, MORTAR, 0.6)
    wait_full_shown(page, seq)
    text1, img1 = editor_text(page), canvas(page)
    assert text1 != text0 and "mortar=0.02" not in text1
    assert np.abs(img1 - img0).mean() > 0.5, "the drag did not change the 3D view"
    seq = shown_seq(page)
    page.locator('[data-testid="undo"]').click()
    wait_full_shown(page, seq)
    assert editor_text(page) == text0
    assert np.abs(canvas(page) - img0).mean() < np.abs(img1 - img0).mean() / 4
    seq = shown_seq(page)
    page.locator('[data-testid="redo"]').click()
    wait_full_shown(page, seq)
    assert editor_text(page) == text1


def test_a_permalink_reopens_the_same_program(browser: Any, page: Any, studio: Studio) -> None:
    seq = shown_seq(page)
    select_in_editor(page, "octaves=3")
    page.keyboard.type("octaves=2")
    wait_full_shown(page, seq)
    edited = editor_text(page)
    page.locator('[data-testid="permalink"]').click()
    page.wait_for_function("() => location.hash.startsWith('#p=')")
    link = page.evaluate("location.href")
    other = open_page(browser, link)
    try:
        assert editor_text(other) == edited
    finally:
        other.close()
    # the same link in a new studio (as on another machine): `matloom studio --link`
    assert decode(link) == edited
    fresh = start_studio(studio.root / "black_ceramic_tiles.mat", None, "--link", link)
    try:
        assert "#p=" in fresh.url
        again = open_page(browser, fresh.url)
        try:
            assert editor_text(again) == edited
        finally:
            again.close()
    finally:
        stop_studio(fresh)


def test_export_writes_a_folder_whose_gltf_passes_the_khronos_validator(
    page: Any, studio: Studio
) -> None:
    node = shutil.which("node")
    validator = ROOT / ".tools" / "node_modules" / "gltf-validator" / "index.js"
    page.locator('[data-testid="tab-export"]').click()
    page.locator('[data-testid="export-out"]').fill("exported")
    page.locator('[data-testid="export-preset-gltf"]').check()
    page.locator('[data-testid="export-run"]').click()
    page.locator('[data-testid="export-result"]').get_by_text("material.json").wait_for(
        timeout=120_000
    )
    folder = studio.root / "exported"
    gltf = sorted((folder / "gltf").glob("*.gltf"))
    assert gltf, sorted(p.name for p in folder.rglob("*"))
    assert json.loads((folder / "material.json").read_text())["maps"]
    if node is None or not validator.is_file():
        pytest.skip("needs node and the Khronos glTF validator (make tools) for the last step")
    res = subprocess.run(
        [node, str(ROOT / "tests" / "io" / "gltf_validate.js"), str(gltf[0])],
        capture_output=True,
        text=True,
        timeout=120,
        env={"GLTF_VALIDATOR_DIR": str(validator.parents[1]), "PATH": "/usr/bin:/bin"},
    )
    assert res.returncode == 0, res.stderr
    report = json.loads(res.stdout.splitlines()[0])
    assert report["errors"] == 0, report["messages"]


def _status(studio: Studio, path: str, headers: dict[str, str]) -> int:
    req = urllib.request.Request(f"http://127.0.0.1:{studio.port}{path}", headers=headers)
    try:
        with urllib.request.urlopen(req, timeout=30) as r:
            return int(r.status)
    except urllib.error.HTTPError as err:
        return int(err.code)


def test_no_token_or_a_forged_host_gets_403(page: Any, studio: Studio) -> None:
    token = {"X-MatLoom-Token": studio.token}
    assert _status(studio, "/api/session", token) == 200
    assert _status(studio, "/api/session", {}) == 403
    forged = {**token, "Host": "evil.example:80"}
    assert _status(studio, "/api/session", forged) == 403
    # from the page itself: a call without the token is refused too
    status = page.evaluate("async () => (await fetch('/api/session')).status")
    assert status == 403


def test_a_cost_bomb_gets_its_error_and_the_studio_keeps_working(page: Any) -> None:
    # 2**12 distinct frames of a 16-octave fBm: over the cost model (E071) at any size
    lines = ["Define(d0, fBm(octaves=16, seed=1))"]
    for k in range(1, 13):
        lines.append(f"Define(d{k}, Translate(d{k - 1}, 0, 0) + Translate(d{k - 1}, {2**k}, 0))")
    lines.append("Material(Layer(1).height(d12))")
    page.evaluate("(t) => window.matloomStudio.store.setText(t, 'editor')", "\n".join(lines))
    page.wait_for_function("() => document.body.innerText.includes('E071')", timeout=60_000)
    seq = shown_seq(page)
    page.evaluate(
        "(t) => window.matloomStudio.store.setText(t, 'editor')",
        (ROOT / "matloom" / "examples" / "bricks_quickstart.mat").read_text(),
    )
    wait_full_shown(page, seq)
    assert "E071" not in page.locator('[data-testid="status"]').text_content()


def test_inspector_tiling_compare_and_author_views(page: Any) -> None:
    # a second version first (while the 3D view is showing), for the A/B compare
    seq = shown_seq(page)
    select_in_editor(page, "base_freq=7")
    page.keyboard.type("base_freq=3")
    wait_full_shown(page, seq)
    page.locator('[data-testid="tab-inspector"]').click()
    page.locator('[data-testid="inspector-canvas"]').wait_for()
    page.wait_for_timeout(1500)
    assert canvas(page, "inspector-canvas").std() > 5
    assert canvas(page, "tiling-canvas").std() > 5
    shot(page, "studio-inspector")
    page.locator('[data-testid="tab-compare"]').click()
    metrics = page.locator('[data-testid="compare-metrics"]')
    metrics.get_by_text("PSNR", exact=False).wait_for(timeout=60_000)
    assert "SSIM" in metrics.text_content()
    page.wait_for_timeout(500)
    assert canvas(page, "compare-canvas").std() > 5
    shot(page, "studio-compare")
    page.locator('[data-testid="tab-author"]').click()
    page.locator('[data-testid="author-prompt"]').fill("weathered red brick wall")
    page.locator('[data-testid="author-run"]').click()
    page.locator('[data-testid="author-rounds"] img').first.wait_for(timeout=120_000)
    shot(page, "studio-author-offline")
