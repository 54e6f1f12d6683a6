"""Studio latency in a real browser: a slider step to the 3D view, p50/p90.

Starts ``matloom studio`` on each program (a temporary workspace, 127.0.0.1), opens it in
Debian's chromium through Playwright (headless, WebGL2 through SwiftShader), waits for the
first full evaluation, then moves one slider of the structured panel back and forth ``--steps``
times (an ``input`` event, as one step of a drag) and measures, in the page:

* maps: from the input event to the moment the first maps evaluated after it reached the page
  (decoded, before any drawing): the server's part and the two round trips (set, evaluate);
* first: to the first frame of the 3D view that shows maps evaluated after it (the quick
  first pass, drawn cheaply on software GL), counted at the next animation frame after that
  frame's draw (so the draw and its presentation are included);
* full: to the first frame showing the full-size (512 px) pass, at any resolution;
* refined: to the first full-resolution frame showing the full-size pass (software GL draws
  cheap frames while a drag goes on and refines once it pauses; a GPU draws every frame full);
* server: the server's own evaluation time of that full pass (``eval_ms``);
* ratio: the pixel ratio the first frame was drawn at (1 = the canvas's full resolution).

After each step's refined frame the page is left idle for ``--pause`` ms, so each step is
measured alone. ``--compare OLD_APP_JS`` times another build of the front end (served in place
of the shipped app.js) on alternate pages of the same server, round by round, so both face the
same machine load. Goals (issue 25): first <= 100 ms p50 on the tile and brick programs; the
heaviest library entry's first pass <= 300 ms. Prints a table; no assertion (see docs/studio.md
for measured figures).

    PYTHONPATH=. .venv/bin/python benchmarks/studio.py [--steps 21] [--compare OLD/app.js]
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
from typing import Any

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
  let ts = 0; // the timestamp of the animation frame we are in
  const frame = () => new Promise((r) => requestAnimationFrame((t) => r((ts = t))));
  // A frame counts as shown at the next animation frame after it was drawn (the browser has
  // presented it by then), not when its draw call was issued: when the draw happened in this
  // very frame (its time is not before this frame's timestamp), wait one more frame.
  const presented = async (shown) => {
    if (shown.t >= ts) await frame();
    return performance.now() - t0;
  };
  let arrived = null;
  const off = s.store.on("maps", (m) => {
    if (arrived === null && m.header.seq > before) arrived = performance.now() - t0;
  });
  const t0 = performance.now();
  el.value = String(value);
  el.dispatchEvent(new Event("input", { bubbles: true }));
  el.dispatchEvent(new Event("change", { bubbles: true }));
  let first = null, ratio = null, full = null;
  const limit = t0 + 60000;
  while (performance.now() < limit) {
    await frame();
    if (first === null && s.lastShownAt.seq > before) {
      ratio = s.lastShownAt.ratio ?? null;
      first = await presented(s.lastShownAt);
    }
    const m = s.store.maps;
    if (!m || m.header.seq <= before || m.header.pass !== "full") continue;
    if (full === null && s.lastShownAt.seq >= m.header.seq) full = await presented(s.lastShownAt);
    // The refined frame: full-size maps at full resolution (older builds draw the full pass so).
    const refinedAt = s.lastRefinedAt;
    if (full !== null && (!refinedAt || refinedAt.seq >= m.header.seq)) {
      const refined = refinedAt ? await presented(refinedAt) : full;
      off();
      return { first: first ?? full, full, refined, ratio, server: m.header.eval_ms, arrived };
    }
  }
  throw new Error("no refined full pass shown within 60 s");
}"""


def _program(ref: str) -> str:
    if ref.startswith("library:"):
        from matloom.library import load_library

        return load_library().entry(ref.split(":", 1)[1]).program
    return (ROOT / ref).read_text(encoding="utf-8")


def serve(folder: Path, file: Path | None = None) -> tuple[subprocess.Popen, str]:
    """Start ``matloom studio`` in ``folder`` (on ``file``, else the demo material, as
    ``make studio`` does) without opening a browser; the process and the URL it serves."""
    args = [str(file)] if file is not None else []
    proc = subprocess.Popen(
        [sys.executable, "-m", "matloom", "studio", *args, "--no-browser"],
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


READY = (
    "() => { const s = window.matloomStudio; const m = s && s.store.maps;"
    " return m && m.header.pass === 'full' && s.lastShownAt.seq >= m.header.seq"
    " && (!s.lastRefinedAt || s.lastRefinedAt.seq >= m.header.seq); }"
)


def _run_page(
    browser: Any,
    url: str,
    bundle: Path | None,
    address: str,
    values: tuple[float, float],
    steps: int,
    warmup: int,
    pause: int,
) -> list[dict[str, Any]]:
    """Open the studio (with ``bundle`` served as its app.js when given) and time ``steps``."""
    page = browser.new_page(viewport={"width": 1500, "height": 900})
    if bundle is not None:
        body = bundle.read_bytes()
        page.route(
            "**/static/app.js",
            lambda route: route.fulfill(body=body, content_type="text/javascript"),
        )
    page.goto(url)
    page.wait_for_function(READY, timeout=120_000)
    page.locator(f'[data-testid="slider-{address}"]').wait_for(timeout=60_000)
    results = []
    for k in range(warmup + steps):
        r = page.evaluate(STEP, {"address": address, "value": values[(k + 1) % 2]})
        page.wait_for_timeout(pause)
        if k >= warmup:
            results.append(r)
    page.close()
    return results


def _row(label: str, results: list[dict[str, Any]]) -> str:
    cols = []
    for key in ("arrived", "first", "full", "refined"):
        vals = [r[key] for r in results]
        cols += [statistics.median(vals), _pct(vals, 0.9)]
    ratio = [r["ratio"] for r in results if r.get("ratio")]
    server = statistics.median(r["server"] for r in results)
    cells = " ".join(f"{v:8.0f}" for v in cols)
    shown = f"{statistics.median(ratio):6.2f}" if ratio else f"{'-':>6}"
    return f"{label:16} {cells} {server:7.0f} {shown}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=21)
    parser.add_argument("--warmup", type=int, default=3)
    parser.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    parser.add_argument("--only", nargs="*", help="case names (tiles, brick, heaviest)")
    parser.add_argument(
        "--compare",
        type=Path,
        help="another build's app.js (e.g. the previous release's): served instead of the shipped"
        " one on alternate pages, in --rounds rounds, so both are timed on the same load",
    )
    parser.add_argument("--rounds", type=int, default=3, help="with --compare: rounds per program")
    parser.add_argument(
        "--pause", type=int, default=500, help="ms of idle page after each step's refined frame"
    )
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    variants: list[tuple[str, Path | None]] = [("", None)]
    rounds = 1
    if args.compare:
        variants = [("compare", args.compare), ("shipped", None)]
        rounds = max(1, args.rounds)
    per_round = max(1, args.steps // rounds)
    rows = []
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=args.chromium, args=ARGS)
        for name, ref, address, values in CASES:
            if args.only and name not in args.only:
                continue
            got: dict[str, list[dict[str, Any]]] = {label: [] for label, _ in variants}
            with tempfile.TemporaryDirectory() as tmp:
                folder = Path(tmp)
                file = folder / f"{name}.mat"
                file.write_text(_program(ref), encoding="utf-8")
                proc, url = serve(folder, file)
                try:
                    for k in range(rounds):
                        order = variants if k % 2 == 0 else variants[::-1]
                        for label, bundle in order:
                            got[label] += _run_page(
                                browser,
                                url,
                                bundle,
                                address,
                                values,
                                per_round,
                                args.warmup,
                                args.pause,
                            )
                finally:
                    proc.terminate()
                    proc.wait(10)
            for label, _ in variants:
                rows.append((f"{name} {label}".strip(), got[label]))
        browser.close()
    n = len(rows[0][1]) if rows else 0
    print(f"slider step -> 3D view, {n} steps each (ms; chromium + SwiftShader)")
    heads = ["maps", "first", "full", "refined"]
    head = " ".join(f"{h + ' p' + q:>8}" for h in heads for q in ("50", "90"))
    print(f"{'program':16} {head} {'server':>7} {'ratio':>6}")
    for label, results in rows:
        print(_row(label, results))


if __name__ == "__main__":
    main()
