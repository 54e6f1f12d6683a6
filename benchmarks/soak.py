"""Soak test of bounded evaluation (acceptance; not part of the test suite). Prints numbers.

Run: PYTHONPATH=. .venv/bin/python benchmarks/soak.py [--count 10000] [--memory-count 1000]
     [--jobs 2] [--timeout 120] [--size 256] [--seed 0]

(a) ``--count`` mutated programs (random, Define-heavy and transform-heavy programs and the
    parity fixtures, edited by the character/token mutations and with the numeric fragments,
    extreme numbers included, of tests/lang/test_fuzz.py) go
    through ``check`` -> ``evaluate`` 32x32 -> ``preview`` 32x32 in worker processes. A worker
    that runs past ``--timeout`` seconds on one program is killed and replaced (the watchdog).
    ProgramError and LimitError are the expected outcomes of bad programs; anything else is an
    unhandled exception. Prints the counts, the worst time and the worst RSS of one program.
(b) ``--memory-count`` random programs (the same three families, unmutated) at ``--size`` on the
    numba and the numpy backends: the peak RSS growth of each evaluation (VmHWM reset through
    /proc/self/clear_refs before it) against the estimate of ``matloom.engine.limits``. Prints the
    programs whose peak exceeds the estimate (there should be none) and the tightest ratios.

Workers run with a fixed glibc mmap threshold so that freed arrays go back to the OS and the
high-water mark of each evaluation is its own.
"""

from __future__ import annotations

import argparse
import importlib.util
import multiprocessing as mp
import os
import random
import re
import sys
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
PARITY = ROOT / "tests" / "data" / "parity"
TRANSFORMS = ("Translate", "Scale", "Rotate")
COMBINE = ("{a} + {b}", "{a} * {b}", "Min({a}, {b})", "Max({a}, {b})", "({a} - {b}) * 0.5")


# ---------------------------------------------------------------------------- programs
def _fuzz_module() -> Any:
    """tests/lang/test_fuzz.py (its mutation helpers and fragments), loaded by path."""
    spec = importlib.util.spec_from_file_location("soak_fuzz", ROOT / "tests/lang/test_fuzz.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _transform(rng: random.Random, ref: str) -> str:
    kind = rng.choice(TRANSFORMS)
    if kind == "Translate":
        return f"Translate({ref}, {rng.choice([0, 0.5, 1, 2, -1])}, {rng.choice([0, 0.25, 1])})"
    if kind == "Scale":
        return f"Scale({ref}, {rng.choice([0.5, 2, -1, 1.5])}, {rng.choice([1, 2, 0.5])})"
    return f"Rotate({ref}, {rng.choice([15, 30, 45, 90, 7])})"


def transform_chain(seed: int) -> str:
    """A Define chain whose levels combine transformed earlier levels (the defect's family)."""
    rng = random.Random(seed)
    levels = rng.randint(2, 12)
    octaves = rng.randint(1, 8)
    lines = [f"Define(d0, fBm(octaves={octaves}, base_freq={rng.randint(2, 12)}, seed={seed}))"]
    for k in range(1, levels + 1):
        a = _transform(rng, f"d{rng.randint(max(0, k - 2), k - 1)}")
        b = _transform(rng, f"d{k - 1}")
        lines.append(f"Define(d{k}, {rng.choice(COMBINE).format(a=a, b=b)})")
    top = f"d{levels}"
    lines.append(
        f"Material(Layer(1).basecolor(({top} * 80 + 100), 90, 80).roughness(0.5),\n"
        f"  Layer(Threshold({top}, above_at=0.2, below_at=0.1)).height(({top} * 0.02)))"
    )
    return "\n".join(lines)


def program_source(seed: int) -> str:
    """Random (1/3), Define-heavy (1/3) and transform-heavy (1/3) programs, by seed."""
    from matloom.lang.random_program import RandomConfig, random_program

    family = seed % 3
    if family == 0:
        return random_program(seed)
    if family == 1:
        config = RandomConfig(min_defs=4, max_defs=10, max_depth=5, max_layers=4)
        return random_program(seed, config=config)
    return transform_chain(seed)


_NUMBER = re.compile(r"(?<![A-Za-z_0-9.])\d+(\.\d*)?(e-?\d+)?")


def _mutate_numbers(text: str, rng: random.Random, fragments: list[str]) -> str:
    """Replace 1-3 numeric literals by numeric fragments (extreme values included), which
    keeps most programs valid so that they reach the evaluator."""
    numbers = [f for f in fragments if f and f.lstrip("-")[:1].isdigit()]
    spans = [m.span() for m in _NUMBER.finditer(text)]
    for start, end in sorted(rng.sample(spans, min(len(spans), rng.randint(1, 3))), reverse=True):
        text = text[:start] + rng.choice(numbers) + text[end:]
    return text


def mutated_program(index: int, fuzz: Any, bases: list[str]) -> str:
    """Program ``index`` of part (a): a source, then 0-4 mutations of it."""
    rng = random.Random(index)
    text = rng.choice(bases) if rng.random() < 0.15 else program_source(index)
    if rng.random() < 0.25:
        return text
    ops = []
    for _ in range(rng.randint(1, 4)):
        kind = rng.choice(["delete", "insert", "replace", "duplicate"])
        arg: Any = rng.randint(1, 40) if kind in ("delete", "duplicate") else None
        ops.append((kind, rng.randint(0, 10**6), arg or rng.choice(fuzz.FRAGMENTS)))
    kind = rng.random()
    if kind < 0.3:
        return _mutate_numbers(text, rng, fuzz.FRAGMENTS)
    if kind < 0.65:
        return fuzz._mutate_chars(text, ops)
    token_ops = [(rng.choice(["delete", "duplicate", "swap", "replace"]), p, f) for _, p, f in ops]
    return fuzz._mutate_tokens(text, [(k, p, str(f)) for k, p, f in token_ops])


# ---------------------------------------------------------------------------- worker side
def _status_kib(field_name: str) -> int:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith(field_name + ":"):
            return int(line.split()[1])
    return 0


def _reset_peak() -> int:
    """Reset VmHWM to the current RSS (Linux); returns the current RSS in KiB."""
    try:
        Path("/proc/self/clear_refs").write_text("5")
    except OSError:
        pass
    return _status_kib("VmRSS")


def _soak_job(text: str) -> dict[str, Any]:
    import matloom
    from matloom.engine.limits import LimitError

    start_rss = _reset_peak()
    t0 = time.perf_counter()
    outcome = "ok"
    try:
        if any(d.is_error for d in matloom.check(text)):
            outcome = "invalid"
        else:
            matloom.evaluate(text, 32, 32)
            matloom.preview(text, 32)
    except matloom.ProgramError:
        outcome = "program-error"
    except LimitError:
        outcome = "limit"
    except Exception as error:  # noqa: BLE001 - what the soak looks for
        outcome = f"UNHANDLED {type(error).__name__}: {error}"[:300]
        outcome += "\n" + traceback.format_exc()[-1500:]
    return {
        "outcome": outcome,
        "seconds": time.perf_counter() - t0,
        "peak_mib": _status_kib("VmHWM") / 1024,
        "growth_mib": (_status_kib("VmHWM") - start_rss) / 1024,
    }


def _memory_job(text: str, size: int, backend: str) -> dict[str, Any]:
    from matloom.engine.backends import get_backend
    from matloom.engine.evaluate import evaluate, prepare
    from matloom.engine.limits import LimitError, check_request

    program = prepare(text)
    be = get_backend(backend)
    evaluate(program, 16, 16, backend=be)  # loads and compiles what this program needs
    try:
        estimate = check_request(program, size, size, fused=be.fused).memory_mb
    except LimitError as error:
        return {"limit": str(error)}
    start_rss = _reset_peak()
    t0 = time.perf_counter()
    maps = evaluate(program, size, size, backend=be)
    seconds = time.perf_counter() - t0
    del maps
    growth = (_status_kib("VmHWM") - start_rss) / 1024
    return {"estimate_mib": estimate, "growth_mib": growth, "seconds": seconds}


def _worker(conn: Any) -> None:
    while True:
        job = conn.recv()
        if job is None:
            return
        kind, args = job
        try:
            result = _soak_job(*args) if kind == "soak" else _memory_job(*args)
        except Exception as error:  # noqa: BLE001 - reported by the parent
            result = {"outcome": f"UNHANDLED in worker {type(error).__name__}: {error}"}
        conn.send(result)


# ---------------------------------------------------------------------------- parent side
@dataclass
class _Slot:
    process: Any
    conn: Any
    job: Any = None
    started: float = 0.0


@dataclass
class Pool:
    """Worker processes with a per-job watchdog (a job past ``timeout`` s kills its worker)."""

    jobs: int
    timeout: float
    slots: list[_Slot] = field(default_factory=list)

    def __post_init__(self) -> None:
        os.environ["MALLOC_MMAP_THRESHOLD_"] = "131072"  # freed arrays leave the heap
        os.environ["MALLOC_TRIM_THRESHOLD_"] = "131072"
        self.ctx = mp.get_context("spawn")
        self.slots = [self._spawn() for _ in range(self.jobs)]

    def _spawn(self) -> _Slot:
        parent, child = self.ctx.Pipe()
        process = self.ctx.Process(target=_worker, args=(child,), daemon=True)
        process.start()
        return _Slot(process, parent)

    def run(self, jobs: list[tuple[Any, Any]]) -> list[dict[str, Any]]:
        """Results in job order ({"outcome": "TIMEOUT"} for a job the watchdog killed)."""
        results: list[dict[str, Any]] = [{} for _ in jobs]
        pending = list(enumerate(jobs))[::-1]
        while pending or any(s.job is not None for s in self.slots):
            for k, slot in enumerate(self.slots):
                if slot.job is None and pending:
                    slot.job, slot.started = pending.pop(), time.perf_counter()
                    slot.conn.send(slot.job[1])
                elif slot.job is not None and slot.conn.poll(0.01):
                    results[slot.job[0]] = slot.conn.recv()
                    slot.job = None
                elif slot.job is not None and time.perf_counter() - slot.started > self.timeout:
                    results[slot.job[0]] = {"outcome": "TIMEOUT", "seconds": self.timeout}
                    slot.process.kill()
                    self.slots[k] = self._spawn()
        return results

    def close(self) -> None:
        for slot in self.slots:
            slot.conn.send(None)
            slot.process.join(5)


def soak(pool: Pool, count: int, seed: int) -> None:
    fuzz = _fuzz_module()
    bases = [p.read_text() for p in sorted(PARITY.glob("*.mat")) if ".canonical" not in p.name]
    texts = [mutated_program(seed + i, fuzz, bases) for i in range(count)]
    t0 = time.perf_counter()
    results = pool.run([("soak", (t,)) for t in texts])
    outcomes: dict[str, int] = {}
    bad = []
    for i, r in enumerate(results):
        name = r.get("outcome", "?").split(":")[0].split("\n")[0]
        outcomes[name] = outcomes.get(name, 0) + 1
        if name.startswith(("UNHANDLED", "TIMEOUT", "?")):
            bad.append((i, r))
    worst_t = max(range(count), key=lambda i: results[i].get("seconds", 0.0))
    worst_m = max(range(count), key=lambda i: results[i].get("peak_mib", 0.0))
    print(f"(a) {count} mutated programs in {time.perf_counter() - t0:.0f} s: {outcomes}")
    print(f"    unhandled exceptions and timeouts: {len(bad)}")
    for i, r in bad[:10]:
        print(f"    program {seed + i}: {r.get('outcome')}\n{texts[i][:400]}")
    print(f"    worst time {results[worst_t].get('seconds', 0):.2f} s (program {seed + worst_t})")
    r = results[worst_m]
    print(
        f"    worst RSS {r.get('peak_mib', 0):.0f} MiB (program {seed + worst_m}; growth "
        f"{r.get('growth_mib', 0):.0f} MiB during it)"
    )


def memory(pool: Pool, count: int, size: int, seed: int) -> None:
    jobs = [
        ("memory", (program_source(seed + i), size, backend))
        for i in range(count)
        for backend in ("numba", "numpy")
    ]
    t0 = time.perf_counter()
    results = pool.run(jobs)
    rows = []
    for (kind, (text, _, backend)), r in zip(jobs, results, strict=True):
        del kind
        if "estimate_mib" in r:
            rows.append((r["growth_mib"] / r["estimate_mib"], r, backend, text))
    over = [row for row in rows if row[0] > 1.0]
    limited = sum(1 for r in results if "limit" in r)
    failed = [r for r in results if "outcome" in r]
    print(
        f"(b) {count} programs x 2 backends at {size}x{size} in {time.perf_counter() - t0:.0f} s:"
        f" {len(rows)} measured, {limited} over a limit, {len(failed)} failed"
    )
    for r in failed[:5]:
        print(f"    failed: {r.get('outcome')}")
    print(f"    peak RSS growth above the estimate: {len(over)}")
    rows.sort(key=lambda row: row[0], reverse=True)
    for ratio, r, backend, text in rows[:5]:
        print(
            f"    {backend:5s} growth {r['growth_mib']:7.1f} MiB / estimate "
            f"{r['estimate_mib']:7.1f} MiB = {ratio:.2f} ({r['seconds']:.2f} s)"
        )
        if ratio > 1.0:
            print("      " + text.replace("\n", "\n      "))
    worst = max(rows, key=lambda row: row[1]["growth_mib"]) if rows else None
    if worst:
        print(
            f"    largest growth {worst[1]['growth_mib']:.1f} MiB ({worst[2]}), estimate "
            f"{worst[1]['estimate_mib']:.1f} MiB"
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=10_000, help="part (a) programs (0 skips)")
    ap.add_argument("--memory-count", type=int, default=1_000, help="part (b) programs")
    ap.add_argument("--size", type=int, default=256, help="part (b) image size")
    ap.add_argument("--jobs", type=int, default=2, help="worker processes")
    ap.add_argument("--timeout", type=float, default=120.0, help="watchdog seconds per program")
    ap.add_argument("--seed", type=int, default=0, help="first program seed")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}; {args.jobs} workers")
    pool = Pool(args.jobs, args.timeout)
    try:
        if args.count:
            soak(pool, args.count, args.seed)
        if args.memory_count:
            memory(pool, args.memory_count, args.size, args.seed)
    finally:
        pool.close()
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
