"""``/api/blender``: the Blender flat or staged render of a program (only where Blender is
available, see :mod:`matloom.blender.runner`). The program is rendered as ``matloom render``
would into a private temporary folder, then rendered by Blender like ``matloom blender``;
nothing is written in the workspace."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from matloom.engine.session import Session
from matloom.studio.program import checked
from matloom.studio.protocol import ApiError, one_line

MODES = ("flat", "staged")


def render_png(text: str, mode: str, size: int, session: Session) -> bytes:
    """The PNG Blender renders of ``text`` in layout ``mode`` at ``size``."""
    from matloom.blender import BlenderError, render_layouts
    from matloom.engine.limits import LimitError
    from matloom.runtime.job import RenderJob, RenderJobError
    from matloom.runtime.run import run_render
    from matloom.runtime.sinks import FolderSink

    if mode not in MODES:
        raise ApiError(400, f"'mode' must be one of {', '.join(MODES)}")
    program = checked(text)
    work = Path(tempfile.mkdtemp(prefix="matloom-studio-blender-"))
    try:
        job = RenderJob(program, size, size, previews=())
        try:
            run_render(job, FolderSink(work / "maps"), session)
        except (RenderJobError, LimitError) as err:
            raise ApiError(422, one_line(err)) from None
        try:
            [image] = render_layouts(work / "maps", [mode], work / "out", size=size)
        except BlenderError as err:
            raise ApiError(422, one_line(err)) from None
        return image.read_bytes()
    finally:
        shutil.rmtree(work, ignore_errors=True)
