#!/usr/bin/env python3
"""Write scenes/textures/tiles.png, the 16x16 sRGB floor texture of scenes/materials.xml.

Warm and cool 8x8 quadrants with a light grout line on every eighth row and column and a small
red mark (rows 2-4, columns 10-12) so that flips and rotations of the uv mapping show. The output
is deterministic. Needs numpy and Mitsuba 3 (for its PNG writer).
"""
import os

import numpy as np


def tiles():
    y, x = np.mgrid[0:16, 0:16]
    img = np.zeros((16, 16, 3), np.uint8)
    warm, cool = np.array([200, 150, 100]), np.array([90, 120, 170])
    quadrant = ((x // 8) + (y // 8)) % 2
    img[:] = np.where(quadrant[..., None] == 0, warm, cool)
    img[(x % 8 == 0) | (y % 8 == 0)] = [235, 235, 225]
    img[2:5, 10:13] = [180, 40, 40]
    return img


def main():
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.join(root, "scenes/textures/tiles.png")
    mi.Bitmap(tiles(), mi.Bitmap.PixelFormat.RGB).write(out)
    print(out)


if __name__ == "__main__":
    main()
