#!/usr/bin/env python3
"""Render the instancing and cylinder test scenes (tests/instances/instances.xml, cylinder.xml)
with Mitsuba 3 and write their references (linear float32 RGB EXR) into tests/instances/refs/,
for tests/tests/instances.rs.

Usage:
    scripts/mitsuba_instance_refs.py [--spp 2048] [--variant scalar_rgb]

The render runs in passes of 256 samples, each with its own seed, averaged in float64.
"""
import argparse
import os

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
DIR = os.path.join(ROOT, "tests", "instances")
SCENES = ["instances.xml", "cylinder.xml"]
PASS = 256


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=2048)
    ap.add_argument("--variant", default="scalar_rgb")
    args = ap.parse_args()
    import mitsuba as mi

    mi.set_variant(args.variant)
    os.makedirs(os.path.join(DIR, "refs"), exist_ok=True)
    for name in SCENES:
        scene = mi.load_file(os.path.join(DIR, name))
        acc = None
        passes = args.spp // PASS
        for k in range(passes):
            img = np.array(mi.render(scene, spp=PASS, seed=k), dtype=np.float64)
            acc = img if acc is None else acc + img
        out = (acc / passes).astype(np.float32)
        path = os.path.join(DIR, "refs", name[: -len(".xml")] + ".exr")
        mi.Bitmap(out).write(path)
        print(f"{path}: {args.spp} spp, mean {out.mean():.5f}")


if __name__ == "__main__":
    main()
