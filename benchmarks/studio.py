"""Studio latency in a real browser: a slider step to the 3D view, p50/p90.

Starts ``matloom studio`` on each program (a temporary workspace, 127.0.0.1), opens it in
Debian's chromium through Playwright (headless, WebGL2 through SwiftShader), waits for the
first full evaluation, then moves one slider of the structured panel back and forth ``--steps``
times (an ``input`` event, as one step of a drag) and measures, in the page:

* first: from the input event to the first frame of the 3D view that shows maps evaluated
  after it (the quick first pass, or the full pass when the program is fast enough to skip it),
  counted at the next animation frame after that frame's draw (so the draw itself is included);
* full: to the first frame showing the full-size (512 px) pass;
* maps: to the moment the first maps evaluated after it reached the page (decoded, before
  any drawing): the part MatLoom controls; the rest is the browser's WebGL draw, which under
  SwiftShader (software GL, no GPU here) costs about 100-300 ms a frame by itself;
* server: the server's own evaluation time of that full pass (``eval_ms``).

Between steps it waits for the full pass, so each step is measured alone. Goals (issue 25):
first <= 100 ms p50 on the tile and brick programs; the heaviest library entry's first pass
<= 300 ms. Prints a table; no assertion (see docs/studio.md for measured figures).

    PYTHONPATH=. .venv/bin/python benchmarks/studio.py [--steps 25] [--chromium PATH]
"""

from __future__ import annotations

import argparse
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ARGS = [
    "--headless=new",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--no-sandbox",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
    "--disable-sync",
]

#: (name, program source, slider address, two values to alternate)
CASES = [
    (
        "tiles",
        "matloom/examples/black_ceramic_tiles.mat",
        "define:tileMask.Bricks.mortar",
        (0.02, 0.05),
    ),
    ("brick", "matloom/examples/bricks_quickstart.mat", "define:brick.Bricks.mortar", (0.05, 0.1)),
    ("heaviest", "library:toile-de-jouy-pastoral", "define:leaf_height", (0.004, 0.008)),
]

STEP = """async ({address, value}) => {
  const s = window.matloomStudio;
  const el = document.querySelector(`[data-testid="slider-${address}"]`);
  if (!el) throw new Error("no slider " + address);
  const before = Math.max(s.lastShownAt.seq, s.store.maps ? s.store.maps.header.seq : 0);
  const frame = () => new Promise((r) => requestAnimationFrame(r));
  let arrived = null;
  const off = s.store.on("maps", (m) => {
    if (arrived === null && m.header.seq > before) arrived = performance.now() - t0;
  });
  const t0 = performance.now();
  el.value = String(value);
  el.dispatchEvent(new Event("input", { bubbles: true }));
  el.dispatchEvent(new Event("change", { bubbles: true }));
  let first = null;
  const limit = t0 + 60000;
  // A frame counts as shown at the next animation frame after it was drawn (the browser has
  // presented it by then), not when its draw call was issued.
  while (performance.now() < limit) {
    await frame();
    if (first === null && s.lastShownAt.seq > before) {
      await frame();
      first = performance.now() - t0;
    }
    const m = s.store.maps;
    if (m && m.header.seq > before && m.header.pass === "full" && s.lastShownAt.seq >= m.header.seq) {
      await frame();
      off();
      return { first: first ?? performance.now() - t0, full: performance.now() - t0,
               server: m.header.eval_ms, arrived };
    }
  }
  throw new Error("no full pass shown within 60 s");
}"""


def _program(ref: str) -> str:
    if ref.startswith("library:"):
        from matloom.library import load_library

        return load_library().entry(ref.split(":", 1)[1]).program
    return (ROOT / ref).read_text(encoding="utf-8")


def _serve(folder: Path, file: Path) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen(
        [sys.executable, "-m", "matloom", "studio", str(file), "--no-browser"],
        stderr=subprocess.PIPE,
        stdout=subprocess.DEVNULL,
        text=True,
        cwd=folder,
    )
    assert proc.stderr is not None
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        line = proc.stderr.readline()
        if m := re.search(r"MatLoom studio at (\S+)", line):
            return proc, m.group(1)
        if not line:
            break
    proc.kill()
    raise SystemExit("matloom studio did not start")


def _pct(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=25)
    parser.add_argument("--warmup", type=int, default=4)
    parser.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    parser.add_argument("--only", nargs="*", help="case names (tiles, brick, heaviest)")
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    rows = []
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=args.chromium, args=ARGS)
        for name, ref, address, values in CASES:
            if args.only and name not in args.only:
                continue
            with tempfile.TemporaryDirectory() as tmp:
                folder = Path(tmp)
                file = folder / f"{name}.mat"
                file.write_text(_program(ref), encoding="utf-8")
                proc, url = _serve(folder, file)
                try:
                    page = browser.new_page(viewport={"width": 1500, "height": 900})
                    page.goto(url)
                    page.wait_for_function(
                        "() => window.matloomStudio && window.matloomStudio.store.maps &&"
                        " window.matloomStudio.store.maps.header.pass === 'full' &&"
                        " window.matloomStudio.lastShownAt.seq >="
                        " window.matloomStudio.store.maps.header.seq",
                        timeout=120_000,
                    )
                    page.locator(f'[data-testid="slider-{address}"]').wait_for(timeout=60_000)
                    results = []
                    for k in range(args.warmup + args.steps):
                        value = values[(k + 1) % 2]
                        r = page.evaluate(STEP, {"address": address, "value": value})
                        page.wait_for_timeout(150)
                        if k >= args.warmup:
                            results.append(r)
                    page.close()
                finally:
                    proc.terminate()
                    proc.wait(10)
            arrived = [r["arrived"] for r in results]
            first = [r["first"] for r in results]
            full = [r["full"] for r in results]
            server = [r["server"] for r in results]
            rows.append((name, arrived, first, full, server))
        browser.close()
    print(f"slider step -> 3D view, {args.steps} steps each (ms; chromium + SwiftShader)")
    print(
        f"{'program':10} {'maps p50':>9} {'maps p90':>9} {'first p50':>10} {'first p90':>10} "
        f"{'full p50':>9} {'full p90':>9} {'server eval p50':>16}"
    )
    for name, arrived, first, full, server in rows:
        print(
            f"{name:10} {statistics.median(arrived):9.1f} {_pct(arrived, 0.9):9.1f} "
            f"{statistics.median(first):10.1f} {_pct(first, 0.9):10.1f} "
            f"{statistics.median(full):9.1f} {_pct(full, 0.9):9.1f} {statistics.median(server):16.1f}"
        )


if __name__ == "__main__":
    main()
