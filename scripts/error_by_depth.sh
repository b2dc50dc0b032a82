#!/usr/bin/env bash
# Where a scene's error sits by path depth: for each max_depth and sampler, renders seeds 0-3
# and prints the relMSE between the images of seeds 0 and 1 and of seeds 2 and 3, and their
# mean. Two independent renders differ by about twice the variance part of the error, so no
# reference is needed, and the rows for growing max_depth show what each added bounce costs.
#
#   scripts/error_by_depth.sh [SCENE [SPP [RES [DEPTHS [SAMPLERS]]]]]
#       defaults: scenes/cbox.xml, 64, 128, "2 3 4 8", "independent zsobol"
#
# Renders use the box filter and 2 threads. TESSERA=path picks the binary (default
# target/dist/tessera, from `cargo build --profile dist -p tessera`); EXTRA="-D rr_depth=8"
# passes more options to every render. Images go to a temporary directory that is removed.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
SCENE="${1:-scenes/cbox.xml}"
SPP="${2:-64}"
RES="${3:-128}"
DEPTHS="${4:-2 3 4 8}"
SAMPLERS="${5:-independent zsobol}"
TESSERA="${TESSERA:-target/dist/tessera}"
EXTRA="${EXTRA:-}"
[ -x "$TESSERA" ] || { echo "error: $TESSERA not found (cargo build --profile dist -p tessera)" >&2; exit 2; }
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
relmse() {
    "$TESSERA" compare "$1" "$2" --json | python3 -c 'import json, sys; print("%.3e" % json.load(sys.stdin)["relmse"])'
}
printf '%-12s %9s %11s %11s %11s\n' sampler max_depth "seeds 0/1" "seeds 2/3" mean
for sampler in $SAMPLERS; do
    for depth in $DEPTHS; do
        for seed in 0 1 2 3; do
            # shellcheck disable=SC2086
            "$TESSERA" render "$SCENE" -D res="$RES" -D spp="$SPP" -D rfilter=box \
                -D max_depth="$depth" $EXTRA --sampler "$sampler" --seed "$seed" --threads 2 \
                -o "$TMP/$seed.exr" --quiet
        done
        a="$(relmse "$TMP/0.exr" "$TMP/1.exr")"
        b="$(relmse "$TMP/2.exr" "$TMP/3.exr")"
        mean="$(python3 -c "print('%.3e' % (($a + $b) / 2))")"
        printf '%-12s %9s %11s %11s %11s\n' "$sampler" "$depth" "$a" "$b" "$mean"
    done
done
