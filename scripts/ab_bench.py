#!/usr/bin/env python3
"""A/B measurement of Tessera builds or settings: the same renders alternated, so that a gain of
a few percent can be told from a machine whose speed drifts by more between sittings.

Usage:
    scripts/ab_bench.py --scenes veach_mis,cs500_spheres [--size 512] [--spp 128]
        [--threads 2] [--rounds 3] [--refs target/protocol-refs] NAME=BINARY[::ARGS] ...

Each variant is a name, a `tessera` binary and optional extra `render` arguments after `::`
(e.g. `old=/tmp/tessera_old new=target/dist/tessera` for two builds, or
`plain=target/dist/tessera zs=target/dist/tessera::--sampler zsobol` for two settings). Every
round renders every scene once with every variant, the variants in a rotated order each round
(so that neither always runs first after a scene change), as the whole `tessera render
SCENE -D res=SIZE --spp SPP --threads T -q -o OUT.exr ARGS` process, timed by wall clock. A
scene is a name in `scenes/` or a path (a file without a `res` parameter is copied with its film
SIZE wide, as `protocol_bench.py` does).

Printed per scene and variant: the fastest, median and slowest seconds, the median's ratio to
the first variant's, and, where `--refs` holds the protocol's reference for the scene and size
(`NAME_SIZE_1024spp_llvm_ad_rgb.exr`, written by `protocol_bench.py`), the relMSE of the last
round's image and the efficiency (relMSE x median seconds). Variants whose images are
byte-identical to the first's are marked `same bits`, the check for a change meant to move only
the time.
"""
import argparse
import filecmp
import os
import shutil
import statistics
import sys
import tempfile
import time
import subprocess

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from protocol_bench import ROOT, cleanup, load, scene_path, sized  # noqa: E402
from mitsuba_bench import errors  # noqa: E402


def parse_variant(text):
    name, sep, rest = text.partition("=")
    if not sep or not name or not rest:
        sys.exit(f"a variant is NAME=BINARY[::ARGS], found {text!r}")
    binary, _, args = rest.partition("::")
    if not os.path.exists(binary):
        sys.exit(f"{name}: no binary {binary}")
    return name, binary, args.split()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", required=True)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--refs", default=os.path.join(ROOT, "target", "protocol-refs"))
    ap.add_argument("variants", nargs="+", help="NAME=BINARY[::ARGS]")
    a = ap.parse_args()
    variants = [parse_variant(v) for v in a.variants]
    if len({v[0] for v in variants}) != len(variants):
        sys.exit("variant names must differ")
    work = tempfile.mkdtemp(prefix="tessera-ab-")
    try:
        for name in a.scenes.split(","):
            measure_scene(a, name, variants, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
        cleanup()


def measure_scene(a, name, variants, work):
    path, res = sized(scene_path(name), a.size)
    defines = [] if res == "-" else ["-D", f"res={res}"]
    seconds = {v[0]: [] for v in variants}
    outs = {v[0]: os.path.join(work, f"{v[0]}.exr") for v in variants}
    for r in range(a.rounds):
        k = r % len(variants)
        for vname, binary, args in variants[k:] + variants[:k]:
            cmd = [binary, "render", path] + defines + [
                "--spp", str(a.spp), "--threads", str(a.threads), "-q", "-o", outs[vname]] + args
            t0 = time.perf_counter()
            p = subprocess.run(cmd, capture_output=True, text=True)
            wall = time.perf_counter() - t0
            if p.returncode != 0:
                sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
            seconds[vname].append(wall)
    base = os.path.basename(scene_path(name))[:-4]
    ref_path = os.path.join(a.refs, f"{base}_{a.size}_1024spp_llvm_ad_rgb.exr")
    ref = load(ref_path) if os.path.exists(ref_path) else None
    first = variants[0][0]
    first_median = statistics.median(seconds[first])
    print(f"## {name}, {a.size} wide, {a.spp} spp, {a.threads} threads, {a.rounds} rounds")
    print("| variant | fastest s | median s | slowest s | median / " + first
          + " | relMSE | efficiency | image |")
    print("|---|---|---|---|---|---|---|---|")
    for vname, _, _ in variants:
        s = seconds[vname]
        med = statistics.median(s)
        rel, eff = "", ""
        if ref is not None:
            e = errors(load(outs[vname]), ref)[1]
            rel, eff = f"{e:.4e}", f"{e * med:.4e}"
        same = vname != first and filecmp.cmp(outs[vname], outs[first], shallow=False)
        image = "same bits" if same else ("" if vname == first else "differs")
        print(f"| {vname} | {min(s):.2f} | {med:.2f} | {max(s):.2f} | {med / first_median:.3f} "
              f"| {rel} | {eff} | {image} |", flush=True)


if __name__ == "__main__":
    main()
