"""A render job: one description of "evaluate this program and export its maps", checked
before any work.

:class:`RenderJob` holds everything ``matloom render`` asks for (size, tileable, the encoding,
presets, physical size, name, map subset, AO radius, previews, seed, backend, metadata); the
CLI ``render``, ``generate``'s export, ``library render``, the demo, :func:`export_maps
<matloom.runtime.export.export_maps>`, Blender's program sources, and later the studio and
cluster workers all build one and hand it to :func:`matloom.runtime.run.run_render`.

:func:`plan_render` turns a job into a :class:`RenderPlan`: the program to evaluate (omitted
seeds made explicit, tileable applied), the text ``material.json`` hashes and ``material.mat``
holds, the View (widened for square texels), the files it will write, and the notes said on
the way. Everything that can be refused is refused there, with a :class:`RenderJobError`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from matloom.engine.limits import DEFAULT_LIMITS, EVALUATE, Usage
from matloom.engine.session import Session, default_session
from matloom.io.encode import Encoding
from matloom.lang import ast as A

if TYPE_CHECKING:
    from matloom.engine.maps import MaterialMaps

#: The largest AO radius, in texels (the largest image side a render may have).
MAX_AO_TEXELS = DEFAULT_LIMITS.max_resolution
#: Preview layouts: name -> (file name, tiles per side). ``preview`` is the flat swatch the
#: CLI writes, ``tiled`` the same swatch repeated 2 x 2 (seams show), as the demo writes.
PREVIEWS: dict[str, tuple[str, int]] = {
    "preview": ("preview.png", 1),
    "tiled": ("preview_tiled.png", 2),
}
#: The program file of a render folder.
PROGRAM_FILE = "material.mat"

View4 = tuple[float, float, float, float]
Notify = Callable[[str], None]


class RenderJobError(ValueError):
    """A job that cannot run; the message is one line for the user. ``field`` names the job
    field at fault (``ao_radius``, ``unit_m``, ``program``, ...; ``program_unit_m`` for the
    ``unit_m`` of the program's own View) so that a front end can point at its option."""

    def __init__(self, message: str, field: str | None = None) -> None:
        super().__init__(message)
        self.field = field


@dataclass(frozen=True)
class RenderJob:
    """What to render and export (see the module docstring).

    ``program`` is an AST or a text. An AST is recorded in canonical form; a text is recorded
    as it is, unless the job changes it (omitted seeds made explicit from ``program_seed``,
    ``tileable`` turned on), and then in canonical form. When
    :func:`~matloom.runtime.run.run_render` is given the maps, the program is only recorded
    (never parsed or changed) and may be None (no ``material.mat`` then).
    """

    program: A.Program | str | None
    width: int = 512
    height: int = 512
    #: Every map repeats seamlessly with the View (as ``View(..., tileable=True)``).
    tileable: bool = False
    #: With ``width != height`` keep the program's View (non-square texels) instead of widening.
    stretch: bool = False
    encoding: Encoding = field(default_factory=Encoding)
    #: Engine/interchange presets (:data:`matloom.io.presets.PRESETS`), each in its subfolder.
    presets: tuple[str, ...] = ()
    #: Metres per coordinate unit; replaces the program's ``View(..., unit_m=...)``.
    unit_m: float | None = None
    #: The material's name (``name`` in material.json, the prefix of preset files).
    name: str = "material"
    #: The maps to write (:data:`matloom.io.export.MAP_NAMES`); None: all of them.
    map_names: tuple[str, ...] | None = None
    #: AO radius in coordinate units (None: the reference's 8 texels).
    ao_radius: float | None = None
    #: Preview layouts to write (:data:`PREVIEWS`); empty: none.
    previews: tuple[str, ...] = ("preview",)
    #: Seed of the noise calls that omit theirs.
    program_seed: int = 0
    #: Kernel backend of the evaluation (``auto``, ``numpy`` or ``numba``).
    backend: str = "auto"
    #: Stored under ``extra`` in material.json (None: no ``extra`` key).
    extra: Mapping[str, Any] | None = None
    #: Where the program comes from (a path), for the diagnostics said on the way.
    source: str | None = None
    #: The program's source text, for the excerpts of those diagnostics (default: a text
    #: ``program``).
    source_text: str | None = None
    #: Write ``material.mat`` (the recorded program text and a newline).
    write_program: bool = True
    #: What ``material.mat`` holds instead, when it must differ from the recorded text (e.g.
    #: a copy with secrets redacted; ``material.json`` still hashes the recorded text).
    program_file_text: str | None = None
    #: ``engine_version`` in material.json (None: this MatLoom's version).
    engine_version: str | None = None


@dataclass(frozen=True)
class RenderPlan:
    """A checked :class:`RenderJob` (see :func:`plan_render`)."""

    job: RenderJob
    #: The program to evaluate (None when the maps are given).
    program: A.Program | None
    #: The recorded program text (hashed into material.json; None: no program).
    text: str | None
    #: The View to evaluate on (None when the maps are given).
    view: View4 | None
    #: ``view_adjusted`` of material.json (None when the program's View is used as it is).
    view_note: dict[str, Any] | None
    #: Every file name the render may write (preset files are checked at the install).
    files: tuple[str, ...]
    #: The lines said while planning (also given to ``notify`` as they came).
    notes: tuple[str, ...]

    @property
    def usage(self) -> Usage:
        """What the render makes of its maps besides the evaluation (the limit check)."""
        tiles = [PREVIEWS[p][1] for p in self.job.previews]
        return Usage(preview_tile=max(tiles)) if tiles else EVALUATE


def plan_render(
    job: RenderJob,
    maps: MaterialMaps | None = None,
    notify: Notify | None = None,
    session: Session | None = None,
) -> RenderPlan:
    """Check ``job`` and work out what it does (``maps``: the job's maps, evaluated already;
    ``session``: whose cache holds a parsed program text).

    Raises :class:`RenderJobError` for anything that would fail later, before any work;
    ``notify`` hears each note as it comes (omitted seeds made explicit, the tileable
    warnings, a ``unit_m`` replacing the program's)."""
    notes: list[str] = []

    def say(line: str) -> None:
        notes.append(line)
        if notify is not None:
            notify(line)

    files = _check_options(job)
    if maps is None:
        if job.program is None:
            raise RenderJobError("a render job needs a program (or its maps)", "program")
        program, text = _prepare(job, say, session)
        view, view_note = square_texel_view(program.view_tuple, job.width, job.height, job.stretch)
        if job.ao_radius is not None:
            check_ao_radius(job.ao_radius, view, job.width, job.height)
        check_physical_size(job.unit_m, program.unit_m, view, say)
    else:  # the maps say their View; the program is recorded as it is, never parsed
        program, view, view_note = None, None, None
        text = _recorded_text(job.program)
        v = maps.view
        check_physical_size(job.unit_m, v.unit_m, (v.x1, v.y1, v.x2, v.y2), say)
    if not (job.write_program and text is not None):
        files = tuple(f for f in files if f != PROGRAM_FILE)
    return RenderPlan(job, program, text, view, view_note, files, tuple(notes))


def _recorded_text(program: A.Program | str | None) -> str | None:
    if isinstance(program, A.Program):
        from matloom.lang.printer import format_program

        return format_program(program)
    return program


def _check_options(job: RenderJob) -> tuple[str, ...]:
    """The job's options outside the program (and the files they make); ValueErrors become
    :class:`RenderJobError`."""
    from matloom.io.export import check_unit_m, planned_files, preset_writers

    unknown = [p for p in job.previews if p not in PREVIEWS]
    if unknown:
        raise RenderJobError(
            f"unknown preview layout(s) {', '.join(unknown)}; choose from {', '.join(PREVIEWS)}",
            "previews",
        )
    for name, check in (
        ("map_names", lambda: planned_files(job.map_names, job.encoding.float_format)),
        ("presets", lambda: preset_writers(job.presets)),
        ("unit_m", lambda: check_unit_m(job.unit_m)),
    ):
        try:
            check()
        except ValueError as err:
            raise RenderJobError(str(err), name) from None
    enc = job.encoding
    files = planned_files(job.map_names, enc.float_format, "preview" in job.previews, enc)
    extra = [PREVIEWS[p][0] for p in job.previews if p != "preview"]
    return (*files, *extra)


def _prepare(job: RenderJob, say: Notify, session: Session | None) -> tuple[A.Program, str]:
    """The program to evaluate and its recorded text: omitted seeds made explicit, tileable
    applied (its warnings said)."""
    from matloom.lang.diagnostics import format_diagnostics
    from matloom.lang.printer import format_program
    from matloom.lang.seeds import canonicalize_seeds, has_seedless_noise
    from matloom.lang.tileable import make_tileable, tileable_warnings

    given = job.program
    if isinstance(given, str):
        from matloom.lang.api import parse
        from matloom.lang.diagnostics import ProgramError

        try:  # parsed once per session (the AST is immutable)
            program = (session or default_session()).cached("parsed", given, lambda: parse(given))
        except ProgramError as err:
            errors = [d for d in err.diagnostics if d.is_error]
            message = format_diagnostics(errors, job.source or "<program>")
            raise RenderJobError(message, "program") from None
        source_text = job.source_text if job.source_text is not None else given
    else:
        assert given is not None
        program, source_text = given, job.source_text or ""
    changed = not isinstance(given, str)
    if has_seedless_noise(program):
        program = canonicalize_seeds(program, job.program_seed)
        say(f"note: omitted noise seeds made explicit from program seed {job.program_seed}")
        changed = True
    if job.tileable or program.tileable:
        warnings = tileable_warnings(program, source_text)
        if warnings:
            say(format_diagnostics(warnings, job.source or "<program>"))
        changed = changed or not program.tileable
        program = make_tileable(program)
    text = format_program(program) if changed else str(given)
    return program, text


def square_texel_view(view: View4, w: int, h: int, stretch: bool) -> tuple[View4, dict | None]:
    """The View to render ``w`` x ``h`` with square texels: the program's View widened about
    its centre along the short side (only when ``w != h`` and not ``stretch``), and a note for
    the manifest (None when the View is used as it is)."""
    x1, y1, x2, y2 = view
    dx, dy = abs(x2 - x1) / w, abs(y2 - y1) / h
    if w == h or abs(dx - dy) <= 1e-9 * max(dx, dy):
        return view, None
    if stretch:
        return view, {"program_view": list(view), "note": "--stretch: texels are not square"}
    texel = max(dx, dy)
    cx, cy = (x1 + x2) / 2, (y1 + y2) / 2
    half_w = texel * w / 2 * (1 if x2 >= x1 else -1)
    half_h = texel * h / 2 * (1 if y2 >= y1 else -1)
    widened = (cx - half_w, cy - half_h, cx + half_w, cy + half_h)
    note = {
        "program_view": list(view),
        "note": "the View was widened about its centre so that texels stay square "
        "(--stretch keeps the program's View)",
    }
    return widened, note


def check_ao_radius(units: float, view: View4, w: int, h: int) -> None:
    """Refuse an AO radius wider than the largest image side (in texels of this View and size)."""
    from matloom.engine.maps import View

    if not units >= 0:
        raise RenderJobError(f"the AO radius must be >= 0, got {units:g}", "ao_radius")
    dx, dy = View(*view).texel_size(w, h)  # > 0: the checker refuses zero and tiny Views
    texels = units / min(dx, dy)
    if texels > MAX_AO_TEXELS:
        raise RenderJobError(
            f"{units:g} units is {texels:.3g} texels at {w}x{h} with this View; the radius may "
            f"be at most {MAX_AO_TEXELS} texels ({MAX_AO_TEXELS * min(dx, dy):.6g} units)",
            "ao_radius",
        )


def check_physical_size(
    unit_m: float | None, program_unit_m: float | None, view: View4, say: Notify
) -> None:
    """The physical size (``unit_m``, else the program's) must be one the presets can store;
    a ``unit_m`` that replaces a different program ``unit_m`` is said (one line naming both)."""
    from matloom.io.presets.common import physical_size_problem, unit_m_override_note

    effective = unit_m if unit_m is not None else program_unit_m
    if effective is None:
        return
    x1, y1, x2, y2 = view
    problem = physical_size_problem(effective, (abs(x2 - x1), abs(y2 - y1)))
    if problem is not None:
        raise RenderJobError(problem, "unit_m" if unit_m is not None else "program_unit_m")
    note = unit_m_override_note(unit_m, program_unit_m, abs(x2 - x1))
    if note is not None:
        say(note)
