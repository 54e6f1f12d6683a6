"""The paper's two Blender layouts as data: the flat swatch and the staged studio scene.

Every number comes from the reference implementation (``docs/compatibility.md``, "Blender"):
the tests read this table, the job builder turns it into JSON for the worker, and the worker
(``worker.py``, run inside Blender) only places what the table says. Colours are 8-bit sRGB
triplets as the reference writes them; the worker decodes them to linear values.

Camera placement is computed here (pure Python), not in Blender, so that it can be tested
without Blender: :func:`camera_for_view` gives the location and rotation of every view.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

#: Layout names, in the order ``--layout both`` renders them.
LAYOUT_NAMES = ("flat", "staged")
#: Oldest Blender the worker supports (4.2 LTS); bpy 5.0.x is what ``make blender-venv`` installs.
MIN_BLENDER = (4, 2)

Vec3 = tuple[float, float, float]
RGB8 = tuple[int, int, int]


@dataclass(frozen=True)
class Common:
    """Cycles and output settings shared by both layouts (the reference's ``initialize``)."""

    device_order: tuple[str, ...] = ("OPTIX", "CUDA", "HIP", "METAL", "NONE")
    adaptive_sampling: bool = True
    adaptive_threshold: float = 0.02
    adaptive_min_samples: int = 0
    denoise: bool = True
    denoise_passes: str = "RGB_ALBEDO_NORMAL"
    light_tree: bool = True
    pixel_filter: str = "BLACKMAN_HARRIS"
    filter_width: float = 0.1
    film_exposure: float = 1.0
    spatial_splits: bool = True
    view_transform: str = "AgX"
    working_space: str = "Linear Rec.2020"
    file_format: str = "PNG"
    color_mode: str = "RGBA"
    color_depth: str = "8"
    compression: int = 15
    resolution_percentage: int = 100


@dataclass(frozen=True)
class Camera:
    """A perspective camera framed on a bounding sphere (``fit_ratio`` 0) or tightly on the
    object's extent (``fit_ratio`` 1); ``rotation_deg`` is the Euler XYZ rotation of view 0."""

    lens_mm: float
    sensor_mm: float
    clip_start: float
    rotation_deg: Vec3
    target: Vec3
    radius: float
    fit_ratio: float


@dataclass(frozen=True)
class Light:
    name: str
    location: Vec3
    power_w: float
    size: float
    shadow: bool
    shape: str = "SQUARE"
    spread_deg: float = 180.0


@dataclass(frozen=True)
class Prop:
    """A coloured prop (``kind``: uv_sphere, cube, cone, torus, plane)."""

    name: str
    kind: str
    location: Vec3
    colour: RGB8
    roughness: float
    rotation_deg: Vec3 = (0.0, 0.0, 0.0)
    scale: Vec3 = (1.0, 1.0, 1.0)
    size: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Layout:
    name: str
    samples: int
    #: the material's plane: rotation and centre (a 2x2-unit plane facing +Z before rotation)
    panel_rotation_deg: Vec3
    panel_location: Vec3
    camera: Camera
    #: "hdri" (Blender's bundled studio light) or "colour" (a flat grey world)
    world: str
    world_strength: float
    film_transparent: bool
    resolution: int
    #: ``--views all``: for the flat swatch the plane turns 90 degrees about Z per view and the
    #: image is turned back, which equals turning the world the other way (``world_turn_deg``);
    #: for the staged scene the camera swings by ``view_azimuths_deg`` about the panel.
    view_azimuths_deg: tuple[float, ...] = (0.0,)
    world_turn_deg: tuple[float, ...] = (0.0,)
    world_colour: RGB8 | None = None
    hdri: str | None = None
    lights: tuple[Light, ...] = ()
    props: tuple[Prop, ...] = ()
    shadow: bool = True
    file_stem: str = ""

    @property
    def n_views(self) -> int:
        return max(len(self.view_azimuths_deg), len(self.world_turn_deg))


COMMON = Common()

#: Blender's 50 mm default lens on its 36 mm sensor (the reference leaves both at default).
LENS_MM = 50.0
SENSOR_MM = 36.0

FLAT = Layout(
    name="flat",
    samples=64,
    panel_rotation_deg=(0.0, 0.0, 0.0),
    panel_location=(0.0, 0.0, 0.0),
    camera=Camera(
        lens_mm=LENS_MM,
        sensor_mm=SENSOR_MM,
        clip_start=0.01,
        rotation_deg=(0.0, 0.0, 0.0),
        target=(0.0, 0.0, 0.0),
        radius=math.sqrt(2.0),
        fit_ratio=1.0,
    ),
    world="hdri",
    world_strength=0.5,
    film_transparent=True,
    resolution=512,
    view_azimuths_deg=(0.0, 0.0, 0.0, 0.0),
    world_turn_deg=(0.0, -90.0, -180.0, -270.0),
    # fixed: the reference loads matloom/blender/hdri/city.exr, which it does not ship
    hdri="studiolights/world/city.exr",
    file_stem="flat",
)

_ROOM_GREY: RGB8 = (197, 198, 202)
_CEILING: RGB8 = (221, 222, 226)
_HALF = 5.5
_ROOM_HEIGHT = 4.5

STAGED = Layout(
    name="staged",
    samples=160,
    panel_rotation_deg=(90.0, 0.0, 0.0),
    panel_location=(0.0, 0.0, 1.02),
    camera=Camera(
        lens_mm=LENS_MM,
        sensor_mm=SENSOR_MM,
        clip_start=0.01,
        rotation_deg=(90.0 - 18.0, 0.0, 26.0),
        target=(0.0, 0.0, 1.02),
        radius=math.sqrt(2.0) * 0.9,
        fit_ratio=0.0,
    ),
    world="colour",
    world_strength=1.0,
    world_colour=(210, 211, 214),
    film_transparent=False,
    resolution=512,
    view_azimuths_deg=(0.0, -75.0, -45.0, -15.0, 15.0, 45.0),
    world_turn_deg=(0.0,),
    lights=(
        Light("key", (-3.0, -3.0, 4.0), 900.0, 2.6, True),
        Light("top", (0.0, 0.0, 4.2), 220.0, 3.6, False),
    ),
    props=(
        Prop("floor", "plane", (0.0, 0.0, 0.0), _ROOM_GREY, 0.85, scale=(_HALF, _HALF, 1.0)),
        Prop(
            "ceiling",
            "plane",
            (0.0, 0.0, _ROOM_HEIGHT),
            _CEILING,
            0.85,
            rotation_deg=(180.0, 0.0, 0.0),
            scale=(_HALF, _HALF, 1.0),
        ),
        Prop(
            "wall_back",
            "plane",
            (0.0, _HALF, _ROOM_HEIGHT / 2),
            _ROOM_GREY,
            0.85,
            rotation_deg=(90.0, 0.0, 0.0),
            scale=(_HALF, _ROOM_HEIGHT / 2, 1.0),
        ),
        Prop(
            "wall_front",
            "plane",
            (0.0, -_HALF, _ROOM_HEIGHT / 2),
            _ROOM_GREY,
            0.85,
            rotation_deg=(-90.0, 0.0, 0.0),
            scale=(_HALF, _ROOM_HEIGHT / 2, 1.0),
        ),
        Prop(
            "wall_left",
            "plane",
            (-_HALF, 0.0, _ROOM_HEIGHT / 2),
            _ROOM_GREY,
            0.85,
            rotation_deg=(90.0, 0.0, 90.0),
            scale=(_HALF, _ROOM_HEIGHT / 2, 1.0),
        ),
        Prop(
            "wall_right",
            "plane",
            (_HALF, 0.0, _ROOM_HEIGHT / 2),
            _ROOM_GREY,
            0.85,
            rotation_deg=(90.0, 0.0, -90.0),
            scale=(_HALF, _ROOM_HEIGHT / 2, 1.0),
        ),
        # back props: behind the panel, for context and refraction
        Prop(
            "back_sphere", "uv_sphere", (1.5, 1.2, 0.8), (205, 120, 55), 0.45, size={"radius": 0.8}
        ),
        Prop(
            "back_cube",
            "cube",
            (-1.9, 1.2, 0.65),
            (70, 110, 200),
            0.55,
            rotation_deg=(0.0, 0.0, 30.0),
            size={"size": 1.3},
        ),
        # front props: outside the frustum, seen only in reflections
        Prop(
            "front_sphere", "uv_sphere", (-1.9, -2.6, 0.7), (210, 70, 60), 0.4, size={"radius": 0.7}
        ),
        Prop(
            "front_cone",
            "cone",
            (-0.2, -3.7, 0.75),
            (80, 175, 95),
            0.4,
            size={"radius": 0.8, "depth": 1.5, "vertices": 3},
        ),
        Prop(
            "front_torus",
            "torus",
            (-2.8, -2.0, 0.9),
            (235, 195, 60),
            0.4,
            rotation_deg=(80.0, 0.0, 20.0),
            size={"major_radius": 0.7, "minor_radius": 0.24},
        ),
    ),
    file_stem="staged",
)

LAYOUTS: dict[str, Layout] = {"flat": FLAT, "staged": STAGED}


def field_of_view(camera: Camera) -> float:
    """Full field of view in radians of a square frame (sensor fit AUTO)."""
    return 2.0 * math.atan(camera.sensor_mm / 2.0 / camera.lens_mm)


def camera_distance(camera: Camera, half_extent: float) -> float:
    """Distance from the target: ``radius / sin(fov/2)`` for a bounding-sphere fit
    (``fit_ratio`` 0), ``half_extent / tan(fov/2)`` for a tight fit of a head-on plane
    (``fit_ratio`` 1), and linear in between."""
    half = field_of_view(camera) / 2.0
    sphere = camera.radius / math.sin(half)
    tight = half_extent / math.tan(half)
    return (1.0 - camera.fit_ratio) * sphere + camera.fit_ratio * tight


def camera_for_view(layout: Layout, view: int, half_extent: float = 1.0) -> dict[str, Any]:
    """Location, Euler rotation (degrees) and lens of ``layout``'s camera for view ``view``.

    The camera looks along its local -Z; its position is the target plus the distance along the
    rotated +Z axis (Blender's XYZ Euler order: R = Rz @ Ry @ Rx).
    """
    cam = layout.camera
    rx, ry, rz = cam.rotation_deg
    rz += layout.view_azimuths_deg[view % len(layout.view_azimuths_deg)]
    distance = camera_distance(cam, half_extent)
    ax, ay, az = (math.radians(a) for a in (rx, ry, rz))
    # rotated +Z axis of R = Rz(az) Ry(ay) Rx(ax)
    zx = math.cos(az) * math.sin(ay) * math.cos(ax) + math.sin(az) * math.sin(ax)
    zy = math.sin(az) * math.sin(ay) * math.cos(ax) - math.cos(az) * math.sin(ax)
    zz = math.cos(ay) * math.cos(ax)
    tx, ty, tz = cam.target
    return {
        "location": [tx + distance * zx, ty + distance * zy, tz + distance * zz],
        "rotation_deg": [rx, ry, rz],
        "lens_mm": cam.lens_mm,
        "sensor_mm": cam.sensor_mm,
        "clip_start": cam.clip_start,
        "distance": distance,
    }


def layout_json(layout: Layout) -> dict[str, Any]:
    """The layout as plain JSON data (for the worker's job)."""
    return asdict(layout)


def srgb8_to_linear(colour: RGB8) -> tuple[float, float, float]:
    """Decode an 8-bit sRGB triplet to linear values (what the worker gives Blender)."""

    def one(c: int) -> float:
        v = c / 255.0
        return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4

    r, g, b = colour
    return (one(r), one(g), one(b))
