"""Engine work off the event loop: a small worker pool, one explicit engine session, and
per-stream supersession of evaluations.

The app owns one :class:`Evaluator`; its :class:`~matloom.engine.session.Session` (backend
policy, parse caches, the engine lock) serves every evaluation, export, edit and generate run
of the studio. The numba kernels share one thread pool that is not thread-safe, so engine work
holds ``session.lock``; the two workers let one request pack its maps (or parse) while the
other evaluates.

**Supersession.** Each evaluation names a ``stream`` (the 3D view, the inspector, the first
pass, ...) and a ``seq``; the newest ``seq`` received on a stream wins. A request whose stream
has seen a newer ``seq`` before it starts -- when it leaves the queue, and again when it gets
the engine lock -- is dropped with :class:`Superseded` (409): a slider drag queues many
requests and only the last one is worth evaluating.

**Limits before work.** The evaluation checks the size, the cost model and the memory budget
(:func:`matloom.engine.limits.check_request`) before any work, so a cost bomb is refused at
once with its one-line error (422) and the workers stay free.
"""

from __future__ import annotations

import asyncio
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace
from typing import Any, TypeVar

from matloom.engine.limits import DEFAULT_LIMITS
from matloom.engine.session import Session
from matloom.lang import ast as A
from matloom.studio.protocol import ApiError

T = TypeVar("T")

#: Engine workers (the machines have 2 cores; the engine lock serialises evaluations anyway).
WORKERS = 2
#: Streams remembered for supersession (the least recently used are forgotten).
MAX_STREAMS = 64
#: The interactive work budget: 2**35 node-texels, 1/128 of a render's (docs/limits.md). The
#: heaviest library entry (64,637 node evaluations per texel) still evaluates up to about
#: 724 x 724; a heavier request is refused at once ("lower the size") instead of holding the
#: engine for minutes. Exports keep the render limits.
INTERACTIVE_LIMITS = replace(DEFAULT_LIMITS, max_node_texels=1 << 35)


class Superseded(ApiError):
    """A newer request on the same stream arrived before this one started."""

    def __init__(self, stream: str, seq: int, newest: int) -> None:
        super().__init__(409, f"superseded: stream {stream!r} has seq {newest} (this is {seq})")


@dataclass(frozen=True)
class EvalRequest:
    """One ``/api/evaluate`` request, checked."""

    text: str
    size: int
    stream: str = "main"
    seq: int = 0
    hidden: tuple[int, ...] = ()
    solo: int | None = None
    lit: bool = False
    raw: tuple[str, ...] = ()
    pass_name: str = "full"
    #: With ``values``: the hash of the edited text that was evaluated (put in the header).
    text_sha: str | None = None
    received: float = field(default_factory=time.perf_counter)


class Evaluator:
    """The worker pool, the session and the streams' newest ``seq`` (see the module docstring)."""

    def __init__(self, session: Session | None = None, workers: int = WORKERS) -> None:
        self.session = session if session is not None else Session.from_env()
        self.pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="matloom-studio")
        self._newest: OrderedDict[str, int] = OrderedDict()
        self._lock = threading.Lock()

    async def run(self, fn: Callable[..., T], *args: Any) -> T:
        """``fn(*args)`` on a worker, awaited."""
        return await asyncio.get_running_loop().run_in_executor(self.pool, fn, *args)

    def close(self) -> None:
        self.pool.shutdown(wait=False, cancel_futures=True)

    # ------------------------------------------------------------------- supersession
    def receive(self, stream: str, seq: int) -> None:
        """Note a request's ``seq`` on its stream as it arrives."""
        with self._lock:
            newest = self._newest.pop(stream, None)
            self._newest[stream] = seq if newest is None else max(newest, seq)
            while len(self._newest) > MAX_STREAMS:
                self._newest.popitem(last=False)

    def check_current(self, stream: str, seq: int) -> None:
        """Raise :class:`Superseded` when the stream has seen a newer ``seq``."""
        with self._lock:
            newest = self._newest.get(stream, seq)
        if newest > seq:
            raise Superseded(stream, seq, newest)

    # ------------------------------------------------------------------- evaluation
    async def evaluate(self, req: EvalRequest) -> bytes:
        """The maps body of ``req`` (:mod:`matloom.studio.wire`); 409 when superseded, 422
        when the program does not check or is over the limits."""
        self.receive(req.stream, req.seq)
        return await self.run(self._evaluate, req)

    def _evaluate(self, req: EvalRequest) -> bytes:
        from matloom.engine.evaluate import evaluate
        from matloom.engine.limits import EVALUATE, LimitError, Usage
        from matloom.studio.wire import map_payloads, pack

        self.check_current(req.stream, req.seq)
        program = shown_layers(self.parsed(req.text), req.hidden, req.solo)
        usage = Usage(preview_tile=1) if req.lit else EVALUATE
        with self.session.lock:
            self.check_current(req.stream, req.seq)  # it may have waited for the lock
            t0 = time.perf_counter()
            try:
                maps = evaluate(program, req.size, req.size, usage=usage, session=self.session,
                                limits=INTERACTIVE_LIMITS)  # fmt: skip
            except LimitError as err:
                raise ApiError(422, str(err)) from None
            except ValueError as err:  # e.g. "material has no layers"
                raise ApiError(422, str(err)) from None
            eval_ms = (time.perf_counter() - t0) * 1000
            extra = {}
            if req.lit:
                from matloom.render.lit import shade_lit

                extra["lit"] = shade_lit(maps, session=self.session)
        payloads, facts = map_payloads(maps, req.raw, extra)
        v = maps.view
        header: dict[str, Any] = {
            "width": maps.width,
            "height": maps.height_px,
            "seq": req.seq,
            "stream": req.stream,
            "pass": req.pass_name,
            "eval_ms": round(eval_ms, 2),
            "view": {
                "x1": v.x1,
                "y1": v.y1,
                "x2": v.x2,
                "y2": v.y2,
                "tileable": v.tileable,
                "unit_m": v.unit_m,
            },  # fmt: skip
            "unit_m": v.unit_m,
            "tileable": v.tileable,
            "seam": seam_ratios(maps) if v.tileable and req.pass_name == "full" else None,
            **facts,
        }
        if req.text_sha is not None:
            header["text_sha"] = req.text_sha
        header["total_ms"] = round((time.perf_counter() - req.received) * 1000, 2)
        return pack(header, payloads)

    def parsed(self, text: str) -> A.Program:
        """The checked program of ``text`` (cached in the session); 422 with the diagnostics
        when it does not check."""
        from matloom.studio.program import checked

        return checked(text, self.session)

    def warm(self, text: str) -> None:
        """Warm the engine (numba's import and cached kernels) on small evaluations of
        ``text``, so the first real request runs on the fast path; errors are ignored."""
        from matloom.engine.evaluate import evaluate
        from matloom.engine.session import AUTO_NUMBA_AFTER_CALLS

        try:
            program = self.parsed(text)
            for _ in range(AUTO_NUMBA_AFTER_CALLS + 2):
                with self.session.lock:
                    evaluate(program, 32, 32, session=self.session, limits=INTERACTIVE_LIMITS)
        except Exception:  # noqa: BLE001 - a warm-up never fails the server
            pass


def shown_layers(program: A.Program, hidden: tuple[int, ...], solo: int | None) -> A.Program:
    """``program`` with the hidden layers left out (1-based, bottom first), or only the solo
    layer; 422 when no layer is left, 400 for an index that is not a layer."""
    if not hidden and solo is None:
        return program
    count = len(program.layers)
    for index in (*hidden, *(() if solo is None else (solo,))):
        if not 1 <= index <= count:
            raise ApiError(400, f"layer {index} does not exist (the program has {count})")
    if solo is not None:
        keep = [solo]
    else:
        keep = [k for k in range(1, count + 1) if k not in set(hidden)]
    if not keep:
        raise ApiError(422, "every layer is hidden: show at least one")
    return replace(program, layers=tuple(program.layers[k - 1] for k in keep))


def seam_ratios(maps: Any) -> dict[str, float] | None:
    """The manifest's seam ratio of every exported map (as ``render`` records them)."""
    from matloom.engine.tiling import manifest_entry
    from matloom.io.export import MAP_SPECS

    return manifest_entry(maps, MAP_SPECS).get("seam_ratio")


def wire_maps(evaluator: Evaluator, text: str, size: int) -> dict[str, Any]:
    """The maps of ``text`` at ``size`` as the wire sends them (name -> array); 422 when it
    does not check or is over the limits. Runs on a worker."""
    from matloom.engine.evaluate import evaluate
    from matloom.engine.limits import LimitError
    from matloom.studio.wire import map_payloads

    program = evaluator.parsed(text)
    with evaluator.session.lock:
        try:
            maps = evaluate(program, size, size, session=evaluator.session,
                            limits=INTERACTIVE_LIMITS)  # fmt: skip
        except (LimitError, ValueError) as err:
            raise ApiError(422, str(err)) from None
    payloads, _ = map_payloads(maps)
    return {p.name: p.array for p in payloads}
