#!/usr/bin/env python3
"""Tabulate Mitsuba 3's ray hits on a curve shape, for tests/tests/curves_mitsuba.rs.

Usage: scripts/mitsuba_curve_hits.py tests/curve_cases/NAME.xml [...]

Each case is a scene holding one `linearcurve` or `bsplinecurve`. Writes NAME.csv beside it,
one row per ray: ox, oy, oz, dx, dy, dz, hit, t, px, py, pz, nx, ny, nz, u, v (the hit's
fields from `scene.ray_intersect`, zeros on a miss). Rays (seed 7): 800 from a sphere of twice
the scene's bounding-box diagonal around its centre toward uniform points of the box, and 150
from uniform points of the box in uniform directions (some start inside the tube, which Mitsuba
does not hit from there).
"""
import math
import os
import random
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def sphere_dir(rng):
    z = rng.uniform(-1.0, 1.0)
    phi = rng.uniform(0.0, 2.0 * math.pi)
    s = math.sqrt(max(0.0, 1.0 - z * z))
    return [s * math.cos(phi), s * math.sin(phi), z]


def rays(bbox, rng):
    lo = [bbox.min[i] for i in range(3)]
    hi = [bbox.max[i] for i in range(3)]
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    diag = math.sqrt(sum((b - a) ** 2 for a, b in zip(lo, hi)))
    out = []
    for _ in range(800):
        w = sphere_dir(rng)
        o = [c[i] + 2.0 * diag * w[i] for i in range(3)]
        p = [rng.uniform(lo[i], hi[i]) for i in range(3)]
        out.append((o, unit([p[i] - o[i] for i in range(3)])))
    for _ in range(150):
        o = [rng.uniform(lo[i], hi[i]) for i in range(3)]
        out.append((o, sphere_dir(rng)))
    return out


def main():
    for path in sys.argv[1:]:
        mi.file_resolver().prepend(os.path.dirname(os.path.abspath(path)))
        scene = mi.load_file(path)
        rng = random.Random(7)
        rows = []
        for o, d in rays(scene.bbox(), rng):
            si = scene.ray_intersect(mi.Ray3f(o, d))
            if si.is_valid():
                vals = [1, si.t, *si.p, *si.n, *si.uv]
            else:
                vals = [0] + [0.0] * 9
            rows.append([*o, *d, *vals])
        out = os.path.splitext(path)[0] + ".csv"
        with open(out, "w") as f:
            f.write("ox,oy,oz,dx,dy,dz,hit,t,px,py,pz,nx,ny,nz,u,v\n")
            for r in rows:
                f.write(",".join("%.9g" % x for x in r) + "\n")
        hits = sum(r[6] for r in rows)
        print(f"{out}: {len(rows)} rays, {hits} hits")


if __name__ == "__main__":
    main()
