"""Condition modifiers (rusty, mossy, cracked, wet, worn ...) as overlay layers.

Each condition adds its own named Defines and one layer on top of the recipe's stack. Coverage
comes from thresholded noise, so the substrate shows through (the "substrate-matrix-first"
idiom). Overlays leave height alone or keep it low: height is a max over covered layers, so a
low overlay never flattens the relief below it. The template slots are those of ``template``;
``_base`` is the recipe's main colour and ``_cond`` the condition's colour (the prompt's, as in
"rust stains", or the condition's default). ``{cut}`` is the noise level above which the
overlay appears: a larger amount lowers it and covers more of the surface.
"""

from __future__ import annotations

from dataclasses import dataclass

from matloom.author.builtin.colours import RGB


@dataclass(frozen=True)
class Overlay:
    """The Define lines and the layer text of one condition, plus its default colour."""

    kind: str
    summary: str
    defines: str
    layer: str
    colour: RGB


_RAMP = "Threshold((({n} - {{cut}}) * {k}), below_at=0, above_at=1)"


def _ramp(noise: str, k: float) -> str:
    return _RAMP.format(n=noise, k=k)


OVERLAYS: dict[str, Overlay] = {
    "rusty": Overlay(
        "rusty",
        "orange-brown rust blooms with fine pitting",
        "Define(rustBlob, fBm(octaves=5, base_freq={mf:5}, to_01=True, seed={seed:rustBlob}))\n"
        "Define(rustPit, fBm(octaves=4, base_freq={mf:48}, to_01=True, seed={seed:rustPit}))\n"
        f"Define(rust, {_ramp('(rustBlob + (rustPit * 0.25))', 9)})",
        "Layer(rust)\n.basecolor({mix:_cond~-0.45,_cond,rustPit})\n.roughness(0.92)\n"
        ".height((rust * {hv:0.004}))",
        (150, 72, 34),
    ),
    "mossy": Overlay(
        "mossy",
        "green moss cushions in clumps",
        "Define(mossBlob, fBm(octaves=5, base_freq={mf:4}, to_01=True, seed={seed:mossBlob}))\n"
        "Define(mossTuft, fBm(octaves=4, base_freq={mf:70}, to_01=True, seed={seed:mossTuft}))\n"
        f"Define(moss, {_ramp('(mossBlob + (mossTuft * 0.2))', 7)})",
        "Layer(moss)\n.basecolor({mix:_cond~-0.5,_cond,mossTuft})\n.roughness(0.95)\n"
        ".sheen(0.4)\n.height((moss * (0.2 + mossTuft) * {hv:0.03}))",
        (88, 118, 40),
    ),
    "cracked": Overlay(
        "cracked",
        "thin dark crack network",
        'Define(crackCell, Worley(combination="F2-F1", base_freq={mf:4}, to_01=True, '
        "seed={seed:crackCell}))\n"
        "Define(crackBreak, fBm(octaves=3, base_freq={mf:6}, to_01=True, seed={seed:crackBreak}))\n"
        "Define(crack, Threshold((((0.045 - crackCell) * 60) * "
        "Threshold((crackBreak - {cut}) * 8 + 1, below_at=0, above_at=1)), "
        "below_at=0, above_at=1))",
        "Layer(crack)\n.basecolor({rgb:_cond})\n.roughness(0.95)",
        (40, 34, 30),
    ),
    "wet": Overlay(
        "wet",
        "dark glossy damp patches and puddles",
        "Define(wetBlob, fBm(octaves=4, base_freq={mf:3}, to_01=True, seed={seed:wetBlob}))\n"
        f"Define(wet, {_ramp('wetBlob', 6)})",
        "Layer((wet * 0.6))\n.basecolor({rgb:_cond})\n.roughness(0.03)\n.coat(1)",
        (20, 20, 22),
    ),
    "worn": Overlay(
        "worn",
        "pale abraded patches where the surface is rubbed off",
        "Define(wearBlob, fBm(octaves=5, base_freq={mf:5}, to_01=True, seed={seed:wearBlob}))\n"
        "Define(wearFine, fBm(octaves=4, base_freq={mf:60}, to_01=True, seed={seed:wearFine}))\n"
        f"Define(wear, {_ramp('(wearBlob + (wearFine * 0.3))', 6)})",
        "Layer((wear * 0.75))\n.basecolor({mix:_cond~-0.15,_cond,wearFine})\n.roughness(0.9)",
        (0, 0, 0),
    ),
    "weathered": Overlay(
        "weathered",
        "faded, greyed streaks running down the surface",
        "Define(streak, fBm(octaves=5, base_freq_x={mf:14}, base_freq_y={mf:1.5}, to_01=True, "
        "seed={seed:streak}))\n"
        "Define(fade, fBm(octaves=3, base_freq={mf:3}, to_01=True, seed={seed:fade}))\n"
        f"Define(weather, {_ramp('((streak * 0.6) + (fade * 0.6))', 5)})",
        "Layer((weather * 0.55))\n.basecolor({rgb:_cond})\n.roughness(0.95)",
        (0, 0, 0),
    ),
    "dirty": Overlay(
        "dirty",
        "brown-grey grime collecting in blotches",
        "Define(grimeBlob, fBm(octaves=5, base_freq={mf:4}, to_01=True, seed={seed:grimeBlob}))\n"
        "Define(grimeFine, fBm(octaves=4, base_freq={mf:50}, to_01=True, seed={seed:grimeFine}))\n"
        f"Define(grime, {_ramp('(grimeBlob + (grimeFine * 0.3))', 4)})",
        "Layer((grime * 0.7))\n.basecolor({mix:_cond~-0.3,_cond,grimeFine})\n.roughness(0.95)",
        (78, 68, 54),
    ),
    "chipped": Overlay(
        "chipped",
        "chipped and peeling paint showing the darker substrate",
        "Define(chipBlob, fBm(octaves=6, base_freq={mf:7}, to_01=True, seed={seed:chipBlob}))\n"
        "Define(chip, Threshold(((chipBlob - {cut}) * 30), below_at=0, above_at=1))",
        "Layer(chip)\n.basecolor({rgb:_cond})\n.roughness(0.8)",
        (96, 90, 84),
    ),
    "stained": Overlay(
        "stained",
        "irregular blotchy stains",
        "Define(stainBlob, fBm(octaves=5, base_freq={mf:3}, to_01=True, seed={seed:stainBlob}))\n"
        f"Define(stain, {_ramp('stainBlob', 7)})",
        "Layer((stain * 0.85))\n.basecolor({mix:_cond,_cond~-0.25,stainBlob})\n.roughness(0.85)",
        (110, 78, 40),
    ),
    "burnt": Overlay(
        "burnt",
        "charred black patches with brown scorched rims",
        "Define(burnBlob, fBm(octaves=5, base_freq={mf:4}, to_01=True, seed={seed:burnBlob}))\n"
        f"Define(burn, {_ramp('burnBlob', 5)})",
        "Layer(burn)\n.basecolor({mix:_cond~0.25,_cond,burn})\n.roughness(0.95)",
        (24, 18, 14),
    ),
    "dusty": Overlay(
        "dusty",
        "a pale powdery dust film",
        "Define(dustBlob, fBm(octaves=5, base_freq={mf:5}, to_01=True, seed={seed:dustBlob}))\n"
        f"Define(dust, {_ramp('dustBlob', 3)})",
        "Layer((dust * 0.55))\n.basecolor({rgb:_cond})\n.roughness(1)",
        (196, 190, 178),
    ),
    "scratched": Overlay(
        "scratched",
        "fine bright scratches in several directions",
        "Define(scratchA, Rotate(fBm(octaves=3, base_freq_x={mf:2}, base_freq_y={mf:90}, "
        "to_01=True, seed={seed:scratchA}), 25))\n"
        "Define(scratchB, Rotate(fBm(octaves=3, base_freq_x={mf:2}, base_freq_y={mf:90}, "
        "to_01=True, seed={seed:scratchB}), -40))\n"
        "Define(scratch, Threshold(((Max(scratchA, scratchB) - ({cut} + 0.2)) * 25), "
        "below_at=0, above_at=1))",
        "Layer((scratch * 0.7))\n.basecolor({rgb:_cond})\n.roughness(0.5)",
        (0, 0, 0),
    ),
    "holes": Overlay(
        "holes",
        "torn holes showing the dark backing",
        "Define(holeCell, Worley(base_freq={mf:3}, to_01=True, seed={seed:holeCell}))\n"
        "Define(holeEdge, fBm(octaves=4, base_freq={mf:30}, to_01=True, seed={seed:holeEdge}))\n"
        "Define(hole, Threshold((((0.2 + ({cut} * -0.25)) - (holeCell + (holeEdge * 0.08))) * 40), "
        "below_at=0, above_at=1))",
        "Layer(hole)\n.basecolor({rgb:_cond})\n.roughness(1)",
        (14, 13, 12),
    ),
    "snowy": Overlay(
        "snowy",
        "drifts of white snow",
        "Define(snowBlob, fBm(octaves=5, base_freq={mf:4}, to_01=True, seed={seed:snowBlob}))\n"
        f"Define(snow, {_ramp('snowBlob', 8)})",
        "Layer(snow)\n.basecolor(238, 242, 248)\n.roughness(0.7)\n.sheen(0.3)\n"
        ".height((snow * {hv:0.02}))",
        (238, 242, 248),
    ),
    "muddy": Overlay(
        "muddy",
        "wet brown mud splashes",
        "Define(mudBlob, fBm(octaves=5, base_freq={mf:4}, to_01=True, seed={seed:mudBlob}))\n"
        f"Define(mud, {_ramp('mudBlob', 8)})",
        "Layer(mud)\n.basecolor({mix:_cond~-0.3,_cond,mudBlob})\n.roughness(0.35)",
        (92, 66, 42),
    ),
    "faded": Overlay(
        "faded",
        "sun-faded, washed-out colour",
        "Define(fadeBlob, fBm(octaves=3, base_freq={mf:2}, to_01=True, seed={seed:fadeBlob}))",
        "Layer((0.25 + (fadeBlob * 0.3)))\n.basecolor({rgb:_cond})\n.roughness(0.9)",
        (0, 0, 0),
    ),
    "glowing": Overlay(
        "glowing",
        "phosphorescent glowing specks",
        "Define(glowCell, Worley(base_freq={mf:9}, to_01=True, seed={seed:glowCell}))\n"
        "Define(glow, Threshold(((0.16 - glowCell) * 25), below_at=0, above_at=1))",
        "Layer(glow)\n.basecolor({rgb:_cond~0.4})\n.roughness(0.5)\n.emissive({rgb:_cond}, 2.5)",
        (110, 255, 170),
    ),
    "iridescent": Overlay(
        "iridescent",
        "a thin-film rainbow sheen",
        "Define(film, fBm(octaves=3, base_freq={mf:3}, to_01=True, seed={seed:film}))",
        "Layer(0.45)\n.basecolor((128 + (Sin((film * 14)) * 110)), "
        "(128 + (Sin(((film * 14) + 2.1)) * 110)), (128 + (Sin(((film * 14) + 4.2)) * 110)))\n"
        ".metallic(0.6)\n.roughness(0.3)",
        (0, 0, 0),
    ),
}

#: conditions whose overlay colour derives from the base colour: kind -> (lighten, desaturate).
DERIVED_COLOUR: dict[str, tuple[float, float]] = {
    "worn": (0.3, 0.45),
    "weathered": (0.25, 0.7),
    "scratched": (0.45, 0.5),
    "faded": (0.45, 0.6),
}

#: default cut level per amount: cut = CUT_BASE - CUT_SLOPE * amount (noise is ~N(0.5, 0.12)).
CUT_BASE = 0.66
CUT_SLOPE = 0.3
