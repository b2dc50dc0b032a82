"""Renders a scene once with Mitsuba 3 for scripts/mitsuba_rays/run.sh (which preloads the
ray-counting shim) and prints the render's wall time and samples.

usage: render.py SCENE.xml VARIANT THREADS [-D name=value ...]"""
import sys
import time

import drjit as dr
import mitsuba as mi


def main():
    scene_file, variant, threads = sys.argv[1], sys.argv[2], int(sys.argv[3])
    params = {}
    rest = sys.argv[4:]
    while rest:
        if rest[0] != "-D" or len(rest) < 2 or "=" not in rest[1]:
            sys.exit("render.py: expected -D name=value, got " + " ".join(rest))
        name, value = rest[1].split("=", 1)
        params[name] = value
        rest = rest[2:]
    mi.set_variant(variant)
    dr.set_thread_count(threads)
    scene = mi.load_file(scene_file, **params)
    spp = scene.sensors()[0].sampler().sample_count()
    size = scene.sensors()[0].film().crop_size()
    start = time.perf_counter()
    image = mi.render(scene, spp=spp, seed=0)
    dr.eval(image)
    dr.sync_thread()
    seconds = time.perf_counter() - start
    samples = int(size[0]) * int(size[1]) * spp
    print(f"RENDER {seconds:.3f} s (with kernel compilation), {samples} samples", file=sys.stderr)


if __name__ == "__main__":
    main()
