#!/usr/bin/env python3
"""Where the time goes, stage by stage, against Mitsuba 3: the same scene file rendered by both
renderers with the path cut at increasing depths, each depth's extra seconds being the cost of
that stage.

Usage:
    scripts/stage_costs.py [--scene materials] [--size 512] [--spp 32] [--depths 1,2,3,8]
        [--threads 2] [--runs 2] [--variant llvm_ad_rgb] [--tessera target/dist/tessera]
        [--strategies]

The scene (`scenes/NAME.xml`, or a path) must declare the parameters `res` and `max_depth` (as
the scenes of `scenes/` do): each run passes `-D res=SIZE -D max_depth=D` (depth 0 passes no
depth: the file's integrator as it stands). For each depth D, both renderers render SIZE x SIZE
at --spp, --runs times each (alternating), and the fastest run counts:
- Tessera: the whole `tessera render` process (load, render, writing the image);
- Mitsuba: loading the scene and `mi.render` up to the image in NumPy, in a process whose
  Dr.Jit kernel cache was filled by an untimed run of the same depth and size at 1 spp.

Depth 1 is the camera stage (camera rays, what they hit, the film); depth 2 adds the first
vertex (light selection, emitter sample, shadow ray, BSDF evaluation and sampling, the
continuation ray and what it finds); each further depth adds one more vertex, for the paths
still alive. The table gives each stage's seconds for both renderers and their ratio
(Tessera / Mitsuba; lower is better).

A cut path is not the same work in both: Mitsuba's vector variant compiles the whole loop into
one kernel and runs a vertex's code with its lanes masked off even where the depth ends the
path before it, so its depth-1 time holds more than the camera stage. --strategies therefore
also renders the first vertex with its two strategies apart, from copies of the file (written
beside it and removed at exit) whose integrator is replaced by:
- `aov` with a depth channel: the camera stage alone (camera ray, hit, film);
- `direct`, 1 emitter sample, 0 BSDF samples: plus light selection, the emitter sample, the
  shadow ray and the BSDF's value;
- `direct`, 0 and 1: plus BSDF sampling, the continuation ray and the emission it finds;
- `direct`, 1 and 1: both, weighed.
Each row's stage cost is its time less the camera stage's.
"""
import argparse
import atexit
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from protocol_bench import scene_path  # noqa: E402

MITSUBA_RUN = r"""
import sys, time, json
import mitsuba as mi
import drjit as dr
mi.set_variant(sys.argv[1])
dr.set_thread_count(int(sys.argv[2]))
path, spp, res, depth = sys.argv[3], int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])
t1 = time.perf_counter()
params = {"res": res} if depth == 0 else {"res": res, "max_depth": depth}
scene = mi.load_file(path, **params)
img = mi.render(scene, spp=spp, seed=7)
import numpy as np
arr = np.array(img)
print(json.dumps({"seconds": time.perf_counter() - t1}))
"""


def tessera(a, path, depth):
    with tempfile.TemporaryDirectory() as d:
        depth_arg = [] if depth == 0 else ["-D", f"max_depth={depth}"]
        cmd = [a.tessera, "render", path, "-D", f"res={a.size}"] + depth_arg + [
               "--spp", str(a.spp), "--threads", str(a.threads), "-q",
               "-o", os.path.join(d, "x.exr")]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        return time.perf_counter() - t0


def mitsuba(a, path, depth, spp=None):
    cmd = [sys.executable, "-c", MITSUBA_RUN, a.variant, str(a.threads), path,
           str(spp or a.spp), str(a.size), str(depth)]
    p = subprocess.run(cmd, check=True, capture_output=True, text=True)
    return json.loads(p.stdout.strip().splitlines()[-1])["seconds"]


def fastest(a, path, depth):
    """Both renderers' fastest of --runs alternated runs of `path` at `depth` (Mitsuba's
    kernel cache filled first by an untimed 1 spp run)."""
    mitsuba(a, path, depth, spp=1)
    t, m = [], []
    for _ in range(a.runs):
        t.append(tessera(a, path, depth))
        m.append(mitsuba(a, path, depth))
    return min(t), min(m)


STRATEGIES = [
    ("camera stage (aov depth)",
     '<integrator type="aov"><string name="aovs" value="dd:depth"/></integrator>'),
    ("emitter sampling (direct 1, 0)", '<integrator type="direct">'
     '<integer name="emitter_samples" value="1"/><integer name="bsdf_samples" value="0"/>'
     '</integrator>'),
    ("BSDF sampling (direct 0, 1)", '<integrator type="direct">'
     '<integer name="emitter_samples" value="0"/><integer name="bsdf_samples" value="1"/>'
     '</integrator>'),
    ("both, weighed (direct 1, 1)", '<integrator type="direct">'
     '<integer name="emitter_samples" value="1"/><integer name="bsdf_samples" value="1"/>'
     '</integrator>'),
]


def strategy_copy(path, k, integrator):
    """A copy of `path` beside it whose integrator element is `integrator`."""
    text = open(path).read()
    new, n = re.subn(r"<integrator\b.*?</integrator>|<integrator\b[^>]*/>", integrator, text,
                     count=1, flags=re.S)
    if n != 1:
        sys.exit(f"{path}: no integrator element to replace")
    out = os.path.join(os.path.dirname(path), f".stage_{k}_{os.path.basename(path)}")
    with open(out, "w") as f:
        f.write(new)
    atexit.register(lambda: os.path.exists(out) and os.remove(out))
    return out


def strategies(a, path):
    rows = []
    for k, (name, integrator) in enumerate(STRATEGIES):
        t, m = fastest(a, strategy_copy(path, k, integrator), 0)
        rows.append((name, t, m))
        print(f"{name}: tessera {t:.3f} s, mitsuba {m:.3f} s", file=sys.stderr)
    print()
    print("| first vertex, by strategy | Tessera s | Mitsuba s | ratio |")
    print("|---|---|---|---|")
    _, t0, m0 = rows[0]
    print(f"| {rows[0][0]} | {t0:.2f} | {m0:.2f} | {t0 / m0:.2f} |")
    for name, t, m in rows[1:]:
        dt, dm = t - t0, m - m0
        ratio = dt / dm if dm > 0 else float("nan")
        print(f"| {name}, less the camera stage | {dt:.2f} | {dm:.2f} | {ratio:.2f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="materials")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--depths", default="1,2,3,8")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--tessera", default=os.path.join(ROOT, "target", "dist", "tessera"))
    ap.add_argument("--strategies", action="store_true")
    a = ap.parse_args()
    path = scene_path(a.scene)
    depths = [int(d) for d in a.depths.split(",")]
    rows = []
    for depth in depths:
        t, m = fastest(a, path, depth)
        rows.append((depth, t, m))
        print(f"depth {depth}: tessera {t:.3f} s, mitsuba {m:.3f} s", file=sys.stderr)
    print(f"{os.path.basename(path)}, {a.size}x{a.size}, {a.spp} spp, {a.threads} threads, "
          f"fastest of {a.runs} (Mitsuba: {a.variant})")
    print("| stage | Tessera s | Mitsuba s | ratio |")
    print("|---|---|---|---|")
    prev = None
    for depth, t, m in rows:
        if prev is None:
            name, dt, dm = f"to depth {depth} (camera stage)", t, m
        else:
            name = f"depth {prev[0]} -> {depth}"
            dt, dm = t - prev[1], m - prev[2]
        ratio = dt / dm if dm > 0 else float("nan")
        print(f"| {name} | {dt:.2f} | {dm:.2f} | {ratio:.2f} |")
        prev = (depth, t, m)
    print(f"| whole render at depth {rows[-1][0]} | {rows[-1][1]:.2f} | {rows[-1][2]:.2f} | "
          f"{rows[-1][1] / rows[-1][2]:.2f} |")
    if a.strategies:
        strategies(a, path)


if __name__ == "__main__":
    main()
