#!/usr/bin/env python3
"""Write scenes/textures/sky.exr, the small latitude-longitude environment of scenes/envmap.xml.

Usage:
    scripts/make_envmap.py [-o scenes/textures/sky.exr] [--width 128] [--no-sun]
    scripts/make_envmap.py -o scenes/textures/sky_soft.exr --width 64 --no-sun

A procedural sky in Mitsuba 3's latitude-longitude convention (row y at polar angle
theta = pi * y / (height - 1) from +y, column x at u = (x + 1/2) / width, direction
(sin(2 pi u) sin(theta), cos(theta), -cos(2 pi u) sin(theta))): a blue sky brightening toward
the horizon, a dim brown ground, a small bright sun (radiance 80, 12 degrees across) at 35
degrees elevation toward +x-ish, and a red and a green band on the horizon so that orientation
mistakes show. Linear float32 RGB EXR (written with Mitsuba's Bitmap, needs Mitsuba 3 and numpy;
the output is deterministic).
"""
import argparse
import os

import numpy as np


def sky(width, with_sun=True):
    height = width // 2 + 1
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    theta = np.pi * y / (height - 1)
    phi = 2 * np.pi * (x + 0.5) / width
    d = np.stack([np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)], -1)
    up = d[..., 1]
    img = np.zeros((height, width, 3))
    # Sky: deeper blue at the zenith, whiter at the horizon.
    t = np.clip(up, 0, 1)
    zenith, horizon = np.array([0.25, 0.45, 1.0]), np.array([0.9, 0.95, 1.0])
    img[up >= 0] = (horizon * (1 - t[..., None]) ** 3 + zenith * (1 - (1 - t[..., None]) ** 3))[up >= 0]
    # Ground: dim brown, darker straight down.
    g = np.clip(-up, 0, 1)[..., None]
    ground = np.array([0.18, 0.12, 0.07]) * (1 - 0.6 * g)
    img[up < 0] = ground[up < 0]
    # Coloured bands on the horizon (azimuth ranges in u), for orientation.
    u = (x + 0.5) / width
    band = np.abs(up) < 0.12
    img[band & (u > 0.55) & (u < 0.65)] = [2.0, 0.1, 0.1]
    img[band & (u > 0.88) & (u < 0.93)] = [0.1, 1.5, 0.1]
    # Sun: a disk of 6 degrees radius at 35 degrees elevation.
    elev, azim = np.radians(35), np.radians(60)
    sun = np.array([np.cos(elev) * np.sin(azim), np.sin(elev), -np.cos(elev) * np.cos(azim)])
    cos_sun = d @ sun
    if with_sun:
        img[cos_sun > np.cos(np.radians(6.0))] = [80.0, 72.0, 60.0]
    return img.astype(np.float32)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("-o", "--output", default=os.path.join(root, "scenes/textures/sky.exr"))
    ap.add_argument("--width", type=int, default=128)
    ap.add_argument("--no-sun", action="store_true",
                    help="leave the sun out (scenes/textures/sky_soft.exr of scenes/materials.xml)")
    args = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    img = sky(args.width, with_sun=not args.no_sun)
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    mi.Bitmap(img, mi.Bitmap.PixelFormat.RGB).write(args.output)
    print(f"{args.output}: {img.shape[1]}x{img.shape[0]}, max {img.max():.1f}, "
          f"mean ({img[..., 0].mean():.4f}, {img[..., 1].mean():.4f}, {img[..., 2].mean():.4f})")


if __name__ == "__main__":
    main()
