"""Where a render's files go: the :class:`Sink` protocol and its two implementations.

:func:`matloom.runtime.run.run_render` talks to a sink in two steps:

1. ``with sink.reserve(planned):`` -- before any work, the sink takes the destination for the
   whole job (a folder is locked: a second writer fails at once) and refuses a destination
   where one of the ``planned`` file names (relative, ``/``-separated) cannot be written;
2. ``with sink.batch(marker) as staging:`` -- inside the reservation, an empty local staging
   folder; the render writes every file into it (maps, presets' subfolders, previews,
   ``material.mat``, the ``marker`` ``material.json`` last). When the block ends normally the
   sink delivers the files, ``marker`` last, so a destination without it is one whose
   delivery did not finish; when it raises, nothing is delivered.

:attr:`Sink.root` is the local folder the files end up in (None where they do not land on
this machine's file system); the result's paths are relative to it.

Implementations: :class:`FolderSink` (the owned, staged, locked folder of
:mod:`matloom.io.outdir`, what ``matloom render`` and ``generate`` write) and
:class:`MemorySink` (the encoded files kept in memory, for the studio). A cluster worker's
sink implements the same three members, e.g. for an object store: ``reserve`` takes a lease
on the key prefix (failing when another worker holds it) and checks the planned keys,
``batch`` stages into a local temporary folder and on success uploads each file under the
prefix with ``material.json`` last (readers treat a prefix without it as incomplete), and
``root`` is None.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator, Sequence
from contextlib import AbstractContextManager, contextmanager, nullcontext
from pathlib import Path
from typing import Protocol

from matloom.io.outdir import OutputFolder

#: The batch group of a render in an :class:`~matloom.io.outdir.OutputFolder`.
RENDER_GROUP = "render"


class Sink(Protocol):
    """The destination of a render's files (see the module docstring)."""

    @property
    def root(self) -> Path | None:
        """The local folder the files are delivered to; None when not on this file system."""

    def reserve(self, planned: Sequence[str]) -> AbstractContextManager[object]:
        """Hold the destination for the job; raise before any work if a planned file cannot
        be written there."""

    def batch(self, marker: str) -> AbstractContextManager[Path]:
        """An empty staging folder whose files are delivered (``marker`` last) when the block
        ends normally, and dropped otherwise."""


class FolderSink:
    """A MatLoom output folder (:class:`~matloom.io.outdir.OutputFolder`): locked while the
    job runs, foreign files never replaced (checked before the work starts and again at the
    install), the files installed as one batch of group ``group``.

    ``target`` is a folder path, or an :class:`OutputFolder` the caller has opened already
    (a ``generate`` run folder); the caller then keeps it open and locked.
    """

    def __init__(self, target: str | os.PathLike[str] | OutputFolder, group: str = RENDER_GROUP):
        self._given = target if isinstance(target, OutputFolder) else None
        self._path = Path(target).absolute() if self._given is None else self._given.path
        self.group = group
        self._folder: OutputFolder | None = self._given

    @property
    def root(self) -> Path:
        return self._path

    @contextmanager
    def reserve(self, planned: Sequence[str]) -> Iterator[OutputFolder]:
        if self._given is not None:
            self._given.check_writable(planned)
            yield self._given
            return
        with OutputFolder(self._path) as folder:  # locked before the work starts
            folder.check_writable(planned)
            self._folder = folder
            try:
                yield folder
            finally:
                self._folder = None

    def batch(self, marker: str) -> AbstractContextManager[Path]:
        if self._folder is None:
            raise RuntimeError("FolderSink.batch outside FolderSink.reserve")
        return self._folder.batch(self.group, marker=marker)


class MemorySink:
    """Keeps the delivered files in memory: :attr:`files` maps each relative path
    (``/``-separated, e.g. ``gltf/m.gltf``) to its bytes, in sorted order; a later batch
    replaces them. Nothing stays on disk (the staging folder is a temporary one)."""

    def __init__(self) -> None:
        self.files: dict[str, bytes] = {}

    @property
    def root(self) -> None:
        return None

    def reserve(self, planned: Sequence[str]) -> AbstractContextManager[object]:
        return nullcontext()

    @contextmanager
    def batch(self, marker: str) -> Iterator[Path]:
        staging = Path(tempfile.mkdtemp(prefix="matloom-render-"))
        try:
            yield staging
            self.files = {
                p.relative_to(staging).as_posix(): p.read_bytes()
                for p in sorted(staging.rglob("*"))
                if p.is_file()
            }
        finally:
            shutil.rmtree(staging, ignore_errors=True)
