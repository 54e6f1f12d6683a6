"""Render a material with Blender and install the images: the shared core of ``matloom blender``
and the Python API the ``generate`` pipeline calls.

* :func:`render_source` renders one source into a folder the caller owns (a staging folder or a
  private temporary folder) and checks every image Blender wrote.
* :func:`render_layouts` renders an exported maps folder into ``out_dir/<layout>.png``.
* :func:`render_to_file` renders one image to a single ``out.png`` (``matloom blender -o x.png``).

Single files are installed like ``matloom preview -o x.png``: atomically, and an existing file
is replaced only when it is a PNG MatLoom wrote (its ``Software`` chunk). A ``.blend`` saved next
to a single file goes through the folder's ownership index (:mod:`matloom.io.outdir`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from matloom.blender.job import (
    MATERIAL_BLEND,
    BlenderJobError,
    RenderOptions,
    Source,
    build_job,
    load_source,
    render_names,
    write_job,
)
from matloom.blender.layouts import LAYOUT_NAMES
from matloom.blender.runner import Blender, BlenderError, check_version, find_blender, run_worker
from matloom.blender.tempdirs import TempDir

EventHandler = Callable[[dict[str, Any]], None]


def describe_event(event: dict[str, Any]) -> str | None:
    """One progress line for a worker event, or None for events not worth a line."""
    kind = event.get("event")
    if kind == "render_start":
        return (
            f"{event.get('layout')} view {event.get('view')} "
            f"({int(event.get('index', 0)) + 1}/{event.get('total')}) rendering"
        )
    if kind == "render":
        return (
            f"{event.get('layout')} view {event.get('view')} "
            f"({int(event.get('index', 0)) + 1}/{event.get('total')}) "
            f"in {float(event.get('seconds', 0)):.1f} s"
        )
    if kind == "saved":
        return f"saved {Path(str(event.get('path'))).name}"
    if kind == "device":
        return f"Cycles on {event.get('device')}"
    if kind == "warning":
        return f"warning: {event.get('message')}"
    return None


def render_source(
    source: Source,
    options: RenderOptions,
    out_dir: Path,
    blender: Blender,
    on_event: EventHandler | None = None,
) -> dict[str, Path]:
    """Render ``source`` into ``out_dir`` (an existing folder the caller owns) and return every
    file written, by name. The renders are checked and re-encoded (:mod:`.images`);
    :class:`BlenderError` or :class:`BlenderJobError` on failure."""
    from matloom.blender.images import adopt_render

    out_dir = out_dir.absolute()
    with TempDir("job-") as work:
        job = build_job(source, options, out_dir)
        run_worker(blender, write_job(job, work / "job.json"), on_event=on_event, temp_dir=work)
    written: dict[str, Path] = {}
    for view in job["renders"]:
        path = Path(view["output"])
        adopt_render(path, options.size)
        written[path.name] = path
    for key in ("save_blend", "save_material"):
        if job[key]:
            path = Path(job[key])
            if not path.is_file():
                raise BlenderError(f"Blender finished but saved no {path.name}")
            written[path.name] = path
    return written


def _layout_names(layouts: Sequence[str]) -> tuple[str, ...]:
    names: list[str] = []
    for name in layouts:
        for one in LAYOUT_NAMES if name == "both" else (name,):
            if one not in names:
                names.append(one)
    return tuple(names)


def _install_png(target: Path, data: bytes) -> Path:
    from matloom.io.outdir import write_output_file
    from matloom.io.png import written_by_matloom

    return write_output_file(target, data, written_by_matloom)


def _refuse_foreign_png(target: Path) -> None:
    """Fail before rendering when ``target`` could not be replaced afterwards."""
    import os

    from matloom.io.outdir import OutputError
    from matloom.io.png import written_by_matloom

    if target.is_dir():
        raise OutputError(f"{target} is a folder; give a file name")
    if os.path.lexists(target) and (target.is_symlink() or not written_by_matloom(target)):
        raise OutputError(
            f"{target} exists and was not written by MatLoom; MatLoom never overwrites such "
            "files: choose another name or remove it"
        )


def render_layouts(
    export_dir: Path,
    layouts: Sequence[str],
    out_dir: Path,
    *,
    size: int = 512,
    samples: int | None = None,
    blender: str | None = None,
    progress: Callable[[str], None] | None = None,
    views: str = "1",
    displacement: str = "true",
    device: str = "auto",
) -> list[Path]:
    """Render the maps folder ``export_dir`` (written by ``matloom render``, ``material.json`` at
    its top) in each of ``layouts`` ("flat", "staged", or "both") into ``out_dir/<layout>.png``
    (``<layout>_view-<k>.png`` with ``views="all"``) and return those paths, in layout order.

    ``samples`` defaults to each layout's own (64 flat, 160 staged); ``blender`` is a Blender
    executable or a Python with ``bpy`` (default: found as ``matloom blender`` finds it);
    ``progress`` receives one line when each view starts and when it is done. Existing files
    are replaced only when MatLoom wrote them. Every failure is a :class:`BlenderError` with a
    one-line message.
    """
    from matloom.io.outdir import OutputError

    try:
        options = RenderOptions(
            layouts=_layout_names(layouts),
            size=size,
            samples=samples,
            views=views,
            displacement=displacement,
            device=device,
        )
        options.validate()
        if not Path(export_dir).is_dir():
            raise BlenderJobError(f"{export_dir}: not a folder exported by `matloom render`")
        source = load_source(str(export_dir))
        found = find_blender(blender)
        check_version(found)
        out = Path(out_dir).absolute()
        targets = [out / name for _, _, name in render_names(options)]
        for target in targets:
            _refuse_foreign_png(target)

        def on_event(event: dict[str, Any]) -> None:
            line = describe_event(event)
            if progress is not None and line is not None:
                progress(line)

        with TempDir() as work:
            written = render_source(source, options, work, found, on_event)
            return [_install_png(t, written[t.name].read_bytes()) for t in targets]
    except (BlenderJobError, OutputError) as err:
        raise BlenderError(str(err).splitlines()[0]) from None


def render_to_file(
    source_path: str,
    options: RenderOptions,
    target: Path,
    blender: Blender,
    *,
    unit_m: float | None = None,
    on_event: EventHandler | None = None,
) -> list[Path]:
    """Render one image of ``source_path`` to the single file ``target`` (a ``.png``); saved
    ``.blend`` files go beside it. Returns the files installed.

    Raises :class:`BlenderJobError`, :class:`BlenderError` or
    :class:`matloom.io.outdir.OutputError`.
    """
    from matloom.io.outdir import OutputFolder

    options.validate()  # clashing names and bad options fail before anything is rendered
    names = render_names(options)
    if len(names) != 1:
        raise BlenderJobError(
            f"-o {target.name} names one image, but --layout/--views ask for {len(names)}: "
            "give a folder for -o"
        )
    target = target.absolute()
    _refuse_foreign_png(target)
    blends = [options.save] if options.save else []
    if options.save_material_only:
        blends.append(MATERIAL_BLEND)
    if blends:
        with OutputFolder(target.parent) as folder:
            folder.check_writable(blends)
    source = load_source(source_path, size=options.size, unit_m=unit_m)
    try:
        with TempDir() as work:
            written = render_source(source, options, work, blender, on_event)
            installed = [_install_png(target, written[names[0][2]].read_bytes())]
            if blends:
                with OutputFolder(target.parent) as folder:
                    for name in blends:
                        data = written[name].read_bytes()
                        group = f"blender:{target.name}:{name}"
                        installed.append(folder.write_bytes(name, data, group=group))
    finally:
        source.cleanup()
    return installed
