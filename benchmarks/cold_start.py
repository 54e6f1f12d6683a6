"""Benchmark: the first `matloom render` after install (empty numba cache) vs later ones.

Run: PYTHONPATH=. .venv/bin/python benchmarks/cold_start.py [--size 1024] [--repeat 3]
     [--program FILE] [--mode background|foreground]

Every repetition starts from a fresh, empty ``NUMBA_CACHE_DIR`` and times whole processes
(``python -m matloom render PROGRAM --size N -o DIR``, wall clock, from start to exit):

1. ``cold``: the first render. In the default ``background`` mode (what the CLI does) it
   evaluates on the numpy/C path while a background process compiles the kernels.
2. ``compiled``: how long after the cold render returned the background compiler finished.
3. ``warm``: two more renders (numba path, kernels loaded from the cache); the median is kept.

``--mode foreground`` sets MATLOOM_BACKGROUND_COMPILE=0: the cold render compiles the kernels
it needs itself (the behaviour before the background compiler; nothing runs after it).
The default program is the paper's tile program (matloom/examples/black_ceramic_tiles.mat).
Prints each run, then the medians; the load average first and last (other processes inflate
wall times on the 2-core machines).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from matloom.cli.progress import COMPILING  # noqa: E402
from matloom.runtime import warmup  # noqa: E402
from matloom.runtime.cold_start import BACKGROUND_ENV  # noqa: E402

PROGRAM = ROOT / "matloom" / "examples" / "black_ceramic_tiles.mat"


def render(program: Path, size: int, out: Path, env: dict[str, str]) -> tuple[float, str]:
    """Wall seconds of one `matloom render` process and its stderr."""
    start = time.perf_counter()
    res = subprocess.run(
        [sys.executable, "-m", "matloom", "render", str(program), "--size", str(size)]
        + ["-o", str(out)],
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    seconds = time.perf_counter() - start
    if res.returncode != 0:
        raise SystemExit(f"render failed ({res.returncode}):\n{res.stderr}")
    return seconds, res.stderr


def one_repetition(program: Path, size: int, mode: str) -> dict[str, float]:
    with tempfile.TemporaryDirectory(prefix="matloom-cold-") as tmp:
        cache = Path(tmp) / "numba-cache"
        env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONPATH": str(ROOT)}
        if mode == "foreground":
            env[BACKGROUND_ENV] = "0"
        cold, err = render(program, size, Path(tmp) / "cold", env)
        said = COMPILING in err
        start = time.perf_counter()
        os.environ["NUMBA_CACHE_DIR"] = str(cache)  # warmup.state() reads it
        done = warmup.wait(cache, timeout=1800)
        compiled = time.perf_counter() - start
        warm = []
        for k in range(2):
            seconds, err = render(program, size, Path(tmp) / f"warm{k}", env)
            warm.append(seconds)
            said_warm = COMPILING in err
        row = {"cold": cold, "compiled": compiled, "warm": statistics.median(warm)}
        background = (
            f"background compile done {compiled:5.1f} s later (ready: {done.ready}), "
            if mode == "background"
            else ""
        )
        print(
            f"  cold {cold:6.2f} s (message: {said}), {background}warm {warm[0]:.2f} / "
            f"{warm[1]:.2f} s (message: {said_warm})",
            flush=True,
        )
        return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--program", type=Path, default=PROGRAM)
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--mode", choices=("background", "foreground"), default="background")
    args = parser.parse_args()
    print(
        f"load average {os.getloadavg()[0]:.2f}; {args.program.name} at {args.size}^2, "
        f"{args.mode} mode, {args.repeat} repetitions with a fresh NUMBA_CACHE_DIR"
    )
    rows = [one_repetition(args.program, args.size, args.mode) for _ in range(args.repeat)]
    med = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
    background = f"background compile done {med['compiled']:.1f} s later, "
    print(
        f"median: cold {med['cold']:.2f} s, "
        f"{background if args.mode == 'background' else ''}warm {med['warm']:.2f} s"
    )
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
