"""Real-browser tests of the studio: `matloom studio` in a subprocess on 127.0.0.1 and Debian's
chromium driven by Playwright for Python (headless, WebGL2 through SwiftShader).

They are marked ``browser`` and run by ``make test-studio`` (its own venv with Playwright);
without Playwright or chromium they skip and say so. ``MATLOOM_CHROMIUM`` names another
chromium binary; ``MATLOOM_STUDIO_SHOTS=DIR`` makes the tests write the screenshots that
docs/studio.md shows.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[3]
DEMO = ROOT / "matloom" / "examples" / "black_ceramic_tiles.mat"
CHROMIUM = os.environ.get("MATLOOM_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"
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


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if "studio/browser" in str(item.fspath).replace(os.sep, "/"):
            item.add_marker(pytest.mark.browser)


@dataclass
class Studio:
    url: str
    root: Path
    port: int
    token: str
    proc: subprocess.Popen


def start_studio(file: Path, env: dict[str, str] | None = None, *args: str) -> Studio:
    """``matloom studio FILE --no-browser [ARGS]`` in a subprocess, once it printed its URL
    (the whole URL, a permalink's ``#p=`` fragment included)."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "matloom", "studio", str(file), "--no-browser", *args],
        stderr=subprocess.PIPE,
        stdout=subprocess.DEVNULL,
        text=True,
        cwd=file.parent,
        env=env,
    )
    url = None
    deadline = time.monotonic() + 60
    assert proc.stderr is not None
    while url is None and time.monotonic() < deadline:
        line = proc.stderr.readline()
        if not line:
            break
        if m := re.search(r"MatLoom studio at (\S+)", line):
            url = m.group(1)
    m = re.match(r"http://[^:]+:(\d+)/\?token=([\w-]+)", url or "")
    if m is None:
        proc.kill()
        pytest.fail("matloom studio did not print its URL")
    return Studio(url or "", file.parent, int(m.group(1)), m.group(2), proc)


def stop_studio(studio: Studio) -> None:
    studio.proc.terminate()
    try:
        studio.proc.wait(10)
    except subprocess.TimeoutExpired:
        studio.proc.kill()


@pytest.fixture(scope="module")
def studio(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Studio]:
    pytest.importorskip("starlette", reason="the studio needs the [studio] extra")
    root = tmp_path_factory.mktemp("workspace")
    shutil.copy(DEMO, root / DEMO.name)
    running = start_studio(root / DEMO.name)
    try:
        yield running
    finally:
        stop_studio(running)


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    sync_api = pytest.importorskip(
        "playwright.sync_api", reason="needs Playwright for Python (make test-studio)"
    )
    if not Path(CHROMIUM).is_file():
        pytest.skip(f"needs chromium at {CHROMIUM} (apt-get install chromium)")
    with sync_api.sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            yield b
        finally:
            b.close()


def open_page(browser: Any, url: str) -> Any:
    """A fresh page on ``url``, waited until the first full evaluation is drawn in 3D."""
    # the page's CSP forbids eval; Playwright's wait_for_function("...") needs it
    page = browser.new_page(viewport={"width": 1500, "height": 900}, bypass_csp=True)
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    page.wait_for_function(
        "() => window.matloomStudio && window.matloomStudio.store.maps"
        " && window.matloomStudio.store.maps.header.pass === 'full'"
        " && window.matloomStudio.lastShownAt.seq >= window.matloomStudio.store.maps.header.seq"
        " && window.matloomStudio.lastRefinedAt.seq >= window.matloomStudio.store.maps.header.seq",
        timeout=60_000,
    )
    page.page_errors = errors  # type: ignore[attr-defined]
    return page


@pytest.fixture
def page(browser: Any, studio: Studio) -> Iterator[Any]:
    p = open_page(browser, studio.url)
    try:
        yield p
    finally:
        assert not p.page_errors, p.page_errors
        p.close()


def shot(page: Any, name: str, selector: str | None = None) -> None:
    """Write a screenshot for docs/studio.md when MATLOOM_STUDIO_SHOTS names a folder."""
    folder = os.environ.get("MATLOOM_STUDIO_SHOTS")
    if not folder:
        return
    Path(folder).mkdir(parents=True, exist_ok=True)
    target = page.locator(selector) if selector else page
    target.screenshot(path=str(Path(folder) / f"{name}.png"))
