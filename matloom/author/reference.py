"""The reference photo of ``matloom generate --reference PHOTO``: loading, hashing, resizing.

The photo is read once, from the path given only: a PNG or JPEG file of at most
:data:`MAX_BYTES` bytes and :data:`MAX_PIXELS` pixels. A symlink is followed only when its
target lies in the symlink's own folder; the file is then opened without following links
(:func:`matloom.io.reading.read_regular_bytes`), so a link swapped in between is refused.
Anything else is a :class:`ReferencePhotoError` with a one-line message.

The photo is centre-cropped to a square (previews are square) and kept at no more than
:data:`KEPT_SIDE` pixels a side; :meth:`ReferencePhoto.at` resizes it to any preview size.
The run record keeps its SHA-256, size and file name (:class:`ReferenceRecord`), never the
pixels: a resumed run reads the photo again and refuses it when its hash changed.
"""

from __future__ import annotations

import hashlib
import io
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from matloom.author.records import ReferenceRecord, RunRecord

#: Largest photo file read, in bytes.
MAX_BYTES = 64 * 1024 * 1024
#: Largest photo decoded, in pixels (width x height; 64 megapixels).
MAX_PIXELS = 64 * 1024 * 1024
#: Smallest photo side, in pixels.
MIN_SIDE = 16
#: The square crop is kept at most this large (every preview size resizes from it).
KEPT_SIDE = 1024
#: File formats read (Pillow's names).
FORMATS = ("PNG", "JPEG")


class ReferencePhotoError(ValueError):
    """The reference photo cannot be used; the message (one line) says why."""


@dataclass(frozen=True)
class ReferencePhoto:
    """A loaded reference photo: its hash and its square crop (uint8 RGB)."""

    name: str
    sha256: str
    width: int
    height: int
    square: np.ndarray
    _sizes: dict[int, np.ndarray] = field(default_factory=dict, repr=False, compare=False)

    def at(self, size: int) -> np.ndarray:
        """The square crop resized to ``size`` x ``size`` (uint8 RGB, read-only)."""
        if size not in self._sizes:
            from PIL import Image

            image = Image.fromarray(self.square)
            if image.width != size:
                image = image.resize((size, size), Image.Resampling.LANCZOS)
            array = np.asarray(image.convert("RGB"), dtype=np.uint8).copy()
            array.setflags(write=False)
            self._sizes[size] = array
        return self._sizes[size]

    def record(self) -> ReferenceRecord:
        """What the run record keeps of the photo (never its pixels)."""
        return ReferenceRecord(
            name=self.name, sha256=self.sha256, width=self.width, height=self.height
        )


def _checked_path(path: str | os.PathLike[str]) -> Path:
    """The file to open: ``path``, or the target of a symlink that stays in its folder."""
    given = Path(path)
    if not given.is_symlink():
        return given
    folder = given.parent.resolve()
    target = given.resolve()
    if target.parent != folder:
        raise ReferencePhotoError(
            f"reference photo {given} is a symlink out of its folder; give the file itself"
        )
    if target.is_symlink():  # resolve() leaves a loop unresolved
        raise ReferencePhotoError(f"reference photo {given} is a symlink loop")
    return target


def _read(path: str | os.PathLike[str]) -> bytes:
    from matloom.io.reading import read_regular_bytes

    if not Path(path).exists() and not Path(path).is_symlink():
        raise ReferencePhotoError(f"reference photo {path} does not exist")
    try:
        return read_regular_bytes(_checked_path(path), MAX_BYTES)
    except OSError as err:
        reason = err.strerror or str(err)
        raise ReferencePhotoError(f"cannot read reference photo {path}: {reason}") from None


def _decode(data: bytes, path: str | os.PathLike[str]) -> np.ndarray:
    """The photo's pixels (uint8 RGB), refused when not a PNG/JPEG or too large."""
    from PIL import Image, ImageOps, UnidentifiedImageError

    try:
        with Image.open(io.BytesIO(data), formats=FORMATS) as image:
            width, height = image.size  # from the header: checked before decoding
            if width * height > MAX_PIXELS:
                raise ReferencePhotoError(
                    f"reference photo {path} is {width} x {height} px, over the "
                    f"{MAX_PIXELS:,}-pixel limit; scale it down"
                )
            if min(width, height) < MIN_SIDE:
                raise ReferencePhotoError(
                    f"reference photo {path} is {width} x {height} px; give at least "
                    f"{MIN_SIDE} px a side"
                )
            upright = ImageOps.exif_transpose(image)  # a phone photo as it was seen
            return np.asarray(upright.convert("RGB"), dtype=np.uint8)
    except ReferencePhotoError:
        raise
    except UnidentifiedImageError:
        raise ReferencePhotoError(f"reference photo {path} is not a PNG or JPEG image") from None
    except (OSError, ValueError, Image.DecompressionBombError) as err:
        reason = " ".join(str(err).split())
        raise ReferencePhotoError(f"cannot decode reference photo {path}: {reason}") from None


def _square(pixels: np.ndarray) -> np.ndarray:
    """The centred square crop, at most :data:`KEPT_SIDE` a side."""
    from PIL import Image

    height, width = pixels.shape[:2]
    side = min(height, width)
    top, left = (height - side) // 2, (width - side) // 2
    crop = Image.fromarray(np.ascontiguousarray(pixels[top : top + side, left : left + side]))
    if side > KEPT_SIDE:
        crop = crop.resize((KEPT_SIDE, KEPT_SIDE), Image.Resampling.LANCZOS)
    square = np.asarray(crop, dtype=np.uint8).copy()
    square.setflags(write=False)
    return square


def load_reference(path: str | os.PathLike[str]) -> ReferencePhoto:
    """Read, check and hash the photo at ``path`` (see the module docstring)."""
    data = _read(path)
    pixels = _decode(data, path)
    height, width = pixels.shape[:2]
    return ReferencePhoto(
        name=Path(path).name,
        sha256=hashlib.sha256(data).hexdigest(),
        width=width,
        height=height,
        square=_square(pixels),
    )


def check_recorded(photo: ReferencePhoto, recorded: ReferenceRecord | None) -> None:
    """Refuse a photo whose hash differs from the one the run started with (on resume)."""
    if recorded is not None and recorded.sha256 != photo.sha256:
        raise ReferencePhotoError(
            f"the reference photo changed since the run started (sha256 {recorded.sha256[:12]}"
            f"... recorded, {photo.sha256[:12]}... now); restore it or start a new run"
        )


def open_reference(record: RunRecord) -> ReferencePhoto | None:
    """The run's reference photo (``settings.reference``), checked against the hash the record
    holds (a resumed run), whose hash the record then holds; None without one."""
    path = record.settings.reference
    if path is None:
        return None
    photo = load_reference(path)
    check_recorded(photo, record.reference)
    record.reference = photo.record()
    return photo
