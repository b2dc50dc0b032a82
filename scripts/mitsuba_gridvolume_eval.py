#!/usr/bin/env python3
"""Writes tests/volume_cases/: a small 3-channel voxel grid (grid.vol, Mitsuba's .vol format)
and Mitsuba 3.9.1's own lookups of it (gridvolume_eval.csv), for tests/tests/hetero_volumes.rs.

The grid is 3 x 4 x 2 voxels of seeded random values, its stated bounding box (-1, 0, 2) to
(2, 2, 3). Each row is one lookup by `mi.load_dict({'type': 'gridvolume', ...}).eval(...)` at a
world point, for every filter_type x wrap_mode, with to_world a scale, rotation and translation,
and with use_grid_bbox on and off; points fall inside the grid, near its faces and outside it.

    python3 scripts/mitsuba_gridvolume_eval.py
"""
import os
import struct

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
OUT = os.path.join(os.path.dirname(__file__), "..", "tests", "volume_cases")
RES = (3, 4, 2)
BBOX = (-1.0, 0.0, 2.0, 2.0, 2.0, 3.0)


def to_world():
    return (mi.ScalarTransform4f().translate([0.3, -0.2, 0.5])
            .rotate([0.6, 0.0, 0.8], 30).scale([1.5, 0.8, 1.2]))


def main():
    os.makedirs(OUT, exist_ok=True)
    rng = np.random.default_rng(7)
    data = rng.uniform(0.0, 4.0, size=(RES[2], RES[1], RES[0], 3)).astype("<f4")
    path = os.path.join(OUT, "grid.vol")
    with open(path, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<iiiii", 1, *RES, 3))
        f.write(struct.pack("<6f", *BBOX))
        f.write(data.tobytes())
    rows = ["filter,wrap,use_grid_bbox,x,y,z,r,g,b"]
    local = rng.uniform(-0.4, 1.4, size=(24, 3))
    local[:4] = [[0.5, 0.5, 0.5], [0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [1 / 6, 0.125, 0.75]]
    for use_bbox in (False, True):
        box = (mi.ScalarTransform4f().translate(BBOX[:3])
               .scale([BBOX[3] - BBOX[0], BBOX[4] - BBOX[1], BBOX[5] - BBOX[2]]))
        place = to_world() @ box if use_bbox else to_world()
        for ft in ("trilinear", "nearest"):
            for wm in ("clamp", "repeat", "mirror"):
                v = mi.load_dict({"type": "gridvolume", "filename": path, "filter_type": ft,
                                  "wrap_mode": wm, "use_grid_bbox": use_bbox,
                                  "to_world": to_world()})
                for q in local:
                    p = place @ mi.ScalarPoint3f(*q)
                    it = mi.Interaction3f()
                    it.p = mi.Point3f(*p)
                    c = v.eval(it)
                    rows.append(f"{ft},{wm},{int(use_bbox)},{p[0]!r},{p[1]!r},{p[2]!r},"
                                f"{float(c[0])!r},{float(c[1])!r},{float(c[2])!r}")
    with open(os.path.join(OUT, "gridvolume_eval.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")
    print(f"{path}, {len(rows) - 1} lookups")


if __name__ == "__main__":
    main()
