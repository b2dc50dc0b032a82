#!/usr/bin/env python3
"""Writes the small textures of tests/bsdf_cases/ that exercise textured BSDF parameters.

Usage: scripts/make_bsdf_case_textures.py (writes into tests/bsdf_cases/textures/)

normal_tilt.png: a 4x4 tangent-space normal map (colours (n + 1) / 2), whose four pixels
around uv = (0.25, 0.75) (the lookup point of scripts/mitsuba_bsdf_eval.py) hold different
normals tilted away from the incident directions' azimuth, so bilinear filtering, the
tangent frame and the flip of normals facing away all matter.
normal_tilt_green_flipped.png: the same with the green channel inverted (the other tangent-space
handedness), for the tests' controls.
roughness.png: a 4x4 grey-and-colour ramp read as a scalar roughness (its luminance).
height.png: a 4x4 one-channel height field for bumpmap, whose four pixels around
uv = (0.25, 0.75) differ along both axes (so both components of its gradient are non-zero).
eta.exr: a 4x4 linear ramp of relative indices between 1.2 and 1.8 (grey), for a textured eta.
"""
import os

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "bsdf_cases", "textures")


def normal_map():
    img = np.zeros((4, 4, 3))
    rng = np.random.default_rng(7)
    for y in range(4):
        for x in range(4):
            n = np.array([rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 1.0])
            img[y, x] = n / np.linalg.norm(n)
    # The pixels bilinear filtering reads at uv = (0.25, 0.75): rows 2-3, columns 0-1.
    for (y, x), n in {
        (2, 0): (-0.45, -0.35, 0.82),
        (2, 1): (-0.25, -0.45, 0.86),
        (3, 0): (-0.5, -0.2, 0.84),
        (3, 1): (-0.3, -0.3, 0.9),
    }.items():
        n = np.array(n)
        img[y, x] = n / np.linalg.norm(n)
    return np.round((img + 1.0) * 0.5 * 255.0).astype(np.uint8)


def roughness_map():
    img = np.zeros((4, 4, 3))
    for y in range(4):
        for x in range(4):
            img[y, x] = (0.05 + 0.1 * x, 0.1 + 0.15 * y, 0.3)
    return np.round(img * 255.0).astype(np.uint8)


def eta_map():
    img = np.zeros((4, 4, 3), dtype=np.float32)
    for y in range(4):
        for x in range(4):
            img[y, x] = 1.2 + 0.15 * x + 0.05 * y
    return img


def height_map():
    rng = np.random.default_rng(11)
    img = rng.uniform(0.2, 0.8, size=(4, 4))
    # The pixels bilinear filtering reads at uv = (0.25, 0.75): rows 2-3, columns 0-1.
    for (y, x), h in {(2, 0): 0.30, (2, 1): 0.55, (3, 0): 0.45, (3, 1): 0.85}.items():
        img[y, x] = h
    return np.round(img * 255.0).astype(np.uint8)[:, :, None]


def main():
    os.makedirs(OUT, exist_ok=True)
    flipped = normal_map()
    flipped[:, :, 1] = 255 - flipped[:, :, 1]
    for name, data in (
        ("normal_tilt.png", normal_map()),
        ("normal_tilt_green_flipped.png", flipped),
        ("roughness.png", roughness_map()),
        ("eta.exr", eta_map()),
        ("height.png", height_map()),
    ):
        fmt = mi.Bitmap.PixelFormat.Y if data.shape[2] == 1 else mi.Bitmap.PixelFormat.RGB
        bmp = mi.Bitmap(data, pixel_format=fmt)
        bmp.set_srgb_gamma(False)
        path = os.path.join(OUT, name)
        bmp.write(path)
        print(path)


if __name__ == "__main__":
    main()
