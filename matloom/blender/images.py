"""Check and adopt the images Blender wrote.

Blender is a separate program: what it leaves under an output name may be missing, truncated or
not a PNG at all (a crashed or foreign "blender"). Every render is read back, checked
(a PNG of the requested size) and re-encoded by MatLoom's own PNG writer, so that it carries
MatLoom's ``Software`` text chunk like every other PNG MatLoom writes (that is how a later run
knows a single ``-o out.png`` is its own) and is replaced atomically.
"""

from __future__ import annotations

from pathlib import Path

from matloom.blender.runner import BlenderError

#: zlib level for the re-encoded renders: they are final images, kept small (level 9 is ~30 %
#: smaller than MatLoom's fast level 1 on Cycles renders, and costs milliseconds at 512 px).
RENDER_COMPRESS_LEVEL = 9


def adopt_render(path: Path, size: int) -> bytes:
    """The PNG bytes of Blender's render at ``path``, re-encoded by MatLoom, written back
    atomically; :class:`BlenderError` (one line) when the file is missing or not a
    ``size`` x ``size`` RGBA PNG."""
    from matloom.io.atomic import atomic_write_bytes
    from matloom.io.png import encode_png8, read_png

    if not path.is_file():
        raise BlenderError(f"Blender finished but wrote no image {path.name}")
    try:
        pixels = read_png(path)
    except Exception as err:  # pypng raises its own errors for every kind of bad file
        raise BlenderError(
            f"Blender wrote an unreadable image {path.name} ({type(err).__name__}: "
            f"{str(err).splitlines()[0] if str(err) else 'bad PNG'})"
        ) from None
    shape = tuple(pixels.shape)
    if pixels.dtype.itemsize != 1 or shape[:2] != (size, size) or pixels.ndim != 3:
        raise BlenderError(
            f"Blender wrote {path.name} as a {'x'.join(map(str, shape))} "
            f"{pixels.dtype} image, not the requested {size}x{size} 8-bit RGBA"
        )
    if shape[2] == 3:  # an RGB PNG from another Blender setup: opaque
        import numpy as np

        pixels = np.concatenate([pixels, np.full((size, size, 1), 255, np.uint8)], axis=2)
    elif shape[2] != 4:
        raise BlenderError(f"Blender wrote {path.name} with {shape[2]} channels, not RGBA")
    data = encode_png8(pixels, RENDER_COMPRESS_LEVEL)
    atomic_write_bytes(path, data)
    return data
