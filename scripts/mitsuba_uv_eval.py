#!/usr/bin/env python3
"""Tabulate Mitsuba 3's eval and pdf of one BSDF over many surface points, for textures.

Usage: scripts/mitsuba_uv_eval.py tests/uv_cases/NAME.xml [...]

Companion of scripts/mitsuba_bsdf_eval.py (which fixes uv and varies directions): here the
directions are fixed and uv varies, so a textured parameter (bitmap, checkerboard, a weight or
opacity texture) is checked at many points, inside and outside [0, 1]^2 (wrap modes, to_uv).
Writes NAME.csv beside each case: columns u, v, eval_r, eval_g, eval_b, pdf, where eval
includes |cos theta_o|, for wi = normalize(0.3, 0.2, 0.9) and wo = normalize(-0.2, 0.1, 0.95).
The points are a 13 x 13 grid over [-1.25, 2.25]^2 and 200 uniform random points (seed 5) in
[-2, 3]^2.
"""
import math
import os
import random
import sys
import xml.etree.ElementTree as ET

import mitsuba as mi

mi.set_variant("scalar_rgb")


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


WI = unit((0.3, 0.2, 0.9))
WO = unit((-0.2, 0.1, 0.95))


def points():
    pts = []
    for i in range(13):
        for j in range(13):
            pts.append((-1.25 + 3.5 * i / 12.0, -1.25 + 3.5 * j / 12.0))
    rng = random.Random(5)
    for _ in range(200):
        pts.append((rng.uniform(-2.0, 3.0), rng.uniform(-2.0, 3.0)))
    return pts


def load_bsdf(path):
    root = ET.parse(path).getroot()
    node = root.find("bsdf")
    if node is None:
        sys.exit(f"{path}: no top-level <bsdf>")
    node.set("version", "3.0.0")
    mi.file_resolver().prepend(os.path.dirname(os.path.abspath(path)))
    return mi.load_string(ET.tostring(node, encoding="unicode"))


def main():
    for path in sys.argv[1:]:
        bsdf = load_bsdf(path)
        ctx = mi.BSDFContext()
        rows = []
        for uv in points():
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(WI)
            si.uv = mi.Point2f(uv)
            si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
            si.n = mi.Normal3f(0, 0, 1)
            v = bsdf.eval(ctx, si, mi.Vector3f(WO))
            p = bsdf.pdf(ctx, si, mi.Vector3f(WO))
            # si.uv holds the single-precision values both renderers see.
            rows.append([si.uv[0], si.uv[1], v[0], v[1], v[2], p])
        out = os.path.splitext(path)[0] + ".csv"
        with open(out, "w") as f:
            f.write(f"# mitsuba {mi.__version__} scalar_rgb, wi = {WI}, wo = {WO}; "
                    "made by scripts/mitsuba_uv_eval.py\n")
            f.write("u,v,eval_r,eval_g,eval_b,pdf\n")
            for r in rows:
                f.write(",".join(f"{float(x):.9g}" for x in r) + "\n")
        print(f"{out}: {len(rows)} rows")


if __name__ == "__main__":
    main()
