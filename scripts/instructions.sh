#!/usr/bin/env bash
# Instructions a render takes, counted by callgrind, for two or more builds of tessera: the
# measure this machine's wall clock cannot resolve (its speed moves by 10-20% between runs
# minutes apart, so a change of a few percent in time is noise, while the instruction count of
# the same command is the same on every run). Also says whether the builds' images have the
# same bits.
#
#   scripts/instructions.sh SCENE "RENDER ARGS" BIN...
#   scripts/instructions.sh scenes/materials.xml "-D res=128 -D spp=16" /tmp/old/tessera target/dist/tessera
#
# Each build renders SCENE with RENDER ARGS on one thread (`--threads 1 -q`), scene load
# included, under `valgrind --tool=callgrind`; two builds run at a time (callgrind is single
# threaded and about fifty times slower than the render). Prints each build's count, its ratio
# to the first build's, and whether its image equals the first build's bit for bit. Builds to
# compare should share a profile (`--profile dist`, say), and on a CPU with AVX-512 be built for
# one without (`RUSTFLAGS="-C target-cpu=x86-64-v3"`: valgrind cannot run AVX-512); line tables
# (`CARGO_PROFILE_DIST_DEBUG=line-tables-only`) make `callgrind_annotate` name the lines.
# Installs valgrind from Debian when it is missing.
set -euo pipefail
if [ $# -lt 3 ]; then
    sed -n 's/^#   //p' "$0" >&2
    exit 2
fi
scene=$1; shift
args=$1; shift
if ! command -v valgrind > /dev/null; then
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update
    $SUDO apt-get install -y valgrind
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {
    local k=$1 bin=$2
    # shellcheck disable=SC2086
    valgrind --tool=callgrind --callgrind-out-file="$out/cg.$k" "$bin" render "$scene" $args \
        --threads 1 -q -o "$out/img.$k.pfm" > "$out/log.$k" 2>&1 || {
        echo "$bin failed:" >&2
        tail -5 "$out/log.$k" >&2
        exit 1
    }
}
k=0
for bin in "$@"; do
    run $k "$bin" &
    k=$((k + 1))
    if [ $((k % 2)) -eq 0 ]; then wait; fi
done
wait
first=""
k=0
for bin in "$@"; do
    if [ ! -s "$out/img.$k.pfm" ]; then
        # Valgrind stops a program at an instruction it cannot decode (3.19: AVX-512) with
        # SIGILL and no error from the program: a build for a CPU with AVX-512 must be made
        # for an older one to be counted.
        echo "$bin wrote no image under valgrind:" >&2
        grep -m1 -E "unhandled instruction|SIGILL" "$out/log.$k" >&2 || tail -3 "$out/log.$k" >&2
        echo "(on an AVX-512 CPU, build with RUSTFLAGS=\"-C target-cpu=x86-64-v3\")" >&2
        exit 1
    fi
    n=$(sed -n 's/.*Collected : \([0-9]*\)/\1/p' "$out/log.$k")
    if [ -z "$first" ]; then
        first=$n
        same="(reference)"
    elif cmp -s "$out/img.0.pfm" "$out/img.$k.pfm"; then
        same="same bits"
    else
        same="DIFFERENT bits"
    fi
    awk -v n="$n" -v f="$first" -v b="$bin" -v s="$same" \
        'BEGIN { printf "%-40s %15.0f instructions  %.4f  %s\n", b, n, n / f, s }'
    k=$((k + 1))
done
