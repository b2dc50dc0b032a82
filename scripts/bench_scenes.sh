#!/usr/bin/env bash
# Error against time, Tessera against Mitsuba 3, on the benchmark scenes at 128x128 (box filter,
# the scene files' max_depth 8): writes docs/bench/NAME.csv (Tessera's rows, then Mitsuba's)
# and docs/bench/NAME.png, and prints each curve's time to relMSE 0.01, 1e-3, 3e-4 and 1e-4
# (TARGETS=a,b,.. to choose) with its ratio to Mitsuba's (llvm_ad_rgb, if measured).
#
#   scripts/bench_scenes.sh [THREADS [MAX_SECONDS [OUTDIR]]]      (defaults: 2, 60, docs/bench)
#
# Needs the dist build (cargo build --profile dist -p tessera-cli; release plus fat LTO), Mitsuba 3 (scripts/install_mitsuba.sh) and, for
# llvm_ad_rgb, scripts/install_llvm.sh. Set VARIANTS=scalar_rgb to skip the LLVM variant,
# SAMPLERS=zsobol to measure only Tessera's zsobol curve, and SEEDS=N to make every curve (both
# renderers) the wave-by-wave mean of N seeds (N times the time; MAX_SECONDS applies per seed).
# REPEATS=N renders every curve (both renderers) N times and keeps each wave's least time.
# ADAPTIVE=1 adds Tessera's adaptive-sampling curves (`--adaptive`), ADAPTIVE=only measures only those.
# FRESH=1 renders each of Tessera's waves afresh (`--fresh`: the sampler set up for that wave's
# samples, the wave timed alone), as Mitsuba's script does.
# INTEGRATORS=a,b (default path_mis) names Tessera's curves, e.g. INTEGRATORS=path_mis,path_mis+reuse.
# The default build is tuned to this CPU, as Mitsuba's LLVM variant's kernels are (same image
# bits as a portable one); profile-guided on top (same bits; see scripts/build_pgo.sh):
#   scripts/build_pgo.sh && TESSERA=target/pgo/dist/tessera scripts/bench_scenes.sh 2 30
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
THREADS="${1:-2}"
MAX="${2:-60}"
OUT="${3:-docs/bench}"
PYTHON="${PYTHON:-python3}"
VARIANTS="${VARIANTS:-scalar_rgb,llvm_ad_rgb}"
SAMPLERS="${SAMPLERS:-independent,zsobol}"
SEEDS="${SEEDS:-1}"
INTEGRATORS="${INTEGRATORS:-path_mis}"
REPEATS="${REPEATS:-1}"
TESSERA="${TESSERA:-target/dist/tessera}"
ADAPTIVE_FLAG=()
case "${ADAPTIVE:-}" in
    1) ADAPTIVE_FLAG=(--adaptive) ;;
    only) ADAPTIVE_FLAG=(--adaptive-only) ;;
esac
FRESH_FLAG=(--waves)
if [ "${FRESH:-}" = 1 ]; then FRESH_FLAG=(--fresh); fi
mkdir -p "$OUT"
for NAME in cbox veach_mis; do
    REF="scenes/refs/${NAME}_128x128_mitsuba.exr"
    "$TESSERA" bench "scenes/$NAME.xml" -D res=128 -D rfilter=box --reference "$REF" \
        --integrators "$INTEGRATORS" --sampler "$SAMPLERS" --seeds "$SEEDS" --repeats "$REPEATS" --threads "$THREADS" \
        --max-seconds "$MAX" ${ADAPTIVE_FLAG[@]+"${ADAPTIVE_FLAG[@]}"} \
        ${FRESH_FLAG[@]+"${FRESH_FLAG[@]}"} -o "$OUT/$NAME.csv"
    "$PYTHON" scripts/mitsuba_bench.py "scenes/$NAME.xml" -D res=128 -D rfilter=box \
        --reference "$REF" --variant "$VARIANTS" --seeds "$SEEDS" --repeats "$REPEATS" --threads "$THREADS" --max-seconds "$MAX" \
        -o "$OUT/$NAME.csv"
    # Each curve's time to the error levels of docs/performance.md, and its ratio to Mitsuba's fastest
    # variant measured (llvm_ad_rgb when it is among VARIANTS, else the first).
    case ",$VARIANTS," in
        *,llvm_ad_rgb,*) PEER="mitsuba-llvm_ad_rgb:path" ;;
        *) PEER="mitsuba-${VARIANTS%%,*}:path" ;;
    esac
    "$TESSERA" bench --plot-only "$OUT/$NAME.csv" --plot "$OUT/$NAME.png" \
        --title "$NAME.xml, 128x128, max_depth 8, $THREADS threads" \
        --target-relmse "${TARGETS:-0.01,0.001,0.0003,0.0001}" --ratio-to "$PEER"
done
