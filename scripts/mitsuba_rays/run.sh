#!/bin/bash
# Counts the rays Mitsuba 3 casts for a scene: per kind (closest hit, any hit), packet width,
# lanes in use, and the time spent inside Embree's calls, by preloading shim.c into a Mitsuba
# render (scripts/install_mitsuba.sh; llvm_ad_rgb also needs scripts/install_llvm.sh).
#
#   scripts/mitsuba_rays/run.sh SCENE.xml [VARIANT [THREADS]] [-D name=value ...]
#   RAYDUMP=/tmp/rays scripts/mitsuba_rays/run.sh ...   # also records every 16-wide packet
#
# Example: cbox at 128x128, 256 spp, max_depth 8, one thread:
#   scripts/mitsuba_rays/run.sh scenes/cbox.xml llvm_ad_rgb 1 -D res=128 -D spp=256 -D rfilter=box
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
scene=$1; shift
variant=llvm_ad_rgb; threads=1
if [[ $# -gt 0 && $1 != -D ]]; then variant=$1; shift; fi
if [[ $# -gt 0 && $1 != -D ]]; then threads=$1; shift; fi
mitsuba_dir=$(python3 -c 'import mitsuba, os; print(os.path.dirname(mitsuba.__file__))')
export MITSUBA_EMBREE="$mitsuba_dir/libembree3.so"
if [[ -z ${DRJIT_LIBLLVM_PATH:-} && -e /usr/lib/x86_64-linux-gnu/libLLVM-19.so ]]; then
    export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so
fi
build=$(mktemp -d)
trap 'rm -rf "$build"' EXIT
cc -O2 -shared -fPIC "$here/shim.c" -o "$build/shim.so" -ldl
LD_PRELOAD="$build/shim.so" python3 "$here/render.py" "$scene" "$variant" "$threads" "$@"
