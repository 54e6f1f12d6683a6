"""The studio's Starlette app: :func:`create_app` and its routes (the contract is
docs/studio-api.md).

Everything the app holds lives in one :class:`Studio` (the workspace, the token, the engine
evaluator with its session, the generate jobs); nothing is kept in module globals. Cheap
requests (check, format, structure, panel edits) run in Starlette's thread pool, engine work
(evaluate, compare, export, edit) on the evaluator's workers, so the event loop always answers.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import threading
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException
from starlette.middleware import Middleware
from starlette.requests import Request
from starlette.responses import (
    FileResponse,
    HTMLResponse,
    JSONResponse,
    Response,
    StreamingResponse,
)
from starlette.routing import Route

from matloom.engine.session import Session
from matloom.studio.evaluator import EvalRequest, Evaluator, wire_maps
from matloom.studio.jobs import Jobs, edit_json, model_setup
from matloom.studio.protocol import (
    MAX_BODY,
    MAX_EVAL_SIZE,
    ApiError,
    error_response,
    need_str,
    opt_bool,
    opt_int,
    opt_list,
    opt_str,
    read_body,
)
from matloom.studio.security import Guard
from matloom.studio.workspace import Workspace

LOG = logging.getLogger("matloom.studio")
#: The shipped front end (written by ``make studio-build``).
STATIC = Path(__file__).with_name("static")
#: The page's content security policy: nothing from another origin, no inline script.
CSP = (
    "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
    "img-src 'self' data: blob:; connect-src 'self'; worker-src 'self' blob:; "
    "object-src 'none'; base-uri 'none'; frame-ancestors 'none'"
)
NO_FRONT_END = (
    "<!doctype html><title>MatLoom studio</title><p>The studio's front end is not built: run "
    "<code>make studio-build</code> (needs node), then reload.</p>"
)
#: Seconds between keep-alive comments of an event stream.
HEARTBEAT_S = 15.0
POLL_S = 0.05

Handler = Callable[["Studio", Request], Awaitable[Response]]


@dataclass
class Studio:
    """What the app holds (see the module docstring)."""

    workspace: Workspace
    token: str
    evaluator: Evaluator
    jobs: Jobs
    static: Path = STATIC
    blender: bool = False
    vocab: dict[str, Any] | None = field(default=None, repr=False)
    #: Held while a Blender render runs: one at a time (each is a Blender process).
    blender_busy: threading.Lock = field(default_factory=threading.Lock, repr=False)

    @property
    def session(self) -> Session:
        return self.evaluator.session


def create_app(
    workspace: Workspace,
    token: str,
    *,
    port: int,
    host: str = "127.0.0.1",
    session: Session | None = None,
    static: Path | None = None,
    warm: bool = False,
) -> Starlette:
    """The studio app for ``workspace``, answering API calls that carry ``token``, served at
    ``host:port`` (the Host and Origin checks use them). ``session``: the engine session
    (default: one from the environment); ``warm``: load the fast engine path at start-up."""
    evaluator = Evaluator(session)
    studio = Studio(workspace, token, evaluator, Jobs(evaluator.session), static or STATIC,
                    blender=_blender_available())  # fmt: skip

    def route(path: str, handler: Handler, method: str = "POST") -> Route:
        async def endpoint(request: Request) -> Response:
            try:
                return await handler(studio, request)
            except ApiError as err:
                return err.response()
            except Exception as err:  # noqa: BLE001 - never a traceback to the page
                LOG.exception("studio: %s %s failed", request.method, request.url.path)
                return error_response(500, f"internal error: {type(err).__name__}: {err}")

        return Route(path, endpoint, methods=[method])

    @contextlib.asynccontextmanager
    async def lifespan(_app: Starlette) -> AsyncIterator[None]:
        if warm:
            text = _opened_text(studio)
            asyncio.get_running_loop().run_in_executor(evaluator.pool, evaluator.warm, text)
        try:
            yield
        finally:
            evaluator.close()

    routes = [
        route("/api/session", session_info, "GET"),
        route("/api/vocab", vocab, "GET"),
        route("/api/check", check),
        route("/api/format", format_),
        route("/api/structure", structure),
        route("/api/set", set_),
        route("/api/layers", layers),
        route("/api/seeds", seeds),
        route("/api/evaluate", evaluate),
        route("/api/compare", compare),
        route("/api/file", file, "GET"),
        route("/api/save", save),
        route("/api/export", export),
        route("/api/export.zip", export_zip),
        route("/api/generate", generate),
        route("/api/jobs/{job}/events", job_events, "GET"),
        route("/api/jobs/{job}/cancel", job_cancel),
        route("/api/edit", edit),
        route("/api/blender", blender),
        route("/api/{rest:path}", not_found, "GET"),
        route("/api/{rest:path}", not_found),
        route("/", static_file, "GET"),
        route("/{path:path}", static_file, "GET"),
    ]
    middleware = [Middleware(Guard, token=token, host=host, port=port)]  # type: ignore[arg-type]
    app = Starlette(routes=routes, middleware=middleware, lifespan=lifespan,
                    exception_handlers={HTTPException: _http_error})  # fmt: skip
    app.state.studio = studio
    return app


async def _http_error(request: Request, exc: Exception) -> Response:
    """Starlette's own refusals (a wrong method: 405) as the studio's one-line JSON errors."""
    assert isinstance(exc, HTTPException)
    reply = error_response(exc.status_code, str(exc.detail))
    reply.headers.update(exc.headers or {})
    return reply


def _blender_available() -> bool:
    try:
        from matloom.blender.runner import BlenderError, find_blender
    except ImportError:
        return False
    try:
        find_blender()
    except BlenderError:
        return False
    return True


def _opened_text(studio: Studio) -> str:
    from matloom.examples import example_text

    opened = studio.workspace.opened
    if opened is not None:
        try:
            return studio.workspace.read(opened)
        except ApiError:
            pass
    return example_text("black_ceramic_tiles")


def _json(data: Any, status: int = 200) -> JSONResponse:
    return JSONResponse(data, status_code=status, headers={"Cache-Control": "no-store"})


# ---------------------------------------------------------------------------- session, vocab
async def session_info(studio: Studio, request: Request) -> Response:
    from matloom._version import __version__
    from matloom.engine.limits import DEFAULT_LIMITS
    from matloom.io.presets import PRESETS

    ws = studio.workspace
    setup = await run_in_threadpool(model_setup)
    files = await run_in_threadpool(ws.programs)
    return _json(
        {
            "version": __version__,
            "token_ok": True,
            "root": str(ws.root),
            "files": files,
            "opened": ws.opened,
            "text": await run_in_threadpool(_opened_text, studio),
            "model": setup.model is not None,
            "model_access": setup.access,
            "model_error": setup.error,
            "blender": studio.blender,
            "presets": list(PRESETS),
            "limits": {
                "max_size": MAX_EVAL_SIZE,
                "max_export_size": DEFAULT_LIMITS.max_resolution,
                "max_body": MAX_BODY,
            },
        }
    )


async def vocab(studio: Studio, request: Request) -> Response:
    if studio.vocab is None:
        from matloom.studio.vocab_json import vocab_json

        studio.vocab = await run_in_threadpool(vocab_json)
    return _json(studio.vocab)


async def not_found(studio: Studio, request: Request) -> Response:
    raise ApiError(404, f"no such endpoint: {request.method} {request.url.path}")


# ---------------------------------------------------------------------------- language
async def check(studio: Studio, request: Request) -> Response:
    from matloom.studio.structure import check_json

    text = need_str(await read_body(request), "text")
    return _json(await run_in_threadpool(check_json, text, studio.session))


async def format_(studio: Studio, request: Request) -> Response:
    from matloom.studio.structure import format_text

    text = need_str(await read_body(request), "text")
    return _json({"text": await run_in_threadpool(format_text, text)})


async def structure(studio: Studio, request: Request) -> Response:
    from matloom.studio.structure import structure_json

    text = need_str(await read_body(request), "text")
    return _json(await run_in_threadpool(structure_json, text, studio.session))


async def set_(studio: Studio, request: Request) -> Response:
    from matloom.studio.structure import set_values

    body = await read_body(request)
    text = need_str(body, "text")
    return _json(await run_in_threadpool(set_values, text, _values(body), studio.session))


def _values(body: dict[str, Any]) -> dict[str, Any]:
    values = body.get("values")
    if not isinstance(values, dict) or not values:
        raise ApiError(400, "'values' must be an object of address -> value")
    return values


async def layers(studio: Studio, request: Request) -> Response:
    from matloom.studio.structure import layer_op

    body = await read_body(request)
    text, op = need_str(body, "text"), need_str(body, "op")
    index = opt_int(body, "index", 0)
    to = opt_int(body, "to", 0) if body.get("to") is not None else None
    return _json(await run_in_threadpool(layer_op, text, op, index, to))


async def seeds(studio: Studio, request: Request) -> Response:
    from matloom.studio.seeds import seed_op

    body = await read_body(request)
    text, op = need_str(body, "text"), need_str(body, "op")
    return _json(await run_in_threadpool(seed_op, text, op, opt_str(body, "address")))


# ---------------------------------------------------------------------------- engine
async def evaluate(studio: Studio, request: Request) -> Response:
    from matloom.studio.wire import MEDIA_TYPE, check_raw

    body = await read_body(request)
    try:
        raw = tuple(check_raw(opt_list(body, "channels", str)))
    except ValueError as err:
        raise ApiError(400, str(err)) from None
    solo = body.get("solo")
    if solo is not None and (isinstance(solo, bool) or not isinstance(solo, int)):
        raise ApiError(400, "'solo' must be a layer index or null")
    pass_name = opt_str(body, "pass", "full") or "full"
    if pass_name not in ("preview", "full"):
        raise ApiError(400, "'pass' must be preview or full")
    text, text_sha = need_str(body, "text"), None
    if body.get("values") is not None:  # evaluate the text /api/set makes of {text, values}
        from matloom.studio.structure import set_values

        edited = await run_in_threadpool(set_values, text, _values(body), studio.session)
        text, text_sha = edited["text"], edited["text_sha"]
    req = EvalRequest(
        text=text,
        size=opt_int(body, "size", 512, 1, MAX_EVAL_SIZE),
        stream=opt_str(body, "stream", "main") or "main",
        seq=opt_int(body, "seq", 0),
        hidden=tuple(opt_list(body, "hidden", int)),
        solo=solo,
        lit=opt_bool(body, "lit"),
        raw=raw,
        pass_name=pass_name,
        text_sha=text_sha,
    )
    data = await studio.evaluator.evaluate(req)
    header = json.loads(data[8 : 8 + int.from_bytes(data[4:8], "little")])
    timing = f"eval;dur={header['eval_ms']}, total;dur={header['total_ms']}"
    return Response(
        data, media_type=MEDIA_TYPE, headers={"Cache-Control": "no-store", "Server-Timing": timing}
    )


async def compare(studio: Studio, request: Request) -> Response:
    from matloom.studio.compare import compare_maps

    body = await read_body(request)
    a, b = need_str(body, "a"), need_str(body, "b")
    size = opt_int(body, "size", 256, 1, MAX_EVAL_SIZE)
    name = opt_str(body, "map", "basecolor") or "basecolor"
    ev = studio.evaluator
    maps_a = await ev.run(wire_maps, ev, a, size)
    maps_b = await ev.run(wire_maps, ev, b, size)
    return _json(await run_in_threadpool(compare_maps, maps_a, maps_b, name))


# ---------------------------------------------------------------------------- files
async def file(studio: Studio, request: Request) -> Response:
    path = request.query_params.get("path")
    if not path:
        raise ApiError(400, "give ?path=REL, a program in the workspace")
    text = await run_in_threadpool(studio.workspace.read, path)
    return _json({"path": path, "text": text})


async def save(studio: Studio, request: Request) -> Response:
    body = await read_body(request)
    path, text = need_str(body, "path", empty=False), need_str(body, "text")
    size = await run_in_threadpool(studio.workspace.save, path, text)
    return _json({"path": path, "bytes": size})


async def export(studio: Studio, request: Request) -> Response:
    from matloom.studio.exporting import export_folder, export_options

    body = await read_body(request)
    ws = studio.workspace
    options = await run_in_threadpool(export_options, body, ws, folder=True)
    return _json(await studio.evaluator.run(export_folder, options, ws, studio.session))


async def export_zip(studio: Studio, request: Request) -> Response:
    from matloom.studio.exporting import export_options
    from matloom.studio.exporting import export_zip as make_zip

    body = await read_body(request)
    options = await run_in_threadpool(export_options, body, studio.workspace, folder=False)
    data, name = await studio.evaluator.run(make_zip, options, studio.session)
    return Response(
        data,
        media_type="application/zip",
        headers={
            "Content-Disposition": f'attachment; filename="{name}"',
            "Cache-Control": "no-store",
        },  # fmt: skip
    )


# ---------------------------------------------------------------------------- author
async def generate(studio: Studio, request: Request) -> Response:
    body = await read_body(request)
    prompt = need_str(body, "prompt", empty=False)
    use_model = body.get("model")
    if use_model is not None and not isinstance(use_model, bool):
        raise ApiError(400, "'model' must be true, false or null")
    job = await run_in_threadpool(studio.jobs.start, prompt, use_model)
    return _json({"job": job.id})


async def job_events(studio: Studio, request: Request) -> Response:
    job = studio.jobs.get(request.path_params["job"])
    try:
        start = max(0, int(request.headers.get("last-event-id", "-1")) + 1)
    except ValueError:
        start = 0
    _, over = job.since(start)
    if over and start >= len(job.events) and start > 0:
        return Response(status_code=204)  # a finished stream: EventSource stops reconnecting

    async def stream() -> AsyncIterator[bytes]:
        index, quiet = start, 0.0
        while True:
            events, over = job.since(index)
            for kind, data in events:
                yield f"id: {index}\nevent: {kind}\ndata: {json.dumps(data)}\n\n".encode()
                index += 1
            if over and not events:
                return
            if events:
                quiet = 0.0
            else:
                await asyncio.sleep(POLL_S)
                quiet += POLL_S
                if quiet >= HEARTBEAT_S:
                    quiet = 0.0
                    yield b": keep-alive\n\n"

    headers = {"Cache-Control": "no-store", "X-Accel-Buffering": "no"}
    return StreamingResponse(stream(), media_type="text/event-stream", headers=headers)


async def job_cancel(studio: Studio, request: Request) -> Response:
    job = studio.jobs.get(request.path_params["job"])
    return _json({"job": job.id, "cancelled": job.stop(), "state": job.state})


async def edit(studio: Studio, request: Request) -> Response:
    body = await read_body(request)
    text, words = need_str(body, "text"), need_str(body, "request", empty=False)
    use_model = body.get("model")
    if use_model is not None and not isinstance(use_model, bool):
        raise ApiError(400, "'model' must be true, false or null")
    result = await studio.evaluator.run(edit_json, text, words, use_model, studio.session)
    return _json(result)


async def blender(studio: Studio, request: Request) -> Response:
    from matloom.studio.blender_view import render_png

    if not studio.blender:
        raise ApiError(404, "Blender is not available (see `matloom blender --help`)")
    body = await read_body(request)
    text = need_str(body, "text")
    mode = opt_str(body, "mode", "flat") or "flat"
    size = opt_int(body, "size", 512, 16, 2048)
    if not studio.blender_busy.acquire(blocking=False):
        raise ApiError(409, "a Blender render is already running; try again when it is done")
    try:
        png = await run_in_threadpool(render_png, text, mode, size, studio.session)
    finally:
        studio.blender_busy.release()
    return Response(png, media_type="image/png", headers={"Cache-Control": "no-store"})


# ---------------------------------------------------------------------------- static
async def static_file(studio: Studio, request: Request) -> Response:
    rel = request.path_params.get("path", "") or "index.html"
    if rel.startswith("static/"):
        rel = rel[len("static/") :]
    root = studio.static.resolve()
    try:
        target = (root / rel).resolve()
        found = root in target.parents and target.is_file()
    except (OSError, ValueError):  # a NUL byte, a name too long
        found = False
    if not found:
        if rel == "index.html":
            return HTMLResponse(NO_FRONT_END, status_code=503)
        raise ApiError(404, f"no such file: /{rel}")
    headers = {"Cache-Control": "no-cache"}
    if target.name == "index.html":
        headers["Content-Security-Policy"] = CSP
    return FileResponse(target, headers=headers)
