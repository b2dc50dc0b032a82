#!/usr/bin/env python3
"""Render a scene of tests/aov/ with Mitsuba 3 and write every channel of its film, under
Mitsuba's own channel names, to tests/aov/NAME_ref.exr (float32, multichannel). The scenes:
aov.xml (a path tracer's image plus depth, shading normal, position and albedo channels) and
aov_index.xml (position and texture-coordinate derivatives, primitive and shape indices).

Usage:
    scripts/mitsuba_aov_ref.py [--scene aov] [--spp 1024] [--seed 7] [--variant scalar_rgb]

Use the scalar variant for aov_index: Mitsuba's shape_index is its scene list's position only
there (the JIT variants give a shape's registry number).

The film is written as Mitsuba develops it (mitsuba.Bitmap of the film), so the reference holds
Mitsuba's names and order; tests/tests/aov_agreement.rs reads it channel by channel.
"""
import argparse
import os

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
AOV_DIR = os.path.join(ROOT, "tests", "aov")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default="aov", help="NAME of tests/aov/NAME.xml")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--variant", default="scalar_rgb")
    args = ap.parse_args()
    import mitsuba as mi

    mi.set_variant(args.variant)
    SCENE = os.path.join(AOV_DIR, args.scene + ".xml")
    OUT = os.path.join(AOV_DIR, args.scene + "_ref.exr")
    scene = mi.load_file(SCENE, spp=str(args.spp))
    mi.render(scene, seed=args.seed, spp=args.spp)
    bitmap = scene.sensors()[0].film().bitmap(raw=False)
    names = [f.name for f in bitmap.struct_()]
    bitmap.write(OUT)
    print(f"wrote {OUT}: {bitmap.width()}x{bitmap.height()}, {args.spp} spp, channels {names}")


if __name__ == "__main__":
    main()
