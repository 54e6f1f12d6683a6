"""The 8-bit PNG encoder (numpy + zlib): valid files that Pillow and pypng decode exactly."""

from __future__ import annotations

import io
import zlib

import numpy as np
import pytest
from PIL import Image

from matloom.io import png


@pytest.mark.parametrize(
    "shape", [(1, 1), (1, 9, 3), (5, 7), (64, 33, 3), (17, 256, 4), (300, 2, 4), (3, 1000)]
)
def test_encoded_png_decodes_to_the_same_pixels(shape: tuple[int, ...], tmp_path) -> None:
    rng = np.random.default_rng(sum(shape))
    pixels = rng.integers(0, 256, size=shape, dtype=np.uint8)
    data = png.encode_png8(pixels)
    with Image.open(io.BytesIO(data)) as image:
        image.load()  # Pillow verifies the chunk CRCs and the zlib stream
        assert image.mode == {2: "L", 3: {3: "RGB", 4: "RGBA"}.get(shape[-1])}[len(shape)]
        assert np.array_equal(np.asarray(image), pixels)
    path = tmp_path / "x.png"
    path.write_bytes(data)
    assert np.array_equal(png.read_png(path), pixels)


def test_smooth_maps_compress_well_with_the_up_filter() -> None:
    ramp = np.tile(np.linspace(0, 255, 512).astype(np.uint8), (512, 1))
    data = png.encode_png8(ramp)
    assert len(data) < len(zlib.compress(ramp.tobytes(), 1))


@pytest.mark.parametrize(
    "bad", [np.zeros((4, 4), np.float32), np.zeros((4, 4, 2), np.uint8), np.zeros((0, 3), np.uint8)]
)
def test_encoder_rejects_what_png_cannot_hold(bad: np.ndarray) -> None:
    with pytest.raises((TypeError, ValueError)):
        png.encode_png8(bad)
