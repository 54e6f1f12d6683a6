"""Contact sheets of preview images and atomic PNG writing (Pillow).

A contact sheet lays images out on a grid of ``cell`` x ``cell`` squares, ``columns`` per row,
each with its label written underneath in Pillow's built-in bitmap font, so that a seed sweep or
a refinement trajectory can be inspected in one picture.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from matloom.io.png import save_png  # noqa: F401  (re-exported: sheets are saved with it)

#: Sheet background and label colours (RGB).
BACKGROUND: tuple[int, int, int] = (24, 24, 24)
LABEL_COLOUR: tuple[int, int, int] = (235, 235, 235)

#: Space around each label, in pixels.
_LABEL_PADDING = 3
_ELLIPSIS = "..."

#: Permissions of written PNGs (owner read/write, everyone read).


@lru_cache(maxsize=1)
def _bitmap_font() -> ImageFont.ImageFont:
    """Pillow's built-in bitmap font (no FreeType, no font files)."""
    return ImageFont.load_default_imagefont()


def _label_height() -> int:
    """Height of the label strip under each cell: one line of the bitmap font plus padding."""
    bottom = _bitmap_font().getbbox("Agjy|")[3]
    return int(bottom) + 2 * _LABEL_PADDING


def _to_rgb_image(img: np.ndarray) -> Image.Image:
    """uint8 (H, W), (H, W, 3) or (H, W, 4) array -> RGB Pillow image."""
    array = np.asarray(img)
    if array.dtype != np.uint8:
        raise ValueError(f"images must be uint8, got {array.dtype}")
    if array.ndim == 2:
        return Image.fromarray(np.ascontiguousarray(array)).convert("RGB")
    if array.ndim == 3 and array.shape[2] in (3, 4):
        return Image.fromarray(np.ascontiguousarray(array)).convert("RGB")
    raise ValueError(f"images must be (H, W), (H, W, 3) or (H, W, 4), got {array.shape}")


def _fit_to_cell(image: Image.Image, cell: int) -> Image.Image:
    """Scale to fit a cell x cell square, keeping the aspect ratio.

    Enlarging uses nearest neighbour so individual texels stay visible; shrinking uses Lanczos.
    """
    width, height = image.size
    scale = cell / max(width, height)
    size = (max(1, round(width * scale)), max(1, round(height * scale)))
    if size == image.size:
        return image
    method = Image.Resampling.NEAREST if scale > 1 else Image.Resampling.LANCZOS
    return image.resize(size, method)


def _fit_label(text: str, width: int) -> str:
    """``text`` on one line, shortened with "..." so that it fits ``width`` pixels."""
    font = _bitmap_font()
    text = " ".join(text.split())
    if font.getlength(text) <= width:
        return text
    while text and font.getlength(text + _ELLIPSIS) > width:
        text = text[:-1]
    return text + _ELLIPSIS if text else ""


def contact_sheet(
    images: Sequence[np.ndarray],
    labels: Sequence[str],
    columns: int = 5,
    cell: int = 256,
) -> np.ndarray:
    """Grid of ``images`` with ``labels`` underneath; uint8 RGB array.

    The sheet is min(n, columns) cells wide and ceil(n / columns) rows high; each row is
    ``cell`` pixels of image plus a label strip. Images are centred in their cell and scaled to
    fit it; labels are shortened with "..." when they are wider than the cell.
    """
    if len(images) != len(labels):
        raise ValueError(f"{len(images)} images but {len(labels)} labels")
    if not images:
        raise ValueError("contact_sheet needs at least one image")
    if columns < 1 or cell < 1:
        raise ValueError(f"columns and cell must be >= 1, got {columns} and {cell}")

    n_cols = min(len(images), columns)
    n_rows = math.ceil(len(images) / columns)
    row_height = cell + _label_height()
    sheet = Image.new("RGB", (n_cols * cell, n_rows * row_height), BACKGROUND)
    draw = ImageDraw.Draw(sheet)
    font = _bitmap_font()
    for index, (img, label) in enumerate(zip(images, labels, strict=True)):
        left = (index % columns) * cell
        top = (index // columns) * row_height
        tile = _fit_to_cell(_to_rgb_image(img), cell)
        sheet.paste(tile, (left + (cell - tile.width) // 2, top + (cell - tile.height) // 2))
        text = _fit_label(label, cell - 2 * _LABEL_PADDING)
        text_left = left + (cell - int(font.getlength(text))) // 2
        draw.text((text_left, top + cell + _LABEL_PADDING), text, fill=LABEL_COLOUR, font=font)
    return np.asarray(sheet, dtype=np.uint8)
