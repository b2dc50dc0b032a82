#!/usr/bin/env python3
"""Write scenes/textures/bumps.png, the height field of scenes/bumpmap.xml.

A 64x64 one-channel 8-bit image (read with raw="true"): 0.5 + 0.4 sin(2 pi 2 x) sin(2 pi 3 y)
over the unit square, so each period is wide enough for the bilinear gradient to vary smoothly
and for 8x8-pixel regions of a 64x64 render to see a consistent tilt. The output is
deterministic. Needs numpy and Mitsuba 3 (for its PNG writer).
"""
import os

import numpy as np


def bumps(n=64):
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    h = 0.5 + 0.4 * np.sin(2 * np.pi * 2 * x) * np.sin(2 * np.pi * 3 * y)
    return np.round(h * 255.0).astype(np.uint8)[:, :, None]


def main():
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.join(root, "scenes/textures/bumps.png")
    mi.Bitmap(bumps(), mi.Bitmap.PixelFormat.Y).write(out)
    print(out)


if __name__ == "__main__":
    main()
