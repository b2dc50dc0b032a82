#!/usr/bin/env python3
"""Render the corpus scenes listed in tests/real/refs/LIST with Mitsuba 3 and write their
references (linear float32 RGB EXR) into tests/real/refs/.

Usage:
    scripts/mitsuba_real_refs.py [--only SUBSTRING ...] [--seed S] [--variant scalar_rgb]

The corpus files are public scene files nobody here wrote; they are never edited. Their film
(often 500x500 or larger, often a Gaussian filter, sometimes in an included file) is overridden
in Mitsuba's parsed scene (mitsuba.parser): width and height from LIST, reconstruction filter
box, every other film and filter property as the file has it. tests/tests/real_agreement.rs
makes the same override on Tessera's parsed scene. Like scripts/mitsuba_ref.py, the render runs
in passes of at most --pass-spp samples, each with its own seed, averaged in float64 (Mitsuba's
scalar film sums in float32).
"""
import argparse
import os
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
REAL = os.path.join(ROOT, "tests", "real")
REFS = os.path.join(REAL, "refs")


def read_list():
    """(scene, width, height, spp, defines) per line of tests/real/refs/LIST (the fifth column,
    the test's own sample count, is not needed here; name=value words after it are -D defines)."""
    out = []
    with open(os.path.join(REFS, "LIST")) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            scene, w, h, spp, _ours_spp, *defs = line.split()
            defines = dict(d.split("=", 1) for d in defs)
            out.append((scene, int(w), int(h), int(spp), defines))
    return out


def ref_name(scene):
    return scene.replace("/", "__")[: -len(".xml")] + ".exr"


def load_overridden(mi, variant, path, width, height, defines):
    """The scene at `path`, its film set to width x height with a box filter. Relative file
    names resolve beside the file, as in mitsuba.load_file."""
    saved = mi.FileResolver(mi.file_resolver())
    mi.file_resolver().prepend(os.path.dirname(os.path.abspath(path)))
    try:
        return load_parsed(mi, variant, path, width, height, defines)
    finally:
        mi.Thread.thread().set_file_resolver(saved)


def load_parsed(mi, variant, path, width, height, defines):
    cfg = mi.parser.ParserConfig(variant)
    state = mi.parser.parse_file(cfg, path, **defines)
    nodes = state.nodes
    films = [n for n in nodes if n.type == mi.ObjectType.Film]
    filters = [n for n in nodes if n.type == mi.ObjectType.ReconstructionFilter]
    if len(films) != 1 or len(filters) != 1:
        sys.exit(f"{path}: expected one film with one rfilter, "
                 f"found {len(films)} films and {len(filters)} filters")
    films[0].props["width"] = width
    films[0].props["height"] = height
    filt = filters[0].props
    for k in list(filt.keys()):
        del filt[k]
    filt.set_plugin_name("box")
    state.nodes = nodes
    mi.parser.transform_all(cfg, state)
    return mi.parser.instantiate(cfg, state)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", action="append", default=[],
                    help="render only scenes whose path contains this (repeatable)")
    ap.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    ap.add_argument("--variant", default="scalar_rgb", help="Mitsuba variant (default scalar_rgb)")
    ap.add_argument("--pass-spp", type=int, default=256,
                    help="samples per pass; passes are averaged in float64 (default 256)")
    args = ap.parse_args()

    import numpy as np
    import mitsuba as mi
    mi.set_variant(args.variant)

    for scene_rel, width, height, total, defines in read_list():
        if args.only and not any(o in scene_rel for o in args.only):
            continue
        scene = load_overridden(mi, args.variant, os.path.join(REAL, scene_rel), width, height,
                                defines)
        size = list(scene.sensors()[0].film().size())
        assert size == [width, height], (scene_rel, size)
        t0 = time.time()
        acc, done, k = None, 0, 0
        while done < total:
            n = min(args.pass_spp, total - done)
            part = np.array(mi.render(scene, spp=n, seed=args.seed * 100003 + k),
                            dtype=np.float64)
            acc = part * n if acc is None else acc + part * n
            done += n
            k += 1
        img = np.ascontiguousarray((acc / total)[:, :, :3], dtype=np.float32)
        out = os.path.join(REFS, ref_name(scene_rel))
        mi.Bitmap(img, mi.Bitmap.PixelFormat.RGB).write(out)
        nan = int(np.isnan(img).sum())
        print(f"{out}: {width}x{height} spp={total} seed={args.seed} variant={args.variant} "
              f"mitsuba={mi.__version__} time={time.time() - t0:.1f}s "
              f"mean=({img[..., 0].mean():.5f}, {img[..., 1].mean():.5f}, "
              f"{img[..., 2].mean():.5f}) nan={nan}", file=sys.stderr)


if __name__ == "__main__":
    main()
