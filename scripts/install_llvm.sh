#!/usr/bin/env bash
# Installs an LLVM shared library that Mitsuba 3's LLVM variants (llvm_ad_rgb, ...) can drive.
#
# The pip drjit 1.5.0 (Mitsuba 3.9.1) emits the llvm.minimum intrinsic: with Debian 12's LLVM 15
# its kernels fail to compile ("LLVM ERROR: Cannot select: ... f32 = fminimum"), LLVM 14 is
# refused outright ("the LLVM backend is inactive"); Debian 12's libllvm19 (19.1.7) works. Dr.Jit finds it by itself once installed;
# scripts/mitsuba_bench.py also sets DRJIT_LIBLLVM_PATH to it unless the variable is set.
# Idempotent: does nothing if the library is already there. Needs root (apt-get).
set -euo pipefail
LIB=/usr/lib/x86_64-linux-gnu/libLLVM-19.so
if [ ! -e "$LIB" ]; then
    if ! dpkg -s libllvm19 >/dev/null 2>&1; then
        apt-get update -q
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q libllvm19
    fi
fi
[ -e "$LIB" ] || { echo "error: $LIB not found after installing libllvm19" >&2; exit 1; }
echo "LLVM for Dr.Jit: $LIB"
echo "  export DRJIT_LIBLLVM_PATH=$LIB"
