"""Benchmark: one-shot `matloom` commands as whole processes, this tree against a previous one.

Run: .venv/bin/python benchmarks/cli.py [--base /tmp/base] [--repeat 7] [--only render-256 ...]

Each command is a fresh ``python -m matloom ...`` process (wall clock from start to exit, the
interpreter's start-up and every import included), what a user typing the command waits for:

* ``render-256``: ``render black_ceramic_tiles.mat --size 256 -o DIR`` (maps, preview.png,
  material.mat, manifest);
* ``render-1024``: the same at 1024 x 1024 (numba's kernels, from a warm cache);
* ``preview``: ``preview black_ceramic_tiles.mat -o FILE.png`` (the default size);
* ``check``: ``check black_ceramic_tiles.mat``;
* ``generate``: offline ``generate "black shiny ceramic floor tiles" -o DIR`` (no model
  configured: the material library).

Each tree runs with ``PYTHONPATH=TREE`` from a neutral working folder (so neither the working
tree nor the editable install shadows it; checked before timing: ``matloom.__file__`` must lie
in TREE). The runs alternate between the trees (current, base, current, base ...), so a change
of machine load hits both alike; the medians and their ratio are printed, with the load
average before and after (other processes inflate wall times on the 2-core machines). Before
timing, each tree's numba kernels are compiled into its cache (its background compiler, waited
for) and every command runs once untimed.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROGRAM = ROOT / "matloom" / "examples" / "black_ceramic_tiles.mat"
PROMPT = "black shiny ceramic floor tiles"

#: name -> arguments after ``python -m matloom`` ({out}: a fresh folder per run).
COMMANDS: dict[str, list[str]] = {
    "render-256": ["render", str(PROGRAM), "--size", "256", "-o", "{out}"],
    "render-1024": ["render", str(PROGRAM), "--size", "1024", "-o", "{out}"],
    "preview": ["preview", str(PROGRAM), "-o", "{out}/preview.png"],
    "check": ["check", str(PROGRAM)],
    "generate": ["generate", PROMPT, "-o", "{out}", "--quiet"],
}

#: Wait until the tree's background compiler has compiled its kernels (either layout).
_WARM_UP = """
try:
    from matloom.runtime import warmup
except ImportError:
    from matloom.engine.kernels import warmup
state = warmup.ensure_background()
state = warmup.wait(timeout=1800) if state.running else state
print("ready" if state.ready else f"not ready: {state}")
"""


def _env(tree: Path, config: Path) -> dict[str, str]:
    env = {**os.environ, "PYTHONPATH": str(tree), "MATLOOM_CONFIG": str(config)}
    for name in ("MATLOOM_BACKEND", "MATLOOM_PURE_NUMPY", "MATLOOM_BACKGROUND_COMPILE"):
        env.pop(name, None)
    return env


def check_tree(tree: Path, env: dict[str, str], cwd: Path) -> None:
    """Fail unless ``python -m matloom`` really imports the package of ``tree``."""
    out = subprocess.run(
        [sys.executable, "-c", "import matloom; print(matloom.__file__)"],
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    if not Path(out).resolve().is_relative_to(tree.resolve()):
        raise SystemExit(f"PYTHONPATH={tree} imports matloom from {out}, not from {tree}")


def run(
    args: list[str], env: dict[str, str], cwd: Path, scratch: Path
) -> tuple[float, subprocess.CompletedProcess[str]]:
    """Wall seconds of one ``python -m matloom ARGS`` process (``{out}`` a fresh folder)."""
    out = scratch / "out"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    cmd = [sys.executable, "-m", "matloom", *(a.replace("{out}", str(out)) for a in args)]
    start = time.perf_counter()
    proc = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - start
    if proc.returncode != 0:
        raise SystemExit(f"failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr[-2000:]}")
    return seconds, proc


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", type=Path, default=Path("/tmp/base"), help="previous tree")
    parser.add_argument("--repeat", type=int, default=7, help="timed runs per tree and command")
    parser.add_argument("--only", nargs="*", choices=list(COMMANDS), help="commands to time")
    args = parser.parse_args(argv)
    names = args.only or list(COMMANDS)
    trees = {"current": ROOT, "base": args.base}
    with tempfile.TemporaryDirectory(prefix="matloom-cli-bench-") as tmp:
        work = Path(tmp)
        config = work / "matloom.toml"  # no model configured: generate is offline
        config.write_text("", encoding="utf-8")
        envs = {label: _env(tree, config) for label, tree in trees.items()}
        for label, tree in trees.items():
            check_tree(tree, envs[label], work)
            warm = subprocess.run(
                [sys.executable, "-c", _WARM_UP],
                env=envs[label],
                cwd=work,
                capture_output=True,
                text=True,
                check=False,
            )
            print(f"{label} ({tree}): kernels {warm.stdout.strip() or warm.stderr[-300:]}")
        print(f"load average before: {os.getloadavg()}")
        times: dict[tuple[str, str], list[float]] = {}
        for name in names:
            for label in trees:  # untimed: page cache, bytecode, the numba cache index
                run(COMMANDS[name], envs[label], work, work / label)
            for _ in range(args.repeat):
                for label in trees:
                    seconds, _ = run(COMMANDS[name], envs[label], work, work / label)
                    times.setdefault((name, label), []).append(seconds)
        print(f"load average after:  {os.getloadavg()}")
    print(f"\nmedian wall seconds of whole processes ({args.repeat} runs each, alternating)")
    print(f"{'command':<12} {'current':>9} {'base':>9} {'current/base':>13}")
    for name in names:
        cur = statistics.median(times[(name, "current")])
        base = statistics.median(times[(name, "base")])
        print(f"{name:<12} {cur:>9.3f} {base:>9.3f} {cur / base:>13.2f}")


if __name__ == "__main__":
    main()
