#!/usr/bin/env python3
"""Samples per second of Mitsuba 3 on a scene file: load, an untimed 1 spp render (which fills
Dr.Jit's kernel cache), then one timed render of SPP samples per pixel, the image transferred to
NumPy (which waits for the kernels). Prints the load and render seconds and the rate.

Usage:
    scripts/mitsuba_rate.py SCENE.xml SPP [--variant llvm_ad_rgb] [--threads 2] [-D name=value ...]

After scripts/install_mitsuba.sh (and, for the LLVM variants, scripts/install_llvm.sh).
"""
import argparse
import os
import time

LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("spp", type=int)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("-D", action="append", default=[], metavar="NAME=VALUE")
    a = ap.parse_args()
    if os.path.exists(LLVM19):
        os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM19)
    import drjit as dr
    import mitsuba as mi
    import numpy as np
    mi.set_variant(a.variant)
    dr.set_thread_count(a.threads)
    params = dict(d.split("=", 1) for d in a.D)
    os.chdir(os.path.dirname(os.path.abspath(a.scene)))
    t0 = time.time()
    scene = mi.load_file(os.path.basename(a.scene), **params)
    t1 = time.time()
    np.array(mi.render(scene, spp=1))
    t2 = time.time()
    img = np.array(mi.render(scene, spp=a.spp, seed=1))
    t3 = time.time()
    samples = img.shape[0] * img.shape[1] * a.spp
    print(f"{a.variant}: load {t1 - t0:.2f} s, render {t3 - t2:.2f} s, "
          f"{samples / (t3 - t2) / 1e6:.2f} M samples/s")


if __name__ == "__main__":
    main()
