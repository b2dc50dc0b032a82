#!/usr/bin/env python3
"""Write Mitsuba 3's view of a mesh shape: world-space vertex positions, normals, texture
coordinates and triangles, for comparing mesh loaders (`.serialized` first).

Usage: scripts/mitsuba_mesh_dump.py tests/serialized_cases/NAME.xml [...]

Each NAME.xml is a scene holding one <shape> (and nothing else that Mitsuba needs to load).
Writes NAME.txt beside it: a comment line, then sections "positions N", "normals N" (0 when
Mitsuba keeps no vertex normals, as with face_normals), "uvs N" and "faces N", one row of
space-separated values per entry, floats as %.9g (enough to round-trip a float32).
"""
import os
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")


def rows(values, dim):
    values = list(values)
    return [values[i:i + dim] for i in range(0, len(values), dim)]


def main():
    for path in sys.argv[1:]:
        scene = mi.load_file(path)
        shapes = scene.shapes()
        if len(shapes) != 1:
            sys.exit(f"{path}: {len(shapes)} shapes, expected 1")
        mesh = shapes[0]
        params = mi.traverse(mesh)
        sections = [
            ("positions", rows(params["vertex_positions"], 3)),
            ("normals", rows(params["vertex_normals"], 3) if mesh.has_vertex_normals() else []),
            ("uvs", rows(params["vertex_texcoords"], 2) if mesh.has_vertex_texcoords() else []),
            ("faces", rows(params["faces"], 3)),
        ]
        out = os.path.splitext(path)[0] + ".txt"
        with open(out, "w") as f:
            f.write(f"# mitsuba {mi.__version__} scalar_rgb; made by scripts/mitsuba_mesh_dump.py\n")
            for name, data in sections:
                f.write(f"{name} {len(data)}\n")
                for r in data:
                    if name == "faces":
                        f.write(" ".join(str(int(x)) for x in r) + "\n")
                    else:
                        f.write(" ".join(f"{float(x):.9g}" for x in r) + "\n")
        print(f"{out}: {len(sections[0][1])} vertices, {len(sections[3][1])} faces")


if __name__ == "__main__":
    main()
