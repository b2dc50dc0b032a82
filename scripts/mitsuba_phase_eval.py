#!/usr/bin/env python3
"""Tabulate Mitsuba 3's eval and pdf of one phase function, for Tessera's agreement test.

Usage: scripts/mitsuba_phase_eval.py tests/phase_cases/NAME.xml [...]

Each case file is a Mitsuba 3 scene whose first top-level <phase> is the function under test.
The script writes NAME.csv beside it: one row per (wi, wo) pair of a fixed grid, columns
wi_x wi_y wi_z wo_x wo_y wo_z eval pdf (the first channel of eval; the phase functions tested
are grey). wi points back toward the previous vertex, as in both renderers; the medium
interaction's frame is built around wi, as Mitsuba's own phase tests do. Outgoing directions
cover the whole sphere, denser near the forward direction -wi where peaked functions change
fastest.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import mitsuba as mi

mi.set_variant("scalar_rgb")


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def directions():
    wis = [normalize(v) for v in ((0.0, 0.0, 1.0), (-0.6, 0.3, -0.2), (0.2, -0.9, 0.4))]
    wos = []
    for i in range(16):
        z = 1.0 - (i + 0.5) / 8.0
        r = math.sqrt(max(0.0, 1.0 - z * z))
        for j in range(8):
            p = 2.0 * math.pi * (j + 0.31) / 8.0
            wos.append((r * math.cos(p), r * math.sin(p), z))
    return wis, wos


def forward_cone(wi):
    """Directions within 25 degrees of -wi (the forward peak)."""
    f = mi.Frame3f(mi.Vector3f([-c for c in wi]))
    out = []
    for th in (0.0, 1.0, 3.0, 6.0, 10.0, 15.0, 25.0):
        t = math.radians(th)
        for j in range(3):
            p = 2.0 * math.pi * (j + 0.17) / 3.0
            v = f.to_world(mi.Vector3f(math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)))
            out.append(normalize((v[0], v[1], v[2])))
    return out


def load_phase(path):
    root = ET.parse(path).getroot()
    node = root.find("phase")
    if node is None:
        sys.exit(f"{path}: no top-level <phase>")
    node.set("version", "3.0.0")
    # Files the function reads (an sggx grid) sit beside the case file.
    mi.file_resolver().prepend(os.path.dirname(os.path.abspath(path)))
    return mi.load_string(ET.tostring(node, encoding="unicode"))


def main():
    for path in sys.argv[1:]:
        phase = load_phase(path)
        ctx = mi.PhaseFunctionContext(None)
        wis, wos = directions()
        rows = []
        for wi in wis:
            mei = mi.MediumInteraction3f()
            mei.t = 0.5
            mei.p = mi.Point3f(0, 0, 0)
            mei.wi = mi.Vector3f(wi)
            mei.sh_frame = mi.Frame3f(mei.wi)
            for wo in wos + forward_cone(wi):
                v, p = phase.eval_pdf(ctx, mei, mi.Vector3f(wo))
                rows.append(list(wi) + list(wo) + [v[0], p])
        out = path[: -len(".xml")] + ".csv"
        with open(out, "w") as f:
            f.write(f"# mitsuba {mi.__version__} scalar_rgb; made by scripts/mitsuba_phase_eval.py\n")
            f.write("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,eval,pdf\n")
            for r in rows:
                f.write(",".join(f"{float(x):.9g}" for x in r) + "\n")
        print(f"{out}: {len(rows)} rows")


if __name__ == "__main__":
    main()
