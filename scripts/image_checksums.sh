#!/usr/bin/env bash
# Prints one line per render, "<sha256>  <scene> <integrator> <sampler>", over every example
# scene, each integrator and both samplers (small images, few samples), then the same for the
# output of the scene test files.
# Used to show that a change to the code's structure leaves every image's bits as they were:
# run it before and after (the old side built in a git worktree) and diff the outputs.
#
#   scripts/image_checksums.sh [TESSERA_BINARY] > sums.txt
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/tessera}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
integrators="path path_half path_ems path_mats path+reuse direct direct_ems direct_mats direct_mis"
for scene in scenes/*.xml; do
  for integ in $integrators; do
    for sampler in independent zsobol; do
      img="$out/img.pfm"
      if "$bin" render "$scene" -o "$img" --quiet --threads 2 --spp 16 --resolution-scale 0.25 \
        --integrator "$integ" --sampler "$sampler" 2>"$out/err"; then
        sum=$(sha256sum "$img" | cut -d' ' -f1)
      else
        sum="error:$(head -c 120 "$out/err" | tr '\n' ' ')"
      fi
      echo "$sum  $scene $integ $sampler"
    done
  done
  # Adaptive sampling takes other code paths.
  "$bin" render "$scene" -o "$out/a.pfm" --quiet --threads 2 --spp 16 --resolution-scale 0.25 \
    --sampler zsobol --adaptive 2>/dev/null && echo "$(sha256sum "$out/a.pfm" | cut -d' ' -f1)  $scene adaptive zsobol"
done
for t in tests/scenes/*.xml; do
  echo "$("$bin" test "$t" 2>&1 | sha256sum | cut -d' ' -f1)  $t test"
done
