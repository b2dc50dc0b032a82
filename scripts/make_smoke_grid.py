#!/usr/bin/env python3
"""Writes scenes/media/smoke.vol: a small smoke-like density grid for scenes/media/smoke.xml.

12 x 16 x 12 voxels, one channel, in Mitsuba's .vol format (version 3, float32). The density is
a rising plume: a column whose radius widens with height and whose centre sways, with two puffs
and soft edges; values in [0, 1], zero at the grid's border so that the grid's box is where the
smoke ends. Deterministic (no random numbers), so the file is reproducible.

    python3 scripts/make_smoke_grid.py [OUT.vol]
"""
import math
import struct
import sys

RES = (12, 16, 12)


def density(x, y, z):
    """Density at the voxel centre (x, y, z) in [0, 1]^3 (y up)."""
    cx = 0.5 + 0.12 * math.sin(5.0 * y)
    cz = 0.5 + 0.08 * math.cos(4.0 * y)
    radius = 0.12 + 0.22 * y
    r = math.hypot(x - cx, z - cz)
    column = max(0.0, 1.0 - (r / radius) ** 2) * min(1.0, 4.0 * y) * (1.0 - 0.5 * y)
    puffs = 0.0
    for (px, py, pz, s, a) in ((0.62, 0.72, 0.45, 0.14, 0.9), (0.35, 0.45, 0.55, 0.1, 0.7)):
        d2 = (x - px) ** 2 + (y - py) ** 2 + (z - pz) ** 2
        puffs += a * math.exp(-d2 / (2.0 * s * s))
    v = min(1.0, column + puffs)
    # Fade to zero at the border voxels.
    edge = min(x, 1.0 - x, y, 1.0 - y, z, 1.0 - z)
    return v * min(1.0, max(0.0, (edge - 0.5 / max(RES)) * 6.0))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/media/smoke.vol"
    nx, ny, nz = RES
    data = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                data.append(density((i + 0.5) / nx, (j + 0.5) / ny, (k + 0.5) / nz))
    with open(out, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<i", 1))
        f.write(struct.pack("<iii", nx, ny, nz))
        f.write(struct.pack("<i", 1))
        f.write(struct.pack("<6f", 0, 0, 0, 1, 1, 1))
        f.write(struct.pack("<%df" % len(data), *data))
    print(f"{out}: {nx}x{ny}x{nz}, max {max(data):.3f}, mean {sum(data) / len(data):.3f}")


if __name__ == "__main__":
    main()
