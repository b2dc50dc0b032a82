#!/usr/bin/env python3
"""Write scenes/textures/tess_rgb.{bmp,tga,jpg}: the pixels of tess_rgb.png (5x4, 8-bit sRGB) in
the other 8-bit formats Mitsuba 3 reads, for the texture tests (tests/uv_cases/bitmap_bmp.xml,
bitmap_tga.xml, bitmap_jpeg.xml).

The BMP (24-bit, rows bottom-up, BGR, rows padded to 4 bytes) and the TGA (uncompressed
true-colour, type 2, bottom-left origin, BGR) are written here byte by byte from their published
layouts, so they hold exactly the PNG's codes. The JPEG is written by Mitsuba 3 (quality 100,
which Mitsuba writes without chroma subsampling); it is lossy, so its codes are near the PNG's,
not equal. Deterministic. Needs numpy and Mitsuba 3 (to read the PNG and write the JPEG).
"""
import os
import struct

import numpy as np


def bmp(img):
    h, w, _ = img.shape
    row = w * 3
    pad = (-row) % 4
    data = b"".join(
        img[y, :, ::-1].tobytes() + b"\0" * pad for y in range(h - 1, -1, -1)
    )
    offset = 14 + 40
    header = b"BM" + struct.pack("<IHHI", offset + len(data), 0, 0, offset)
    info = struct.pack("<IiiHHIIiiII", 40, w, h, 1, 24, 0, len(data), 2835, 2835, 0, 0)
    return header + info + data


def tga(img):
    h, w, _ = img.shape
    # id length, colour map type, image type 2 (true colour), colour map spec (5 bytes),
    # x/y origin, width, height, 24 bits per pixel, descriptor 0 (bottom-left origin).
    header = struct.pack("<BBB5sHHHHBB", 0, 0, 2, b"\0" * 5, 0, 0, w, h, 24, 0)
    data = b"".join(img[y, :, ::-1].tobytes() for y in range(h - 1, -1, -1))
    footer = struct.pack("<II", 0, 0) + b"TRUEVISION-XFILE.\0"
    return header + data + footer


def main():
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    tex = os.path.join(root, "scenes/textures")
    img = np.array(mi.Bitmap(os.path.join(tex, "tess_rgb.png")), dtype=np.uint8)
    for name, data in [("tess_rgb.bmp", bmp(img)), ("tess_rgb.tga", tga(img))]:
        with open(os.path.join(tex, name), "wb") as f:
            f.write(data)
        back = np.array(mi.Bitmap(os.path.join(tex, name)), dtype=np.uint8)
        assert (back == img).all(), f"{name}: Mitsuba reads other codes"
        print(os.path.join(tex, name))
    out = os.path.join(tex, "tess_rgb.jpg")
    mi.Bitmap(img, mi.Bitmap.PixelFormat.RGB).write(out, quality=100)
    print(out)


if __name__ == "__main__":
    main()
