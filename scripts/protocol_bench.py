#!/usr/bin/env python3
"""Efficiency against Mitsuba 3 at the sizes people render: the whole `tessera render` process
against Mitsuba 3 (`llvm_ad_rgb` by default) loading and rendering the same scene file, side by
side on this machine, with each scene file's own settings.

Usage:
    scripts/protocol_bench.py [--scenes cbox,veach_mis,materials] [--sizes 256,512]
        [--threads 2] [--min-seconds 5] [--min-spp 64] [--ref-spp 2048]
        [--variant llvm_ad_rgb] [--tessera target/dist/tessera] [--refs DIR]
        [--csv OUT.csv] [--tessera-args "--sampler zsobol ..."] [--label NAME]
        [--plots DIR [--doubling]] [--refs-only]

For each scene (`scenes/NAME.xml`, or a path: a file without a `res` parameter is rendered
from a copy whose films are SIZE wide) and image size (`-D res=SIZE`):
- a reference: Mitsuba 3 at --ref-spp (passes of 256 spp, `scripts/mitsuba_ref.py`, kept in
  --refs and reused);
- Tessera: `tessera render` at 64, 128, 256, ... spp until one run takes at least --min-seconds
  (and at least --min-spp samples per pixel); that sample count is rendered twice, and once more
  after both renderers' runs, and the fastest run counts: wall seconds of the whole process, its
  relMSE against the reference, its peak memory (max RSS);
- Mitsuba: likewise, one process per run that loads the scene (timed) and renders it (timed,
  including the transfer of the image to NumPy); a first, untimed 1 spp run fills Dr.Jit's kernel
  cache, and of the three runs at the final sample count (two, then one more after Tessera's)
  the fastest counts (the first may compile the kernels of a new launch size);
- efficiency = relMSE x seconds (lower is better; independent of the sample count for an
  unbiased renderer), and the ratio Tessera / Mitsuba.

relMSE = mean((a - b)^2 / (b^2 + 0.01)), as `tessera bench` computes it. The reference's own
noise adds to both renderers' relMSE; it is estimated from Mitsuba's run (relMSE falls as one
over the samples) and subtracted from both, and the table says how large it was.
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

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_bench import errors, rgb  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load(path):
    """An EXR file's RGB as float64."""
    import mitsuba as mi
    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    return rgb(np.array(mi.Bitmap(path)))

MITSUBA_RUN = r"""
import sys, time, json
t0 = time.perf_counter()
import mitsuba as mi
import drjit as dr
mi.set_variant(sys.argv[1])
dr.set_thread_count(int(sys.argv[2]))
scene_path, out, spp, res = sys.argv[3], sys.argv[4], int(sys.argv[5]), sys.argv[6]
t1 = time.perf_counter()
scene = mi.load_file(scene_path, res=int(res)) if res != "-" else mi.load_file(scene_path)
t2 = time.perf_counter()
img = mi.render(scene, spp=spp, seed=7)
import numpy as np
arr = np.array(img)
t3 = time.perf_counter()
mi.Bitmap(arr).write(out)
print(json.dumps({"import": t1 - t0, "load": t2 - t1, "render": t3 - t2}))
"""


def timed(cmd, env=None):
    """Runs `cmd` under /usr/bin/time: (wall seconds, max RSS in MB, stdout)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as tf:
        t0 = time.perf_counter()
        p = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", tf.name] + cmd,
                           capture_output=True, text=True, env=env)
        wall = time.perf_counter() - t0
        if p.returncode != 0:
            sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
        rss_kb = int(open(tf.name).read().strip().splitlines()[-1])
    return wall, rss_kb / 1024.0, p.stdout


def scene_path(name):
    return name if name.endswith(".xml") else os.path.join(ROOT, "scenes", name + ".xml")


SIZED = []


def sized(path, size):
    """The scene to render at `size` pixels wide, and the value of its `res` parameter ("-"
    for none). A file that declares `res` (as scenes/ do) is used as it is; any other (a
    public scene) is copied beside itself, with each film's width set to `size` and its height
    scaled alike, and so is every file it includes, so that relative paths still resolve. The
    copies are removed at exit."""
    text = open(path).read()
    if re.search(r'name="res"', text):
        return path, str(size)

    def copy(p):
        t = open(p).read()
        d = os.path.dirname(p)

        def inc(m):
            name = os.path.basename(copy(os.path.join(d, m.group(2))))
            return m.group(1) + os.path.join(os.path.dirname(m.group(2)), name) + m.group(3)
        t = re.sub(r'(<include\s+filename=")([^"]+)(")', inc, t)
        w = re.search(r'<integer\s+name="width"\s+value="(\d+)"', t)
        h = re.search(r'<integer\s+name="height"\s+value="(\d+)"', t)
        if w and h:
            height = max(1, round(size * int(h.group(1)) / int(w.group(1))))
            t = t[:w.start(1)] + str(size) + t[w.end(1):h.start(1)] + str(height) + t[h.end(1):] \
                if w.start() < h.start() else t
        out = os.path.join(d, f".{os.path.basename(p)[:-4]}.protocol{size}.xml")
        open(out, "w").write(t)
        SIZED.append(out)
        return out
    return copy(path), "-"


def cleanup():
    for p in SIZED:
        if os.path.exists(p):
            os.remove(p)


def reference(a, name, size):
    os.makedirs(a.refs, exist_ok=True)
    base = os.path.basename(scene_path(name))[:-4]
    out = os.path.join(a.refs, f"{base}_{size}_{a.ref_spp}spp_{a.variant}.exr")
    if not os.path.exists(out):
        print(f"reference {out} ...", flush=True)
        path, res = sized(scene_path(name), size)
        defines = [] if res == "-" else ["-D", f"res={res}"]
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "mitsuba_ref.py"),
                        path, "-o", out, "--spp", str(a.ref_spp), "--seed", "1000",
                        "--variant", a.variant] + defines, check=True)
    return load(out)


def tessera_run(a, name, size, spp, out):
    path, res = sized(scene_path(name), size)
    defines = [] if res == "-" else ["-D", f"res={res}"]
    cmd = [a.tessera, "render", path] + defines + ["--spp", str(spp),
           "--threads", str(a.threads), "-q", "-o", out] + a.tessera_args.split()
    wall, rss, _ = timed(cmd)
    return {"seconds": wall, "rss": rss, "load": tessera_load(a, path, defines)}


def tessera_load(a, path, defines):
    """Seconds `tessera info` reports for loading the scene (parsing, meshes, textures, the
    acceleration structure): what precedes the first sample."""
    p = subprocess.run([a.tessera, "info", path] + defines, capture_output=True, text=True)
    m = re.search(r"load\s+([0-9.]+) s in all", p.stdout)
    return float(m.group(1)) if m else float("nan")


def mitsuba_run(a, name, size, spp, out, env):
    path, res = sized(scene_path(name), size)
    cmd = [sys.executable, "-c", MITSUBA_RUN, a.variant, str(a.threads), path, out,
           str(spp), res]
    wall, rss, stdout = timed(cmd, env)
    parts = json.loads(stdout.strip().splitlines()[-1])
    # The whole process less Python's and Mitsuba's import: what loading and rendering took.
    return {"seconds": parts["load"] + parts["render"], "rss": rss, "load": parts["load"],
            "wall": wall}


def measure(a, run, name, size, ref):
    """Doubles the sample count from --min-spp until a run takes --min-seconds; the last run,
    with every run kept (the last count's faster one) in its "curve"."""
    spp = a.min_spp
    curve = []
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "x.exr")
        while True:
            r = run(spp, out)
            img = load(out)
            r["spp"] = spp
            r["pixels"] = img.shape[0] * img.shape[1]
            r["errors"] = errors(img, ref)
            r["relmse"] = r["errors"][1]
            if r["seconds"] >= a.min_seconds or spp >= 1 << 16:
                # The same run again, the faster kept: the first run at a sample count may
                # include one-off costs (Dr.Jit compiles a kernel per launch size), and on a
                # shared machine the faster of two identical runs is the better estimate.
                curve.append(r)
                r["curve"] = curve
                return faster_again(r, run, ref)
            curve.append(r)
            # Jump straight to about the sample count that takes long enough (or, for a
            # curve to plot, double).
            factor = max(2, 2 ** int(np.ceil(np.log2(a.min_seconds / max(r["seconds"], 1e-3)))))
            spp *= 2 if a.doubling else factor


def faster_again(r, run, ref):
    """`r` (a final run of `measure`, last in its "curve") or, if faster, the same run made once
    more, which then takes its place in the curve."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "x.exr")
        again = run(r["spp"], out)
        if again["seconds"] >= r["seconds"]:
            return r
        again.update(spp=r["spp"], pixels=r["pixels"], curve=r["curve"])
        again["errors"] = errors(load(out), ref)
        again["relmse"] = again["errors"][1]
        again["curve"][-1] = again
        return again


def plot(a, name, size, t, m):
    """The runs of both renderers as a tessera bench report, and its plot."""
    os.makedirs(a.plots, exist_ok=True)
    base = f"{os.path.basename(scene_path(name))[:-4]}_{size}"
    csv = os.path.join(a.plots, base + ".csv")
    lines = ["integrator,sampler,spp,threads,seconds,samples_per_second,rmse,relmse,mae"]
    for label, r in (("tessera", t), ("mitsuba-" + a.variant, m)):
        for c in r["curve"]:
            pixels = c.get("pixels", size * size)
            lines.append(f"{label},independent,{c['spp']},{a.threads},{c['seconds']:.6f},"
                         f"{pixels * c['spp'] / c['seconds']:.1f},{c['errors'][0]:.9g},"
                         f"{c['errors'][1]:.9g},{c['errors'][2]:.9g}")
    open(csv, "w").write("\n".join(lines) + "\n")
    title = f"{os.path.basename(scene_path(name))}, {size} wide, {a.threads} threads"
    subprocess.run([a.tessera, "bench", "--plot-only", csv, "--plot", csv[:-4] + ".png",
                    "--title", title, "--ratio-to", "mitsuba"], check=True,
                   stdout=subprocess.DEVNULL)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="cbox,veach_mis,materials")
    ap.add_argument("--sizes", default="256,512")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--min-seconds", type=float, default=5.0)
    ap.add_argument("--min-spp", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=2048)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--tessera", default=os.path.join(ROOT, "target", "dist", "tessera"))
    ap.add_argument("--tessera-args", default="")
    ap.add_argument("--refs", default=os.path.join(ROOT, "target", "protocol-refs"))
    ap.add_argument("--csv", default=None)
    ap.add_argument("--label", default="scene file's own settings")
    ap.add_argument("--plots", default=None,
                    help="write DIR/NAME_SIZE.csv (in tessera bench's report format, every run) "
                         "and DIR/NAME_SIZE.png (relMSE against seconds, both renderers)")
    ap.add_argument("--doubling", action="store_true",
                    help="double the sample count from --min-spp (no jumps): more runs, for --plots "
                         "(with a small --min-spp, e.g. 4)")
    ap.add_argument("--refs-only", action="store_true",
                    help="only render the missing references (needs no quiet machine), then stop")
    a = ap.parse_args()
    atexit.register(cleanup)

    env = dict(os.environ)
    llvm = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"
    if a.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in env and os.path.exists(llvm):
        env["DRJIT_LIBLLVM_PATH"] = llvm
    cpu = next((re.sub(r"\s+", " ", l.split(":", 1)[1]).strip()
                for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown CPU")
    print(f"# {cpu}, {a.threads} threads; Tessera: {a.label} {a.tessera_args}; "
          f"Mitsuba 3 {a.variant}")
    rows = []
    header = ("scene,size,renderer,spp,seconds,load_seconds,max_rss_mb,relmse,"
              "relmse_less_ref,efficiency")
    print("| scene | size | Tessera spp, s (load), relMSE, MB | Mitsuba spp, s (load), relMSE, MB "
          "| reference noise | efficiency ratio |")
    print("|---|---|---|---|---|---|")
    for name in a.scenes.split(","):
        for size in [int(s) for s in a.sizes.split(",")]:
            ref = reference(a, name, size)
            if a.refs_only:
                continue
            with tempfile.TemporaryDirectory() as d:
                # Fill Dr.Jit's kernel cache (untimed).
                mitsuba_run(a, name, size, 1, os.path.join(d, "w.exr"), env)
            m = measure(a, lambda spp, out: mitsuba_run(a, name, size, spp, out, env),
                        name, size, ref)
            t = measure(a, lambda spp, out: tessera_run(a, name, size, spp, out),
                        name, size, ref)
            # A third run of each at its final count, Mitsuba's then Tessera's, the fastest of
            # three kept: each renderer's runs then span the same stretch of time, so that a
            # change in the host's speed (this is often a shared virtual machine) weighs on
            # both sides of the ratio alike.
            m = faster_again(m, lambda spp, out: mitsuba_run(a, name, size, spp, out, env), ref)
            t = faster_again(t, lambda spp, out: tessera_run(a, name, size, spp, out), ref)
            # Reference noise: Mitsuba's relMSE is c (1/spp + 1/ref_spp).
            c = m["relmse"] / (1.0 / m["spp"] + 1.0 / a.ref_spp)
            noise = c / a.ref_spp
            for r in (m, t):
                r["clean"] = max(r["relmse"] - noise, 1e-30)
                r["eff"] = r["clean"] * r["seconds"]
            ratio = t["eff"] / m["eff"]
            if 2 * max(t["spp"], m["spp"]) > a.ref_spp:
                # The reference's noise is then a third or more of what a run measures, and the
                # ratio rests on the subtraction: a larger --ref-spp settles it.
                print(f"warning: {name} at {size}: a run took {max(t['spp'], m['spp'])} spp, "
                      f"over half the reference's {a.ref_spp}; the ratio is uncertain "
                      f"(render with a larger --ref-spp)", file=sys.stderr, flush=True)
            h = t["pixels"] // size
            print(f"| {os.path.basename(scene_path(name))} | {size}x{h} "
                  f"| {t['spp']}, {t['seconds']:.2f} ({t['load']:.3f}), {t['relmse']:.3e}, "
                  f"{t['rss']:.0f} "
                  f"| {m['spp']}, {m['seconds']:.2f} ({m['load']:.3f}), {m['relmse']:.3e}, "
                  f"{m['rss']:.0f} | {noise:.1e} | {ratio:.2f} |", flush=True)
            if a.plots:
                plot(a, name, size, t, m)
            for label, r in (("tessera", t), ("mitsuba-" + a.variant, m)):
                rows.append(f"{name},{size},{label},{r['spp']},{r['seconds']:.3f},"
                            f"{'' if r['load'] is None else round(r['load'], 3)},"
                            f"{r['rss']:.0f},{r['relmse']:.6e},{r['clean']:.6e},"
                            f"{r['eff']:.6e}")
            # Written after every row, so that a scene that fails keeps the ones before it.
            if a.csv:
                with open(a.csv, "w") as f:
                    f.write(header + "\n" + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
