"""Reusable Define snippets for lattices the language has no primitive for.

* ``HEX``: a hexagonal lattice (neighbour distance 1) from two offset rectangular grids;
  ``hexD`` is the hex distance to the nearest centre (0 at the centre, 0.5 on an edge) and
  ``hexTone`` a per-cell random value in [0, 1) from the Floor-cell sin hash.
* ``TRIANGLE``: a triangular lattice of side 1 from three line families at 0/60/120 degrees;
  ``triEdge`` is the distance to the nearest edge, ``triUp`` is 1 on upward triangles.
* ``HERRINGBONE``: a true herringbone of 2:1 bricks laid at 45 degrees (brick width
  ``{hb_w}``); ``hbEdge`` is the distance to the nearest joint in brick widths, ``hbHoriz`` is
  1 on bricks running along +45 degrees and ``hbTone`` a per-brick value. Each unit cell of the
  rotated grid is half a brick; (column - row) mod 4 says which half, hence which cell edges
  are joints.
* ``SCALES``: overlapping scale rows (fish scales, reptile skin); ``scaleRim`` is 0 on a
  scale's lower rim and grows toward the next row, ``scaleTone`` a per-row-and-column value.

Snippets are template text: they can use ``{slot}`` forms, and every recipe using one must
reference the names it needs (unused Defines would be reported by the checker).
"""

from __future__ import annotations


def hash01(name: str, a: str, b: str) -> str:
    """Two Define lines: ``name`` = a per-cell random value in [0, 1) for integer cell (a, b)."""
    return (
        f"Define({name}Hash, (Sin((({a} * 12.9898) + ({b} * 78.233))) * 43758.5453))\n"
        f"Define({name}, ({name}Hash - Floor({name}Hash)))"
    )


HEX = """
Define(ax, (X() - Floor((X() + 0.5))))
Define(ay, (Y() - (1.732 * Floor(((Y() / 1.732) + 0.5)))))
Define(bx, ((X() - 0.5) - Floor(X())))
Define(by, ((Y() - 0.866) - (1.732 * Floor((Y() / 1.732)))))
Define(hexA, Max(Abs(ax), ((Abs(ax) * 0.5) + (Abs(ay) * 0.866))))
Define(hexB, Max(Abs(bx), ((Abs(bx) * 0.5) + (Abs(by) * 0.866))))
Define(hexD, Min(hexA, hexB))
""".strip("\n")

HEX_TONE = """
Define(inA, Threshold(((hexB - hexA) * 1000), below_at=0, above_at=1))
Define(hcx, ((inA * Floor((X() + 0.5))) + ((1 - inA) * (Floor(X()) + 0.5))))
Define(hcy, ((inA * Floor(((Y() / 1.732) + 0.5))) + ((1 - inA) * (Floor((Y() / 1.732)) + 0.5))))
Define(hexHash, (Sin(((hcx * 12.9898) + (hcy * 78.233))) * 43758.5453))
Define(hexTone, (hexHash - Floor(hexHash)))
""".strip("\n")

TRIANGLE = """
Define(t0, (Y() / 0.866))
Define(t1, (((X() * 0.866) + (Y() * 0.5)) / 0.866))
Define(t2, (((Y() * 0.5) - (X() * 0.866)) / 0.866))
Define(triEdge, Min(Min(Abs((t0 - Floor((t0 + 0.5)))), Abs((t1 - Floor((t1 + 0.5))))), Abs((t2 - Floor((t2 + 0.5))))))
Define(triSum, ((Floor(t0) + Floor(t1)) + Floor(t2)))
Define(triUp, (triSum - (2 * Floor((triSum / 2)))))
""".strip("\n")

SCALES = """
Define(scaleRow, Floor((Y() / {scale_h})))
Define(scaleU, ((X() / {scale_w}) + ((scaleRow - (2 * Floor((scaleRow / 2)))) * 0.5)))
Define(scaleFx, (((scaleU - Floor(scaleU)) * 2) - 1))
Define(scaleArc, ((Y() / {scale_h}) - ((1 - Sqrt(Max((1 - (scaleFx * scaleFx)), 0))) * 0.9)))
Define(scaleRim, (scaleArc - Floor(scaleArc)))
""".strip("\n")

HERRINGBONE = (
    """
Define(hu, (((X() + Y()) * 0.7071) / {hb_w}))
Define(hv, (((Y() - X()) * 0.7071) / {hb_w}))
Define(hd, (Floor(hu) - Floor(hv)))
Define(hr, (hd - (4 * Floor((hd / 4)))))
Define(hq0, Threshold(((0.5 - Abs(hr)) * 10), below_at=0, above_at=1))
Define(hq1, Threshold(((0.5 - Abs((hr - 1))) * 10), below_at=0, above_at=1))
Define(hq2, Threshold(((0.5 - Abs((hr - 2))) * 10), below_at=0, above_at=1))
Define(hq3, Threshold(((0.5 - Abs((hr - 3))) * 10), below_at=0, above_at=1))
Define(hfx, (hu - Floor(hu)))
Define(hfy, (hv - Floor(hv)))
Define(hbEdge, Min(Min((hfx + hq1), ((1 - hfx) + hq0)), Min((hfy + hq2), ((1 - hfy) + hq3))))
Define(hbHoriz, (hq0 + hq1))
""".strip("\n")
    + "\n"
    + hash01("hbTone", "(Floor(hu) - hq1)", "(Floor(hv) + hq3)")
)
