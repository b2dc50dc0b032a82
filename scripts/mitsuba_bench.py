#!/usr/bin/env python3
"""Error against time for Mitsuba 3 on a scene file, in the CSV format of `tessera bench`.

Usage:
    scripts/mitsuba_bench.py SCENE.xml --reference REF.exr -o report.csv
        [--variant scalar_rgb[,llvm_ad_rgb]] [--threads N] [--max-seconds S] [--max-spp N]
        [--seed S] [--seeds N] [--repeats N] [--target-relmse E] [--label NAME]
        [-D name=value ...]

Renders the scene in waves of 1, 2, 4, ... samples per pixel. Unlike `tessera bench`, which
continues one sample sequence, each wave here is a FRESH Mitsuba render with that sample count
and the same fixed seed (one `mi.render(scene, spp=N, seed=S)` call, as a user would make): a
row's `seconds` is the wall-clock time of that single call, including the conversion of the
result to a NumPy array (which, for the LLVM variants, waits for the kernels to finish). Before
the waves one untimed 1 spp render warms up (LLVM variants compile their kernels then; later
calls hit Dr.Jit's kernel cache). A curve stops before a wave whose predicted time (twice the
last one) would pass --max-seconds, or at --max-spp.

With --seeds N, each wave renders N times, with seeds S, S + 1, ..., S + N - 1, and its row is the
mean of those renders (seconds, relMSE, MSE, MAE; RMSE is the root of the mean MSE), as
`tessera bench --seeds N` reports; the time limit applies to the mean seconds.

With --repeats N, each of those renders is made N times and its time is the least of the N (its
errors are those of the first; a render whose errors differ from the first's is reported on
stderr), as `tessera bench --repeats N` keeps each wave's least time: on a shared machine the
fastest of several identical runs estimates the time the work takes.

Errors are computed as in Tessera, in float64 over every pixel and channel against the
reference: RMSE, relMSE = mean((a - b)^2 / (b^2 + 0.01)), MAE. Rows are APPENDED to the report
(the header is written if the file is new or empty; an existing file must have the same
header), with the integrator column `mitsuba-VARIANT:NAME` (NAME from the scene's integrator,
e.g. `mitsuba-scalar_rgb:path`; --label overrides), sampler `independent`. Plot a combined
report with `tessera bench --plot-only report.csv --plot report.png`.

--threads sets Dr.Jit's thread pool (`drjit.set_thread_count`), which both the scalar and the
LLVM variants render with. For `llvm_ad_rgb`, Dr.Jit needs an LLVM it can drive:
`scripts/install_llvm.sh` installs Debian's libllvm19; this script then points
DRJIT_LIBLLVM_PATH at it unless the variable is already set.
"""
import argparse
import os
import sys
import time

HEADER = "integrator,sampler,spp,threads,seconds,samples_per_second,rmse,relmse,mae"
LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"


def errors(img, ref):
    import numpy as np
    d = img.astype(np.float64) - ref.astype(np.float64)
    return (float(np.sqrt(np.mean(d * d))),
            float(np.mean(d * d / (ref.astype(np.float64) ** 2 + 0.01))),
            float(np.mean(np.abs(d))))


def rgb(arr):
    import numpy as np
    a = np.asarray(arr, dtype=np.float64)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.shape[2] < 3:
        a = np.repeat(a[:, :, :1], 3, axis=2)
    return a[:, :, :3]


def time_to_target(rows, target):
    """Seconds to first reach `target` relMSE, interpolated in log-log (as tessera bench)."""
    import math
    prev = None
    for r in rows:
        if r["relmse"] <= target:
            if prev is None:
                return f"<= {r['seconds']:.3f} s (first wave)"
            e0, e1 = math.log(prev["relmse"]), math.log(r["relmse"])
            t0, t1 = math.log(max(prev["seconds"], 1e-12)), math.log(max(r["seconds"], 1e-12))
            f = (math.log(target) - e0) / (e1 - e0) if e1 < e0 else 1.0
            return f"{math.exp(t0 + min(max(f, 0.0), 1.0) * (t1 - t0)):.3f} s"
        prev = r
    if not rows:
        return "not reached (no rows)"
    best = min(rows, key=lambda r: r["relmse"])
    return f"not reached (best relMSE {best['relmse']:.3e} at {best['seconds']:.3f} s)"


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", help="Mitsuba 3 XML scene file")
    ap.add_argument("--reference", required=True, help="converged reference (.exr)")
    ap.add_argument("-o", "--output", required=True, help="CSV report to append to")
    ap.add_argument("--variant", default="scalar_rgb",
                    help="Mitsuba variant(s), comma separated (default scalar_rgb)")
    ap.add_argument("--threads", type=int, default=None, help="threads (default: all cores)")
    ap.add_argument("--max-seconds", type=float, default=60.0)
    ap.add_argument("--max-spp", type=int, default=1 << 20)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--seeds", type=int, default=1,
                    help="renders per wave, seeds --seed, --seed + 1, ...; rows are their means")
    ap.add_argument("--repeats", type=int, default=1,
                    help="time each render this many times and keep the least time")
    ap.add_argument("--target-relmse", type=float, default=0.01)
    ap.add_argument("--label", default=None, help="integrator column (default mitsuba-VARIANT:NAME)")
    ap.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE",
                    help="set a scene <default> parameter")
    ap.add_argument("-q", "--quiet", action="store_true", help="no line per wave")
    args = ap.parse_args()

    params = {}
    for d in args.defines:
        if "=" not in d:
            ap.error(f"-D expects name=value, got {d!r}")
        k, v = d.split("=", 1)
        params[k.strip()] = v.strip()
    if args.max_seconds <= 0 or args.max_spp < 1 or args.seeds < 1 or args.repeats < 1:
        ap.error("--max-seconds must be positive, --max-spp, --seeds and --repeats at least 1")
    variants = [v.strip() for v in args.variant.split(",") if v.strip()]
    if any(v.startswith("llvm") for v in variants) and "DRJIT_LIBLLVM_PATH" not in os.environ \
            and os.path.exists(LLVM19):
        os.environ["DRJIT_LIBLLVM_PATH"] = LLVM19

    import numpy as np
    import drjit as dr
    import mitsuba as mi

    if os.path.exists(args.output) and os.path.getsize(args.output) > 0:
        with open(args.output) as f:
            first = f.readline().strip()
        if first != HEADER:
            print(f"error: {args.output}:1: not a bench report (first line must be {HEADER!r})",
                  file=sys.stderr)
            sys.exit(2)
        need_header = False
    else:
        need_header = True

    threads = args.threads if args.threads else (os.cpu_count() or 1)
    all_rows = []
    for variant in variants:
        mi.set_variant(variant)
        dr.set_thread_count(threads)
        try:
            ref = rgb(mi.Bitmap(os.path.abspath(args.reference)))
        except Exception as e:  # noqa: BLE001 - one line, exit 2, like tessera bench
            print(f"error: {args.reference}: cannot read image: {e}".splitlines()[0],
                  file=sys.stderr)
            sys.exit(2)
        scene = mi.load_file(os.path.abspath(args.scene), **params)
        film = scene.sensors()[0].film()
        w, h = film.crop_size()
        if ref.shape[0] != h or ref.shape[1] != w:
            print(f"error: {args.reference}: the reference is {ref.shape[1]}x{ref.shape[0]} "
                  f"but the scene renders {w}x{h}", file=sys.stderr)
            sys.exit(2)
        name = scene.integrator().class_name()
        name = name[:-len("Integrator")] if name.endswith("Integrator") else name
        label = args.label or f"mitsuba-{variant}:{name.lower()}"
        if "," in label:
            ap.error("--label may not contain a comma")

        np.asarray(mi.render(scene, spp=1, seed=args.seed))  # warm-up, untimed
        rows, spp, last = [], 1, 0.0
        while spp <= args.max_spp and (not rows or 2.0 * last <= args.max_seconds):
            runs = []
            for k in range(args.seeds):
                best, errs = None, None
                for rep in range(args.repeats):
                    t0 = time.perf_counter()
                    img = rgb(mi.render(scene, spp=spp, seed=args.seed + k))
                    t = time.perf_counter() - t0
                    e = errors(img, ref)
                    if errs is None:
                        errs = e
                    elif e != errs:
                        print(f"warning: {label}: {spp} spp, seed {args.seed + k}: repeat "
                              f"{rep + 1} gave relMSE {e[1]:.6e} against {errs[1]:.6e}",
                              file=sys.stderr)
                    best = t if best is None else min(best, t)
                runs.append((best,) + errs)
            n = len(runs)
            last = sum(r[0] for r in runs) / n
            rmse = (sum(r[1] ** 2 for r in runs) / n) ** 0.5
            relmse = sum(r[2] for r in runs) / n
            mae = sum(r[3] for r in runs) / n
            row = dict(integrator=label, spp=spp, seconds=last,
                       sps=w * h * spp / max(last, 1e-9), rmse=rmse, relmse=relmse, mae=mae)
            rows.append(row)
            if not args.quiet:
                print(f"{label}: {spp:>7} spp {last:>9.3f} s {row['sps'] / 1e6:>7.3f} M samples/s"
                      f"  relMSE {relmse:.4e}  RMSE {rmse:.4e}  MAE {mae:.4e}", file=sys.stderr)
            spp *= 2
        print(f"{label} ({threads} threads): time to relMSE {args.target_relmse}: "
              f"{time_to_target(rows, args.target_relmse)}")
        all_rows += rows

    with open(args.output, "a") as f:
        if need_header:
            f.write(HEADER + "\n")
        for r in all_rows:
            f.write(f"{r['integrator']},independent,{r['spp']},{threads},{r['seconds']!r},"
                    f"{r['sps']!r},{r['rmse']!r},{r['relmse']!r},{r['mae']!r}\n")


if __name__ == "__main__":
    main()
