#!/usr/bin/env python3
"""Writes the SGGX matrix grids of scenes/media/flakes.xml, in Mitsuba's .vol format (version 3,
float32, 6 channels per voxel: S_xx, S_yy, S_zz, S_xy, S_xz, S_yz).

- scenes/media/flakes.vol: 6 x 6 x 6 voxels of fibre-like flakes, S = s^2 t t^T + (I - t t^T)
  with s = 0.2, their axis t turning with x and tilting with y, so that the projected area (and
  with it the extinction) varies with both place and direction; eigenvalues s^2 and 1, so the
  projected area never exceeds 1 (Mitsuba 3's majorant assumes it does not).
- scenes/media/flakes_uniform.vol: 1 voxel of surface-like flakes, S = n n^T + s^2 (I - n n^T)
  with n tilted from the y axis and s = 0.3 (a fixed phase function, for a homogeneous medium).

Deterministic (no random numbers), so the files are reproducible.

    python3 scripts/make_flakes_grid.py [OUT_DIR]
"""
import math
import struct
import sys


def outer_mix(a, big, small):
    """small * a a^T + big * (I - a a^T) as (xx, yy, zz, xy, xz, yz), a a unit vector."""
    def m(i, j):
        return small * a[i] * a[j] + big * ((1.0 if i == j else 0.0) - a[i] * a[j])
    return [m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2)]


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def write(path, res, voxels):
    with open(path, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<i", 1))
        f.write(struct.pack("<iii", *res))
        f.write(struct.pack("<i", 6))
        f.write(struct.pack("<6f", 0, 0, 0, 1, 1, 1))
        data = [c for v in voxels for c in v]
        f.write(struct.pack("<%df" % len(data), *data))
    print(f"{path}: {res[0]}x{res[1]}x{res[2]}, 6 channels")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/media"
    n = 6
    voxels = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                x, y = (i + 0.5) / n, (j + 0.5) / n
                phi = math.pi * x
                tilt = 0.9 * (y - 0.5)
                t = unit([math.cos(phi) * math.cos(tilt), math.sin(tilt),
                          math.sin(phi) * math.cos(tilt)])
                voxels.append(outer_mix(t, 1.0, 0.2 ** 2))
    write(f"{out}/flakes.vol", (n, n, n), voxels)
    normal = unit([0.3, 1.0, -0.2])
    write(f"{out}/flakes_uniform.vol", (1, 1, 1), [outer_mix(normal, 0.3 ** 2, 1.0)])


if __name__ == "__main__":
    main()
