#!/usr/bin/env python3
"""Render tests/aov/aov.xml (the aov integrator: a path tracer's image plus depth, shading
normal, position and albedo channels) with Mitsuba 3 and write every channel of its film, under
Mitsuba's own channel names, to tests/aov/aov_ref.exr (float32, multichannel).

Usage:
    scripts/mitsuba_aov_ref.py [--spp 1024] [--seed 7] [--variant scalar_rgb]

The film is written as Mitsuba develops it (mitsuba.Bitmap of the film), so the reference holds
Mitsuba's names and order; tests/tests/aov_agreement.rs reads it channel by channel.
"""
import argparse
import os

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
SCENE = os.path.join(ROOT, "tests", "aov", "aov.xml")
OUT = os.path.join(ROOT, "tests", "aov", "aov_ref.exr")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--variant", default="scalar_rgb")
    args = ap.parse_args()
    import mitsuba as mi

    mi.set_variant(args.variant)
    scene = mi.load_file(SCENE, spp=str(args.spp))
    mi.render(scene, seed=args.seed, spp=args.spp)
    bitmap = scene.sensors()[0].film().bitmap(raw=False)
    names = [f.name for f in bitmap.struct_()]
    bitmap.write(OUT)
    print(f"wrote {OUT}: {bitmap.width()}x{bitmap.height()}, {args.spp} spp, channels {names}")


if __name__ == "__main__":
    main()
