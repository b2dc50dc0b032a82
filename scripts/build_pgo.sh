#!/usr/bin/env bash
# Profile-guided build of the `tessera` binary: target/pgo/dist/tessera (the `dist` profile,
# release plus fat LTO, optimised with a profile of the renderer's own hot paths).
#
#   scripts/build_pgo.sh                    for this CPU, as every build is by default
#                                           (`.cargo/config.toml`; the benchmark table's column)
#   TARGET_CPU=x86-64 scripts/build_pgo.sh  a portable x86-64 binary
#
# Steps: (1) an instrumented `dist` build in target/pgo-gen; (2) training renders with it: the
# benchmark scenes at the benchmark's settings (128x128, box filter, both samplers, adaptive) and
# small renders of the other example scenes, so that no scene's code is left cold; (3) the raw
# profiles merged with the toolchain's own llvm-profdata (rustup's `llvm-tools` component,
# installed here if missing: its LLVM must be the compiler's); (4) the `dist` build using the
# profile, in target/pgo; (5) a check that the optimised binary renders the training scenes with
# exactly the instrumented binary's bits (profile guidance moves code, never arithmetic: Rust
# forms no fused multiply-add and reassociates nothing unasked). Exits non-zero if any image
# differs.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
# RUSTFLAGS (set below) replaces the config's flags, so the target CPU is named here again.
FLAGS="-C target-cpu=${TARGET_CPU:-native}"
HOST="$(rustc -vV | sed -n 's/^host: //p')"
PROFDATA="$(rustc --print sysroot)/lib/rustlib/$HOST/bin/llvm-profdata"
if [ ! -x "$PROFDATA" ]; then
    rustup component add llvm-tools
fi
[ -x "$PROFDATA" ] || { echo "error: $PROFDATA not found after installing llvm-tools" >&2; exit 1; }

DATA="$ROOT/target/pgo-data"
rm -rf "$DATA"
mkdir -p "$DATA"
echo "== 1/5 instrumented build (target/pgo-gen)"
RUSTFLAGS="$FLAGS -Cprofile-generate=$DATA" CARGO_TARGET_DIR=target/pgo-gen \
    cargo build --profile dist -p tessera-cli --quiet
# Build scripts and proc macros of step 1 are instrumented too: their profiles are not wanted.
rm -f "$DATA"/*.profraw

SCRATCH="$(mktemp -d)"
trap 'rm -rf "$SCRATCH"' EXIT
# The training set: NAME OUTFILE ARGS... (each also renders in step 5 for the bit check).
train() {
    local bin="$1" tag="$2"
    local i=0
    while read -r scene args; do
        [ -n "$scene" ] || continue
        # shellcheck disable=SC2086
        "$bin" render "scenes/$scene.xml" $args --quiet -o "$SCRATCH/$tag-$i.exr"
        i=$((i + 1))
    done <<'EOF'
cbox -D res=128 -D rfilter=box --spp 64 --sampler zsobol
cbox -D res=128 -D rfilter=box --spp 64 --sampler independent
cbox -D res=128 -D rfilter=box --spp 32 --sampler zsobol --adaptive
cbox -D res=128 -D rfilter=box --spp 32 --sampler zsobol --integrator path+reuse
cbox -D res=128 -D rfilter=box --spp 16 --sampler zsobol --integrator path+reuse --adaptive
veach_mis -D res=128 -D rfilter=box --spp 64 --sampler zsobol
veach_mis -D res=128 -D rfilter=box --spp 64 --sampler independent
veach_mis -D res=128 -D rfilter=box --spp 32 --sampler zsobol --adaptive
veach_mis -D res=128 -D rfilter=box --spp 32 --sampler zsobol --integrator path+reuse
materials -D res=64 --spp 16
envmap -D res=64 --spp 16
cs500_spheres -D res=64 --spp 16
furnace -D res=64 --spp 16
EOF
}
echo "== 2/5 training renders"
train target/pgo-gen/dist/tessera gen
echo "== 3/5 merging $(ls "$DATA"/*.profraw | wc -l) profiles"
"$PROFDATA" merge -o "$DATA/merged.profdata" "$DATA"/*.profraw
echo "== 4/5 profile-guided build (target/pgo)"
RUSTFLAGS="$FLAGS -Cprofile-use=$DATA/merged.profdata" CARGO_TARGET_DIR=target/pgo \
    cargo build --profile dist -p tessera-cli --quiet
echo "== 5/5 same image bits as the instrumented build"
train target/pgo/dist/tessera pgo
for f in "$SCRATCH"/gen-*.exr; do
    g="$SCRATCH/pgo-${f##*/gen-}"
    cmp -s "$f" "$g" || { echo "error: ${f##*/} differs between the two builds" >&2; exit 1; }
done
echo "target/pgo/dist/tessera (RUSTFLAGS: ${FLAGS:-none}); same bits on $(ls "$SCRATCH"/gen-*.exr | wc -l) renders"
