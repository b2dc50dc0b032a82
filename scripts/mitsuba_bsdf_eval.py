#!/usr/bin/env python3
"""Tabulate Mitsuba 3's eval and pdf of one BSDF, for Tessera's agreement test.

Usage: scripts/mitsuba_bsdf_eval.py tests/bsdf_cases/NAME.xml [...]

Each case file is a Mitsuba 3 scene whose first top-level <bsdf> is the material under test.
The script writes NAME.csv beside it: one row per (wi, wo) pair of a fixed grid, columns
wi_x wi_y wi_z wo_x wo_y wo_z eval_r eval_g eval_b pdf, where eval includes |cos theta_o| (both
renderers' convention) and uv = (0.25, 0.75). Incident directions cover both sides (the back
side matters for twosided and glass); outgoing directions cover the whole sphere.

The shading frame is the world's axes. Cases whose name starts with "bumpmap" read the
surface's partials and geometric normal, so they get the fixed GEOMETRY below (dp/du, dp/dv,
geometric normal), which the table's second comment line states for the test to use.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import mitsuba as mi

mi.set_variant("scalar_rgb")

UV = (0.25, 0.75)
_N = (0.08, -0.06, 1.0)
GEOMETRY = {
    "dp_du": (0.9, 0.2, 0.15),
    "dp_dv": (-0.25, 1.1, -0.1),
    "n": tuple(c / math.sqrt(sum(x * x for x in _N)) for c in _N),
}


def directions():
    wis = []
    for th in (0.0, 20.0, 45.0, 70.0, 85.0, 120.0, 160.0):
        t = math.radians(th)
        p = 0.7
        wis.append((math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)))
    wos = []
    for i in range(12):
        z = 1.0 - (i + 0.5) / 6.0
        r = math.sqrt(max(0.0, 1.0 - z * z))
        for j in range(8):
            p = 2.0 * math.pi * (j + 0.31) / 8.0
            wos.append((r * math.cos(p), r * math.sin(p), z))
    return wis, wos


def load_bsdf(path):
    root = ET.parse(path).getroot()
    node = root.find("bsdf")
    if node is None:
        sys.exit(f"{path}: no top-level <bsdf>")
    node.set("version", "3.0.0")
    # Relative file names resolve beside the case file.
    mi.file_resolver().prepend(os.path.dirname(os.path.abspath(path)))
    return mi.load_string(ET.tostring(node, encoding="unicode"))


def main():
    for path in sys.argv[1:]:
        bsdf = load_bsdf(path)
        ctx = mi.BSDFContext()
        wis, wos = directions()
        rows = []
        geometry = os.path.basename(path).startswith("bumpmap")
        for wi in wis:
            si = mi.SurfaceInteraction3f()
            si.wi = mi.Vector3f(wi)
            si.uv = mi.Point2f(UV)
            si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
            si.n = mi.Normal3f(0, 0, 1)
            if geometry:
                si.dp_du = mi.Vector3f(GEOMETRY["dp_du"])
                si.dp_dv = mi.Vector3f(GEOMETRY["dp_dv"])
                si.n = mi.Normal3f(GEOMETRY["n"])
            for wo in wos:
                v = bsdf.eval(ctx, si, mi.Vector3f(wo))
                p = bsdf.pdf(ctx, si, mi.Vector3f(wo))
                rows.append(list(wi) + list(wo) + [v[0], v[1], v[2], p])
        out = os.path.splitext(path)[0] + ".csv"
        with open(out, "w") as f:
            f.write(f"# mitsuba {mi.__version__} scalar_rgb, uv = {UV}; made by scripts/mitsuba_bsdf_eval.py\n")
            if geometry:
                g = " ".join(f"{k}=" + ",".join(f"{float(c):.9g}" for c in v) for k, v in GEOMETRY.items())
                f.write(f"# geometry {g}\n")
            f.write("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,eval_r,eval_g,eval_b,pdf\n")
            for r in rows:
                f.write(",".join(f"{float(x):.9g}" for x in r) + "\n")
        print(f"{out}: {len(rows)} rows")


if __name__ == "__main__":
    main()
