"""The author box: ``/api/generate`` (a background run of what ``matloom generate`` runs, its
rounds streamed as Server-Sent Events, cancellable) and ``/api/edit`` (``matloom.edit``).

Without a model in the user's own configuration (``matloom.toml``: ``$MATLOOM_CONFIG`` or
``~/.config/matloom/matloom.toml``, its default profile and settings preset, as ``generate``
reads them) a run is the material library, offline; with one, the LLM pipeline. Keys never
leave the server: the page only learns whether a model is configured and its one-line access
description.

A run authors into a private temporary run folder (removed afterwards) in a worker thread,
inside the app's engine session (its lock serialises the pipeline's renders with the studio's
evaluations). Each new program of the trajectory becomes a ``round`` event with a small preview;
progress lines become ``log`` events; the run ends with one ``done`` (the program) or ``error``.
*Cancel* ends the stream at once; the thread stops at its next progress report (a model request
in flight is not interrupted) and its results are dropped.
"""

from __future__ import annotations

import base64
import difflib
import shutil
import tempfile
import threading
import uuid
from collections import OrderedDict
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.engine.session import Session
from matloom.studio.protocol import ApiError, one_line

#: Side of each round's preview.
PREVIEW_SIZE = 128
#: Finished jobs kept for late readers of their events.
KEEP_JOBS = 8


class JobCancelled(Exception):
    """Raised inside a run's progress report once the user cancelled it."""


# ---------------------------------------------------------------------------- configuration
@dataclass(frozen=True)
class ModelSetup:
    """What the user's configuration says: the generate settings, the model (None: offline),
    its access line (no key), or the error reading the configuration."""

    config: Any
    model: Any | None
    access: str | None
    error: str | None = None


def model_setup() -> ModelSetup:
    """The settings ``matloom generate`` would use with no flags (read now)."""
    from matloom.author.access import describe_access
    from matloom.author.config import AuthorConfig, ConfigError, load_config_file, resolve_profile
    from matloom.author.settings_presets import default_preset, preset_values

    try:
        data = load_config_file()
        model = resolve_profile(data, None)
        preset = default_preset(data)
        values = preset_values(preset, data) if preset is not None else {}
        config = AuthorConfig.model_validate({**values, "generator": model})
    except (ConfigError, ValueError) as err:
        return ModelSetup(AuthorConfig(), None, None, one_line(err))
    access = describe_access("model", model) if model is not None else None
    return ModelSetup(config, model, access)


# ---------------------------------------------------------------------------- jobs
@dataclass
class Job:
    """One generate run: its events (``(kind, data)``, in order) and state."""

    id: str
    prompt: str
    events: list[tuple[str, dict[str, Any]]] = field(default_factory=list)
    state: str = "running"  # running, done, error, cancelled
    cancel: threading.Event = field(default_factory=threading.Event)
    lock: threading.Lock = field(default_factory=threading.Lock)
    #: The thread running it: a cancelled run's thread stops at its next progress report.
    thread: threading.Thread | None = None

    @property
    def busy(self) -> bool:
        """Running, or cancelled but its thread not yet stopped (its work still uses the CPU)."""
        if self.state == "running":
            return True
        thread = self.thread
        return self.state == "cancelled" and thread is not None and thread.is_alive()

    def emit(self, kind: str, data: dict[str, Any]) -> None:
        """Add an event unless the job is over (a cancelled run's late events are dropped)."""
        with self.lock:
            if self.state != "running":
                return
            self.events.append((kind, data))
            if kind in ("done", "error"):
                self.state = kind

    def since(self, index: int) -> tuple[list[tuple[str, dict[str, Any]]], bool]:
        """The events from ``index`` on, and whether the job is over."""
        with self.lock:
            return self.events[index:], self.state != "running"

    def stop(self) -> bool:
        """Cancel: the stream ends with ``error: cancelled``; False when already over."""
        self.cancel.set()
        with self.lock:
            if self.state != "running":
                return False
            self.events.append(("error", {"error": "cancelled"}))
            self.state = "cancelled"
            return True


class Jobs:
    """The app's generate runs (one at a time)."""

    def __init__(self, session: Session) -> None:
        self.session = session
        self._jobs: OrderedDict[str, Job] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, job_id: str) -> Job:
        with self._lock:
            job = self._jobs.get(job_id)
        if job is None:
            raise ApiError(404, f"no generate job {job_id!r}")
        return job

    def start(self, prompt: str, use_model: bool | None) -> Job:
        """Start a run for ``prompt`` (``use_model``: False forces the library, True needs a
        configured model, None uses one when configured)."""
        from matloom.author.pipeline import check_prompt

        try:
            check_prompt(prompt)
        except ValueError as err:
            raise ApiError(400, str(err)) from None
        setup = model_setup()
        if use_model and setup.model is None:
            raise ApiError(400, setup.error or "no model is configured (matloom.toml profile)")
        config = setup.config
        if use_model is False or setup.model is None:
            config = config.model_copy(update={"generator": None, "critic": None})
        with self._lock:
            running = [j for j in self._jobs.values() if j.busy]
            if any(j.state == "running" for j in running):
                raise ApiError(400, "a generate run is going on; cancel it first")
            if running:
                raise ApiError(
                    409, "the cancelled run is still stopping (at its next step); try again soon"
                )
            job = Job(uuid.uuid4().hex[:12], prompt)
            self._jobs[job.id] = job
            while len(self._jobs) > KEEP_JOBS:
                self._jobs.popitem(last=False)
        if config.generator is None:
            job.emit("log", {"line": "no model configured: using the material library"})
        elif setup.access:
            job.emit("log", {"line": setup.access})
        job.thread = threading.Thread(
            target=self._run, args=(job, config), name=f"matloom-generate-{job.id}", daemon=True
        )
        job.thread.start()
        return job

    def _run(self, job: Job, config: Any) -> None:
        from matloom.author.pipeline import AuthoringError, author_material
        from matloom.engine.session import use_session

        folder = Path(tempfile.mkdtemp(prefix="matloom-studio-run-"))
        rounds = _Rounds(job, folder / "run", self.session)
        try:
            with use_session(self.session):  # the pipeline's renders share the engine lock
                result = author_material(job.prompt, folder / "run", config,
                                         progress=rounds.progress)  # fmt: skip
                rounds.emit_new(result.record)
                job.emit("done", {"text": _final_text(result.record),
                                  "name": result.record.material_name})  # fmt: skip
        except JobCancelled:
            pass
        except AuthoringError as err:
            job.emit("error", {"error": one_line(err)})
        except Exception as err:  # noqa: BLE001 - the stream says what went wrong, in one line
            job.emit("error", {"error": f"{type(err).__name__}: {one_line(err)}"})
        finally:
            shutil.rmtree(folder, ignore_errors=True)


def _final_text(record: Any) -> str:
    """The run's program; the library's own text (with its header comments) when it is the
    same program."""
    from matloom.lang.api import analyse
    from matloom.lang.printer import format_program

    final = record.final.program
    if record.programs and record.final.program_index == 0:
        authored = record.programs[0].authored
        program, diags = analyse(authored)
        if program is not None and not any(d.is_error for d in diags):
            if format_program(program) == final:
                return authored.rstrip("\n")
    return final


class _Rounds:
    """Turns a run's progress reports into ``log`` and ``round`` events."""

    def __init__(self, job: Job, folder: Path, session: Session) -> None:
        self.job, self.folder, self.session = job, folder, session
        self.sent = 0
        self.last: tuple[str, int | None] | None = None

    def progress(self, event: Any) -> None:
        if self.job.cancel.is_set():
            raise JobCancelled
        if event.done is None or event.done == event.total:
            line = f"{event.stage}: {event.message}"
            if event.total:
                line += f" {event.done}/{event.total}"
            self.job.emit("log", {"line": line})
        key = (event.stage, event.round)
        if key != self.last:
            self.last = key
            self._sync()

    def _sync(self) -> None:
        from matloom.author.records import RECORD_NAME, RecordStore

        if not (self.folder / RECORD_NAME).is_file():
            return
        try:
            record = RecordStore.load(self.folder).record
        except (OSError, ValueError):
            return
        self.emit_new(record)

    def emit_new(self, record: Any) -> None:
        for program in record.programs[self.sent :]:
            critique = record.critique_of(program.index)
            self.job.emit(
                "round",
                {
                    "round": program.index,
                    "score": critique.match_score if critique is not None else None,
                    "text": program.text,
                    "preview_png_b64": self._preview(program.text),
                },
            )
            self.sent += 1

    def _preview(self, text: str) -> str | None:
        from matloom.io.png import encode_png
        from matloom.render.api import preview

        try:
            with self.session.lock:
                image = preview(text, PREVIEW_SIZE, session=self.session)
        except Exception:  # noqa: BLE001 - a round without a preview is still a round
            return None
        return base64.b64encode(encode_png(image)).decode("ascii")


# ---------------------------------------------------------------------------- edit
def edit_json(text: str, request: str, use_model: bool | None, session: Session) -> dict:
    """``/api/edit``: the edited text, a unified diff and the report; 422 when refused (with
    the parameters it could change) or when the edit fails."""
    from matloom.author.edit import EditError, EditRefused, edit
    from matloom.lang.diagnostics import ProgramError

    model = None
    if use_model is not False:
        setup = model_setup()
        if use_model and setup.model is None:
            raise ApiError(400, setup.error or "no model is configured (matloom.toml profile)")
        if setup.model is not None:
            from matloom.author.llm.providers import get_model

            try:
                model = get_model(setup.model)
            except Exception as err:  # noqa: BLE001 - ModelError and friends, one line
                raise ApiError(400, one_line(err)) from None
    try:
        # not under the session's lock: each evaluation takes it (engine.evaluate), so the 3D
        # view keeps updating while a model answers
        result = edit(text, request, model, session=session)
    except EditRefused as err:
        raise ApiError(422, str(err), parameters=[p.to_json() for p in err.params]) from None
    except (EditError, ProgramError, ValueError) as err:
        raise ApiError(422, one_line(err)) from None
    after = result.program
    diff = "".join(
        difflib.unified_diff(
            text.splitlines(keepends=True),
            after.splitlines(keepends=True),
            fromfile="before",
            tofile="after",
        )
    )
    return {"text": after, "diff": diff, "report": result.report.to_json()}
