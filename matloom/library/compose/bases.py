"""The composer's bases: one physical class of material each (its colours, finish, structure and
sizes). :data:`BASES` is read through :mod:`matloom.library.compose.tables`; the structure
builders are in :mod:`matloom.library.compose.structures`, keyed by ``BaseSpec.structure``.

To add a base: a :class:`BaseSpec` here (a new structure, or an existing one's key) and, for a
new structure, its builder in ``structures.py`` / ``structures_soft.py``; the grid test then
composes it with every layout and motif.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

from matloom.library.colour import RGB


@dataclass(frozen=True)
class BaseSpec:
    """A base material class.

    ``colours``: the default base, secondary (the structure's second colour: grain, bands,
    grains) and accent (speckles, veins, chips) colours; ``accent_share``: the share of the
    surface in the accent colour (0: the structure shows none). Sizes in metres: ``feature_m``
    the structure's main feature, ``relief_m`` its height amplitude, ``cell_m`` one tile, plank
    or cell of a layout made of it, ``plain_m`` the View of the plain material. ``words``: the
    request words that name this class (the parts reader reads them)."""

    name: str
    category: str
    noun: str
    words: tuple[str, ...]
    colours: tuple[RGB, RGB, RGB]
    roughness: float
    structure: str
    feature_m: float
    relief_m: float
    cell_m: float
    plain_m: float
    metallic: float = 0.0
    coat: float = 0.0
    transmission: float = 0.0
    ior: float = 1.5
    sheen: float = 0.0
    subsurface: float = 0.0
    anisotropy: float = 0.0
    accent_share: float = 0.0
    #: the structure has a grain direction (it turns with upright planks)
    directional: bool = False
    #: printed motifs lie flat (fabric, paper); others are inlaid or glazed slightly raised
    flat_motif: bool = False


def _b(name: str, category: str, noun: str, words: str, colours: tuple[RGB, RGB, RGB],
       rough: float, structure: str, sizes: tuple[float, float, float, float],
       **extra: float | bool) -> BaseSpec:  # fmt: skip
    feature, relief, cell, plain = sizes
    return BaseSpec(name, category, noun, tuple(words.split()), colours, rough, structure,
                    feature, relief, cell, plain, **extra)  # type: ignore[arg-type]  # fmt: skip


_ALL = (
    # name, category, noun, words, (base, secondary, accent), roughness, structure,
    # (feature_m, relief_m, cell_m, plain_m), extras
    _b(
        "ceramic",
        "ceramic",
        "glazed ceramic",
        "ceramic ceramics glazed stoneware earthenware faience majolica pottery",
        ((236, 230, 218), (214, 204, 188), (128, 108, 88)),
        0.12,
        "glaze",
        (0.05, 0.0003, 0.2, 0.6),
        coat=0.7,
        accent_share=0.015,
    ),
    _b(
        "porcelain",
        "ceramic",
        "porcelain",
        "porcelain china bone-china vitreous",
        ((246, 246, 243), (230, 232, 233), (206, 208, 212)),
        0.06,
        "glaze",
        (0.08, 0.0002, 0.3, 0.6),
        coat=0.9,
    ),
    _b(
        "stone",
        "stone",
        "natural stone",
        "stone rock limestone travertine flagstone",
        ((152, 146, 136), (120, 114, 106), (188, 182, 170)),
        0.75,
        "stone",
        (0.15, 0.0025, 0.4, 1.0),
        accent_share=0.08,
    ),
    _b(
        "marble",
        "stone",
        "marble",
        "marble marbled",
        ((236, 234, 230), (216, 214, 210), (118, 116, 122)),
        0.12,
        "marble",
        (0.25, 0.0002, 0.6, 1.2),
        coat=0.4,
        accent_share=0.1,
    ),
    _b(
        "granite",
        "stone",
        "granite",
        "granite granitic",
        ((172, 166, 160), (112, 106, 102), (38, 36, 36)),
        0.2,
        "granite",
        (0.005, 0.0002, 0.6, 0.6),
        coat=0.3,
        accent_share=0.25,
    ),
    _b(
        "slate",
        "stone",
        "slate",
        "slate shale schist",
        ((72, 78, 84), (56, 60, 66), (104, 108, 112)),
        0.7,
        "slate",
        (0.1, 0.003, 0.4, 0.8),
    ),
    _b(
        "sandstone",
        "stone",
        "sandstone",
        "sandstone sandstones",
        ((202, 172, 128), (176, 140, 96), (224, 204, 166)),
        0.85,
        "strata",
        (0.04, 0.002, 0.4, 1.0),
        accent_share=0.06,
    ),
    _b(
        "concrete",
        "concrete",
        "concrete",
        "concrete cement screed",
        ((160, 158, 152), (134, 132, 128), (88, 88, 86)),
        0.85,
        "concrete",
        (0.3, 0.0015, 0.6, 1.5),
        accent_share=0.05,
    ),
    _b(
        "terrazzo",
        "concrete",
        "terrazzo",
        "terrazzo",
        ((226, 222, 214), (158, 148, 138), (72, 82, 92)),
        0.15,
        "terrazzo",
        (0.012, 0.0002, 0.5, 0.8),
        coat=0.4,
        accent_share=0.2,
    ),
    _b(
        "wood",
        "wood",
        "wood",
        "wood wooden timber hardwood plank planks lumber",
        ((172, 122, 76), (122, 80, 46), (92, 62, 36)),
        0.5,
        "wood",
        (0.008, 0.0006, 0.9, 1.0),
        directional=True,
    ),
    _b(
        "bamboo",
        "wood",
        "bamboo",
        "bamboo",
        ((208, 180, 122), (172, 140, 86), (128, 98, 58)),
        0.4,
        "bamboo",
        (0.002, 0.0004, 0.6, 0.6),
        coat=0.3,
        directional=True,
        accent_share=0.05,
    ),
    _b(
        "cork",
        "wood",
        "cork",
        "cork",
        ((178, 134, 90), (132, 94, 60), (92, 62, 38)),
        0.9,
        "cork",
        (0.004, 0.0008, 0.3, 0.3),
        accent_share=0.1,
    ),
    _b(
        "metal",
        "metal",
        "metal",
        "metal metallic steel iron aluminium aluminum chrome",
        ((192, 194, 198), (162, 164, 168), (120, 122, 126)),
        0.3,
        "metal",
        (0.1, 0.0001, 0.3, 0.5),
        metallic=1.0,
    ),
    _b(
        "brushed_metal",
        "metal",
        "brushed metal",
        "brushed satin-finish",
        ((198, 200, 204), (172, 174, 178), (140, 142, 146)),
        0.35,
        "brushed",
        (0.0005, 0.00005, 0.3, 0.4),
        metallic=1.0,
        anisotropy=0.8,
        directional=True,
    ),
    _b(
        "rust",
        "metal",
        "rusted metal",
        "rust rusty rusted corroded oxidised oxidized",
        ((142, 72, 38), (96, 46, 26), (182, 106, 52)),
        0.85,
        "rust",
        (0.08, 0.0012, 0.4, 0.8),
        metallic=0.2,
        accent_share=0.15,
    ),
    _b(
        "leather",
        "leather",
        "leather",
        "leather hide suede nubuck",
        ((122, 74, 44), (92, 52, 30), (150, 100, 64)),
        0.55,
        "leather",
        (0.003, 0.0005, 0.15, 0.3),
        sheen=0.1,
        flat_motif=True,
    ),
    _b(
        "rubber",
        "plastic",
        "rubber",
        "rubber rubbery latex neoprene",
        ((42, 42, 44), (32, 32, 34), (78, 78, 80)),
        0.8,
        "rubber",
        (0.02, 0.0002, 0.3, 0.5),
        accent_share=0.03,
    ),
    _b(
        "plastic",
        "plastic",
        "plastic",
        "plastic polymer acrylic vinyl pvc laminate",
        ((226, 226, 222), (212, 212, 208), (150, 150, 150)),
        0.35,
        "glaze",
        (0.1, 0.0001, 0.2, 0.4),
    ),
    _b(
        "foam",
        "plastic",
        "foam",
        "foam sponge spongy porous",
        ((204, 198, 186), (150, 144, 132), (120, 114, 104)),
        0.95,
        "foam",
        (0.003, 0.0015, 0.2, 0.3),
    ),
    _b(
        "glass",
        "glass",
        "glass",
        "glass glassy",
        ((204, 222, 226), (172, 198, 204), (236, 244, 246)),
        0.04,
        "glass",
        (0.2, 0.0002, 0.2, 0.5),
        transmission=0.85,
        accent_share=0.01,
    ),
    _b(
        "resin",
        "glass",
        "resin",
        "resin epoxy",
        ((212, 172, 92), (172, 122, 52), (240, 230, 200)),
        0.06,
        "glass",
        (0.15, 0.0002, 0.3, 0.4),
        coat=0.8,
        transmission=0.5,
        accent_share=0.02,
    ),
    _b(
        "crystal",
        "glass",
        "crystal",
        "crystal crystals crystalline quartz gem gemstone",
        ((204, 194, 232), (150, 132, 202), (242, 238, 252)),
        0.05,
        "crystal",
        (0.03, 0.003, 0.2, 0.2),
        transmission=0.4,
        ior=1.55,
        accent_share=0.1,
    ),
    _b(
        "mineral",
        "stone",
        "banded mineral",
        "mineral minerals agate banded",
        ((152, 122, 102), (102, 82, 72), (202, 192, 182)),
        0.15,
        "banded",
        (0.008, 0.0001, 0.3, 0.3),
        coat=0.5,
        accent_share=0.05,
    ),
    _b(
        "soil",
        "ground",
        "soil",
        "soil earth dirt loam humus",
        ((102, 76, 54), (72, 52, 36), (142, 122, 102)),
        0.95,
        "soil",
        (0.05, 0.004, 0.5, 1.0),
        accent_share=0.06,
    ),
    _b(
        "sand",
        "ground",
        "sand",
        "sand sandy dune",
        ((214, 190, 148), (190, 164, 120), (150, 130, 100)),
        0.95,
        "sand",
        (0.001, 0.002, 0.5, 1.0),
        accent_share=0.05,
    ),
    _b(
        "gravel",
        "ground",
        "gravel",
        "gravel pebbles shingle grit",
        ((152, 146, 138), (110, 104, 98), (182, 172, 160)),
        0.85,
        "gravel",
        (0.025, 0.01, 0.5, 1.0),
        accent_share=0.2,
    ),
    _b(
        "grass",
        "ground",
        "grass",
        "grass lawn turf meadow",
        ((82, 132, 50), (50, 90, 30), (150, 160, 78)),
        0.8,
        "grass",
        (0.004, 0.01, 0.5, 1.0),
        sheen=0.2,
        accent_share=0.1,
    ),
    _b(
        "moss",
        "organic",
        "moss",
        "moss mossy lichen",
        ((92, 122, 42), (60, 86, 28), (142, 152, 62)),
        0.9,
        "moss",
        (0.006, 0.006, 0.3, 0.5),
        accent_share=0.08,
    ),
    _b(
        "bark",
        "organic",
        "bark",
        "bark",
        ((102, 82, 64), (62, 48, 36), (150, 142, 122)),
        0.9,
        "bark",
        (0.03, 0.012, 0.5, 0.8),
        accent_share=0.06,
    ),
    _b(
        "fabric",
        "fabric",
        "woven fabric",
        "fabric cloth textile woven linen cotton canvas",
        ((182, 172, 152), (150, 140, 120), (120, 110, 96)),
        0.85,
        "weave",
        (0.0012, 0.0004, 0.1, 0.2),
        sheen=0.4,
        flat_motif=True,
    ),
    _b(
        "knit",
        "fabric",
        "knit",
        "knit knitted knitwear jersey wool woollen",
        ((222, 212, 192), (190, 180, 160), (160, 150, 130)),
        0.9,
        "knit",
        (0.006, 0.001, 0.1, 0.2),
        sheen=0.3,
        flat_motif=True,
    ),
    _b(
        "felt",
        "fabric",
        "felt",
        "felt felted fleece",
        ((122, 122, 128), (100, 100, 106), (150, 150, 156)),
        0.95,
        "felt",
        (0.002, 0.0004, 0.1, 0.3),
        sheen=0.2,
        flat_motif=True,
    ),
    _b(
        "paper",
        "paper",
        "paper",
        "paper cardboard card parchment",
        ((240, 236, 226), (224, 218, 204), (196, 186, 170)),
        0.9,
        "paper",
        (0.002, 0.0001, 0.1, 0.3),
        accent_share=0.03,
        flat_motif=True,
    ),
    _b(
        "plaster",
        "concrete",
        "plaster",
        "plaster stucco render",
        ((228, 224, 214), (206, 200, 190), (180, 174, 164)),
        0.9,
        "plaster",
        (0.12, 0.0015, 0.5, 1.0),
    ),
    _b(
        "asphalt",
        "concrete",
        "asphalt",
        "asphalt tarmac bitumen blacktop",
        ((60, 60, 62), (42, 42, 44), (124, 120, 116)),
        0.9,
        "asphalt",
        (0.008, 0.002, 0.5, 1.0),
        accent_share=0.15,
    ),
    _b(
        "ice",
        "glass",
        "ice",
        "ice icy frozen",
        ((212, 230, 240), (182, 210, 228), (242, 248, 252)),
        0.08,
        "ice",
        (0.1, 0.001, 0.4, 0.8),
        transmission=0.6,
        ior=1.31,
        accent_share=0.05,
    ),
)

#: base name -> spec (read-only)
BASES: MappingProxyType[str, BaseSpec] = MappingProxyType({b.name: b for b in _ALL})
