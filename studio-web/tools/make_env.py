"""Generate the studio's bundled HDR environments (numpy only; nothing is downloaded).

Writes Radiance RGBE files (run-length encoded, 1024x512 equirectangular, row 0 = up) into
``matloom/studio/static/env/``: ``studio.hdr`` (a dark room with softboxes), ``sky.hdr`` (a
sunny sky over a plain ground) and ``interior.hdr`` (a warm room with a window and lamps).

Directions follow three.js's equirectangular mapping: column u (0..1) is the azimuth
``phi = (u - 0.5) * 2 pi`` with ``dir = (cos(el) cos(phi), sin(el), cos(el) sin(phi))`` and the
default camera on +z (azimuth 90 degrees). The output is deterministic (no random numbers) and
kept smooth along each row so that run-length encoding keeps every file small.

Usage: ``python studio-web/tools/make_env.py [OUT_DIR]``
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np

WIDTH, HEIGHT = 1024, 512
OUT = Path(__file__).resolve().parents[2] / "matloom" / "studio" / "static" / "env"

Grid = tuple[np.ndarray, np.ndarray]  # (azimuth degrees 0..360, elevation degrees -90..90)


def grid() -> Grid:
    u = (np.arange(WIDTH) + 0.5) / WIDTH
    v = (np.arange(HEIGHT) + 0.5) / HEIGHT
    az = np.degrees((u - 0.5) * 2 * np.pi) % 360.0
    el = 90.0 - v * 180.0
    return np.meshgrid(az, el)


def smoothstep(e0: float, e1: float, x: np.ndarray) -> np.ndarray:
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def az_delta(az: np.ndarray, centre: float) -> np.ndarray:
    """Signed azimuth difference in degrees, wrapped to -180..180."""
    return (az - centre + 180.0) % 360.0 - 180.0


def box(g: Grid, az0: float, el0: float, w: float, h: float, soft: float = 1.5) -> np.ndarray:
    """A soft-edged rectangle in (azimuth, elevation) degrees: 1 inside, 0 outside."""
    az, el = g
    dx = np.abs(az_delta(az, az0)) * np.cos(np.radians(el0))
    dy = np.abs(el - el0)
    return smoothstep(w / 2 + soft, w / 2, dx) * smoothstep(h / 2 + soft, h / 2, dy)


def disc(g: Grid, az0: float, el0: float, radius: float, soft: float) -> np.ndarray:
    """A soft disc of angular radius ``radius`` degrees around (az0, el0)."""
    angle = angular_distance(g, az0, el0)
    return smoothstep(radius + soft, radius, angle)


def angular_distance(g: Grid, az0: float, el0: float) -> np.ndarray:
    az, el = (np.radians(a) for a in g)
    a0, e0 = np.radians(az0), np.radians(el0)
    cos_d = np.sin(el) * np.sin(e0) + np.cos(el) * np.cos(e0) * np.cos(az - a0)
    return np.degrees(np.arccos(np.clip(cos_d, -1.0, 1.0)))


def rgb(*c: float) -> np.ndarray:
    return np.array(c, dtype=np.float64)


def add(img: np.ndarray, mask: np.ndarray, colour: np.ndarray) -> None:
    img += mask[..., None] * colour


def studio() -> np.ndarray:
    """A dark grey photo studio: a big back softbox, a key box, a fill, a top strip."""
    g = grid()
    _, el = g
    wall = 0.06 + 0.05 * smoothstep(-10.0, 60.0, el)
    floor = 0.035 + 0.02 * smoothstep(-90.0, -5.0, el)
    base = np.where(el < 0, floor, wall)
    img = base[..., None] * rgb(1.0, 1.0, 1.0)
    add(img, box(g, 270.0, 30.0, 40.0, 16.0, 2.0), rgb(9.0, 9.0, 8.6))  # behind the object
    add(img, box(g, 140.0, 40.0, 34.0, 44.0, 3.0), rgb(14.0, 13.2, 12.0))  # key, upper left
    add(img, box(g, 25.0, 18.0, 26.0, 46.0, 4.0), rgb(2.6, 2.8, 3.0))  # fill, right
    add(img, box(g, 200.0, 70.0, 120.0, 8.0, 2.0), rgb(5.0, 5.0, 5.0))  # overhead strip
    add(img, smoothstep(70.0, 88.0, el), rgb(0.6, 0.6, 0.6))  # ceiling bounce
    return img


def sky() -> np.ndarray:
    """A clear afternoon sky with a sun, over a warm grey ground with a hazy horizon."""
    g = grid()
    _, el = g
    t = smoothstep(0.0, 70.0, el)
    zenith, horizon = rgb(0.18, 0.36, 0.85), rgb(0.85, 0.92, 1.0)
    sky_part = (1 - t)[..., None] * horizon + t[..., None] * zenith
    ground = rgb(0.22, 0.19, 0.15) * 0.9
    haze = smoothstep(-6.0, 0.0, el)[..., None]
    img = np.where((el >= 0)[..., None], sky_part * 1.6, (1 - haze) * ground + haze * horizon)
    sun_az, sun_el = 150.0, 42.0
    glow = smoothstep(35.0, 0.0, angular_distance(g, sun_az, sun_el)) ** 3
    add(img, glow * (el > -2), rgb(1.6, 1.4, 1.0))
    add(img, disc(g, sun_az, sun_el, 1.6, 0.8), rgb(900.0, 820.0, 700.0))
    return img


def interior() -> np.ndarray:
    """A warm room: beige walls, a dark wooden floor, a daylight window and two lamps."""
    g = grid()
    _, el = g
    wall = rgb(0.42, 0.30, 0.19) * (0.35 + 0.25 * smoothstep(-5.0, 60.0, el))[..., None]
    floor = rgb(0.20, 0.11, 0.055) * (0.5 + 0.3 * smoothstep(-90.0, 0.0, el))[..., None]
    ceiling = rgb(0.55, 0.45, 0.34) * 0.45
    img = np.where((el < 0)[..., None], floor, wall)
    img = np.where((el > 72)[..., None], ceiling, img)
    window = box(g, 250.0, 22.0, 56.0, 40.0, 1.0)
    bars = np.maximum(box(g, 250.0, 22.0, 2.0, 40.0, 0.5), box(g, 250.0, 22.0, 56.0, 2.0, 0.5))
    window = window * (1.0 - bars)
    daylight = rgb(3.4, 3.7, 4.2) * (1.0 + 0.6 * smoothstep(2.0, 42.0, el))[..., None]
    img = img * (1.0 - window[..., None]) + window[..., None] * daylight
    add(img, smoothstep(12.0, 0.0, np.abs(az_delta(g[0], 250.0))) * (el < 0) * 0.15, rgb(1, 1, 1))
    add(img, disc(g, 120.0, 55.0, 4.0, 3.0), rgb(40.0, 24.0, 9.0))  # pendant lamp
    add(img, disc(g, 20.0, 12.0, 3.0, 4.0), rgb(18.0, 10.0, 3.5))  # table lamp
    return img


ENVIRONMENTS: dict[str, Callable[[], np.ndarray]] = {
    "studio": studio,
    "sky": sky,
    "interior": interior,
}


def to_rgbe(img: np.ndarray) -> np.ndarray:
    """float RGB (H, W, 3) -> uint8 RGBE (H, W, 4)."""
    img = np.maximum(img, 0.0)
    v = img.max(axis=-1)
    mant, expo = np.frexp(v)
    scale = np.where(v > 1e-32, mant * 256.0 / np.maximum(v, 1e-32), 0.0)
    out = np.zeros(img.shape[:2] + (4,), np.uint8)
    out[..., :3] = np.clip(np.floor(img * scale[..., None]), 0, 255).astype(np.uint8)
    out[..., 3] = np.where(v > 1e-32, expo + 128, 0).astype(np.uint8)
    return out


def rle_row(values: np.ndarray) -> bytes:
    """Radiance's run-length encoding of one component of one scanline."""
    out = bytearray()
    data = values.tobytes()
    n, i = len(data), 0
    while i < n:
        run = 1
        while i + run < n and run < 127 and data[i + run] == data[i]:
            run += 1
        if run >= 4:
            out += bytes((128 + run, data[i]))
            i += run
            continue
        j = i  # a literal stretch until the next run of 4 or 128 bytes
        while j < n and j - i < 128:
            if j + 3 < n and data[j] == data[j + 1] == data[j + 2] == data[j + 3]:
                break
            j += 1
        out += bytes((j - i,)) + data[i:j]
        i = j
    return bytes(out)


def encode_hdr(img: np.ndarray) -> bytes:
    h, w, _ = img.shape
    rgbe = to_rgbe(img)
    head = "#?RADIANCE\n# MatLoom studio environment (studio-web/tools/make_env.py)\n"
    head += f"FORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n"
    body = bytearray(head.encode("ascii"))
    for row in rgbe:
        body += bytes((2, 2, w >> 8, w & 255))
        for c in range(4):
            body += rle_row(row[:, c])
    return bytes(body)


def main(argv: list[str]) -> int:
    out = Path(argv[0]) if argv else OUT
    out.mkdir(parents=True, exist_ok=True)
    for name, make in ENVIRONMENTS.items():
        data = encode_hdr(make())
        (out / f"{name}.hdr").write_bytes(data)
        print(f"{out / (name + '.hdr')}: {len(data) // 1024} KB")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
