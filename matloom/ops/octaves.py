"""The fBm octave schedule: per-octave frequencies and amplitudes (pure Python).

Shared by the noise plans (:mod:`matloom.engine.kernels.noise`), the lazy fused path and fBm's
period rule (:mod:`matloom.ops.period_rules`: whether every octave's lattice can be wrapped).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["OctaveSchedule", "octave_schedule"]


@dataclass(frozen=True)
class OctaveSchedule:
    """Per-octave frequencies/amplitudes (Python floats) and the amplitude sum ``norm``."""

    freqs_x: tuple[float, ...]
    freqs_y: tuple[float, ...]
    amps: tuple[float, ...]
    norm: float


def octave_schedule(
    octaves: int, lacunarity: float, gain: float, freq_x: float, freq_y: float
) -> OctaveSchedule:
    """Build f_k = base * lacunarity^k and amp_k = gain^k by repeated multiplication.

    Repeated multiplication (not ``**``) is what the reference does; it matters for the
    float32 rounding of the per-octave coordinates.
    """
    if int(octaves) < 1:
        raise ValueError(f"octaves must be >= 1, got {octaves}")
    # Python floats: a numpy float64 frequency would be a "strong" scalar for numpy 2 and turn
    # float32 axes * f_k into a float64 product, losing the reference's float32 rounding.
    lacunarity, gain = float(lacunarity), float(gain)
    fx, fy, amp = float(freq_x), float(freq_y), 1.0
    freqs_x: list[float] = []
    freqs_y: list[float] = []
    amps: list[float] = []
    for _ in range(int(octaves)):
        freqs_x.append(fx)
        freqs_y.append(fy)
        amps.append(amp)
        fx *= lacunarity
        fy *= lacunarity
        amp *= gain
    norm = 0.0
    for a in amps:
        norm += a
    return OctaveSchedule(tuple(freqs_x), tuple(freqs_y), tuple(amps), norm)
