"""Preview views of trajectory programs: what the critic (and a revising generator) is shown.

A program is evaluated once per size and shaded in each requested layout: ``flat`` is the
paper's head-on swatch (:func:`matloom.render.preview.shade`, byte-identical to
:func:`matloom.render.api.preview`), ``lit`` the studio layout of :mod:`matloom.render.lit`.
The statistics come from the same evaluation when they are the ``visible`` ones (computed at
the critique resolution), or from the paper's 28 statistics on their own grid.

Engine work is serialised by the session's lock (``session.lock``, see
:mod:`matloom.engine.session`): the numba kernels are ``parallel=True`` and numba's default
threading layer is not thread-safe, so the runs of a threaded batch take turns.
"""

from __future__ import annotations

import io
from collections import OrderedDict
from typing import TYPE_CHECKING

import numpy as np

from matloom.author.llm.base import ImageInput

if TYPE_CHECKING:
    from matloom.author.reference import ReferencePhoto
    from matloom.engine.maps import MaterialMaps
    from matloom.engine.session import Session

#: Evaluated maps kept per renderer (a 512 x 512 evaluation is tens of MB).
_MAPS_KEPT = 2


class ViewUnavailableError(RuntimeError):
    """A requested layout or statistics module is not installed in this MatLoom."""


def view_file(index: int, view: str) -> str:
    """Where the critic's image of P_index in layout ``view`` is stored in the run folder."""
    return f"renders/p{index}.png" if view == "flat" else f"renders/p{index}_{view}.png"


def png_bytes(image: np.ndarray) -> bytes:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="PNG")
    return buffer.getvalue()


def jpeg_bytes(image: np.ndarray) -> bytes:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="JPEG", quality=92)
    return buffer.getvalue()


def image_input(image: np.ndarray, path: str | None) -> ImageInput:
    """The image as a model input (JPEG, as the reference sent it) stored at ``path``."""
    return ImageInput(data=jpeg_bytes(image), mime="image/jpeg", path=path)


def shade_view(
    maps: MaterialMaps, view: str, *, backend: str = "auto", session: Session | None = None
) -> np.ndarray:
    """uint8 RGB image of ``maps`` in preview layout ``view`` (``flat`` or ``lit``); ``auto``
    is ``session``'s choice of shader."""
    if view == "flat":
        from matloom.render.preview import shade

        return shade(maps, backend=backend, session=session)
    if view == "lit":
        try:
            from matloom.render.lit import shade_lit
        except ImportError as err:
            raise ViewUnavailableError(f"the lit preview is unavailable ({err})") from None
        return shade_lit(maps, backend=backend, session=session)
    raise ValueError(f"unknown preview layout {view!r}; choose flat or lit")


def available_views(views: tuple[str, ...]) -> tuple[tuple[str, ...], str | None]:
    """(the layouts of ``views`` this MatLoom can shade, or flat when none; a warning naming
    the missing ones, or None)."""
    missing = []
    if "lit" in views:
        try:
            from matloom.render.lit import shade_lit  # noqa: F401
        except ImportError as err:
            missing.append(f"the lit preview is unavailable ({err})")
    if not missing:
        return views, None
    kept = tuple(v for v in views if v != "lit") or ("flat",)
    return kept, f"{'; '.join(missing)}; the critic saw the {' and '.join(kept)} preview only"


def visible_stats(
    maps: MaterialMaps, program: str | None = None, *, session: Session | None = None
) -> str:
    """The statistics of what is visible at the maps' resolution; given the ``program`` the
    maps are of, also its coverage per layer and the sources of its repeating patterns
    (:mod:`matloom.render.layer_stats`)."""
    try:
        from matloom.render.layer_stats import visible_stats_text as with_layers
        from matloom.render.visible_stats import visible_stats_text
    except ImportError as err:
        raise ViewUnavailableError(f"the visible statistics are unavailable ({err})") from None
    if program is None:
        return visible_stats_text(maps)
    return with_layers(program, maps, session=session)


class Renderer:
    """Evaluates and shades programs for one run, caching images and the latest maps, in
    ``session`` (default: the process's default session; its lock serialises the engine work
    of the runs of a threaded batch)."""

    def __init__(
        self, session: Session | None = None, reference: ReferencePhoto | None = None
    ) -> None:
        from matloom.engine.session import default_session

        self.session = session or default_session()
        #: The run's reference photo (``--reference``): :meth:`stats` then compares the flat
        #: preview with it (:mod:`matloom.render.compare_stats`).
        self.reference = reference
        self._maps: OrderedDict[tuple[str, int], MaterialMaps] = OrderedDict()
        self._images: dict[tuple[str, int, str], np.ndarray] = {}

    def maps(self, program: str, size: int) -> MaterialMaps:
        """The program's maps at ``size`` x ``size`` (evaluated as the preview does)."""
        key = (program, size)
        if key in self._maps:
            self._maps.move_to_end(key)
            return self._maps[key]
        from matloom.engine.evaluate import evaluate
        from matloom.engine.limits import Usage

        with self.session.lock:
            maps = evaluate(program, size, size, usage=Usage(preview_tile=1), session=self.session)
        self._maps[key] = maps
        while len(self._maps) > _MAPS_KEPT:
            self._maps.popitem(last=False)
        return maps

    def image(self, program: str, size: int, view: str = "flat") -> np.ndarray:
        """The program's preview at ``size`` in layout ``view``."""
        key = (program, size, view)
        if key not in self._images:
            maps = self.maps(program, size)
            with self.session.lock:
                self._images[key] = shade_view(maps, view, session=self.session)
        return self._images[key]

    def stats(self, program: str, kind: str, *, grid: int, size: int) -> str:
        """The critic's statistics: ``paper`` (28, on a ``grid`` grid) or ``visible`` (at
        ``size``, the critique resolution), followed by the comparison with the reference
        photo when the run has one."""
        text = self._stats(program, kind, grid=grid, size=size)
        if self.reference is None:
            return text
        return f"{text.rstrip()}\n\n{self.reference_comparison(program, size)}"

    def reference_comparison(self, program: str, size: int) -> str:
        """The flat preview at ``size`` compared with the reference photo at that size."""
        from matloom.render.compare_stats import comparison_text, image_stats

        assert self.reference is not None
        render = image_stats(self.image(program, size, "flat"))
        return comparison_text(render, image_stats(self.reference.at(size)))

    def _stats(self, program: str, kind: str, *, grid: int, size: int) -> str:
        if kind == "visible":
            maps = self.maps(program, size)
            with self.session.lock:
                return visible_stats(maps, program, session=self.session)
        from matloom.render.api import stats_text

        with self.session.lock:
            return stats_text(program, grid=grid)
