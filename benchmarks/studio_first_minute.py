"""A newcomer's first minute in the studio, timed in the real browser (issue 25's acceptance:
open the demo, change the grout width, see it in 3D, export a glTF, in under a minute).

Runs what ``make studio`` runs (``matloom studio`` with no file: a copy of the demo material in
``./matloom-studio/`` of a temporary folder, here with ``--no-browser``), opens the page in
Debian's chromium through Playwright (headless, WebGL2 through SwiftShader), then as a user
would: drags the grout (mortar) slider of the structured panel with the mouse, waits until the
3D view shows the full pass of the new program, opens the Export tab, names a folder, ticks
the glTF preset and exports. Prints the time of each step from the command's start, the files
written, and the Khronos validator's verdict on the glTF when ``make tools`` installed it.
No assertion on the times (see docs/studio.md for measured figures).

    PYTHONPATH=. .venv/bin/python benchmarks/studio_first_minute.py
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.studio import ARGS, serve  # noqa: E402

READY = (
    "(after) => { const s = window.matloomStudio; const m = s && s.store.maps;"
    " return m && m.header.pass === 'full' && m.header.seq > after"
    " && s.lastShownAt.seq >= m.header.seq"
    " && (!s.lastRefinedAt || s.lastRefinedAt.seq >= m.header.seq); }"
)


def _validate(gltf: Path) -> str:
    node = shutil.which("node")
    validator = ROOT / ".tools" / "node_modules" / "gltf-validator" / "index.js"
    if node is None or not validator.is_file():
        return "not run (needs node and `make tools`)"
    res = subprocess.run(
        [node, str(ROOT / "tests" / "io" / "gltf_validate.js"), str(gltf)],
        capture_output=True,
        text=True,
        timeout=120,
        env={"GLTF_VALIDATOR_DIR": str(validator.parents[1]), "PATH": "/usr/bin:/bin"},
    )
    if res.returncode != 0:
        return f"failed: {res.stderr.strip()[:200]}"
    report = json.loads(res.stdout.splitlines()[0])
    return f"{report['errors']} errors, {report.get('warnings', '?')} warnings"


def main() -> None:
    from playwright.sync_api import sync_playwright

    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        t0 = time.monotonic()
        marks: list[tuple[str, float]] = []
        proc, url = serve(folder)
        marks.append(("studio serving", time.monotonic() - t0))
        try:
            with sync_playwright() as pw:
                browser = pw.chromium.launch(executable_path=chromium, args=ARGS)
                page = browser.new_page(viewport={"width": 1500, "height": 900})
                page.goto(url)
                page.wait_for_function(READY, arg=0, timeout=120_000)
                marks.append(("demo shown in 3D", time.monotonic() - t0))
                slider = page.locator('[data-testid^="slider-"][data-testid*="mortar"]').first
                slider.scroll_into_view_if_needed()
                box = slider.bounding_box()
                assert box is not None
                seq = int(page.evaluate("window.matloomStudio.lastShownAt.seq"))
                before = str(page.evaluate("window.matloomStudio.store.text"))
                y = box["y"] + box["height"] / 2
                page.mouse.move(box["x"] + 2, y)
                page.mouse.down()
                for k in range(1, 9):  # a drag of about half a second
                    page.mouse.move(box["x"] + 2 + (box["width"] - 4) * 0.6 * k / 8, y)
                    page.wait_for_timeout(60)
                page.mouse.up()
                page.wait_for_function(READY, arg=seq, timeout=120_000)
                after = str(page.evaluate("window.matloomStudio.store.text"))
                marks.append(("grout widened, shown in 3D", time.monotonic() - t0))
                page.locator('[data-testid="tab-export"]').click()
                page.locator('[data-testid="export-out"]').fill("my-tiles")
                page.locator('[data-testid="export-preset-gltf"]').check()
                page.locator('[data-testid="export-run"]').click()
                page.locator('[data-testid="export-result"]').get_by_text("material.json").wait_for(
                    timeout=120_000
                )
                marks.append(("glTF exported", time.monotonic() - t0))
                browser.close()
        finally:
            proc.terminate()
            proc.wait(timeout=30)
        out = folder / "matloom-studio" / "my-tiles"
        if not out.is_dir():
            out = next(folder.rglob("my-tiles"))
        gltf = sorted(out.rglob("*.gltf"))
        for label, t in marks:
            print(f"{t:6.1f} s  {label}")
        changed = [
            a for a, b in zip(before.splitlines(), after.splitlines(), strict=False) if a != b
        ]
        print(f"program lines changed by the drag: {len(changed)} ({changed[0].strip()[:70]!r})")
        print(f"exported to {out.name}/: {', '.join(sorted(p.name for p in out.iterdir()))}")
        print(
            f"glTF: {gltf[0].relative_to(out) if gltf else 'none'}; validator: "
            f"{_validate(gltf[0]) if gltf else 'no file'}"
        )


if __name__ == "__main__":
    main()
