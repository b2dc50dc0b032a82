#!/usr/bin/env bash
# Renders the Wakame assignment's scenes that have reference images committed in its
# repository (dragonmeteor/wakame), read with Nori's conventions and with Wakame's, and prints
# each render's relMSE against Wakame's own reference. Wakame's images are the mirror image of
# Nori's, so only `--dialect wakame` should agree.
# The repository's files carry no licence to copy them, so they are not in Tessera's tree and
# this is not part of the test suite; it needs a local git snapshot of the repository.
#
#   scripts/wakame_refs.sh WAKAME_GIT_DIR [TESSERA_BINARY] [SPP]
set -euo pipefail
git_dir=${1:?usage: scripts/wakame_refs.sh WAKAME_GIT_DIR [TESSERA_BINARY] [SPP]}
bin=$(realpath "${2:-target/release/tessera}")
spp=${3:-64}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The scenes, their meshes and the references (files absent from a snapshot are skipped).
git --git-dir="$git_dir" ls-tree -r HEAD --name-only data/pa1 data/pa2 | while read -r f; do
  mkdir -p "$work/$(dirname "$f")"
  git --git-dir="$git_dir" show "HEAD:$f" >"$work/$f" 2>/dev/null || rm -f "$work/$f"
done
cd "$work/data"
printf '%-34s %14s %14s\n' scene "relMSE nori" "relMSE wakame"
for ref in pa2/*/ref/*.pfm; do
  [ -f "$ref" ] || continue
  dir=$(dirname "$(dirname "$ref")")
  # sphere_side_mis_128spp.pfm -> sphere_side_mis.xml
  scene="$dir/$(basename "$ref" .pfm | sed -E 's/_[0-9]+spp.*$//').xml"
  [ -f "$scene" ] || continue
  row=()
  for dialect in nori wakame; do
    if "$bin" render "$scene" -o "$work/out.pfm" --spp "$spp" --quiet --dialect "$dialect" 2>/dev/null; then
      row+=("$("$bin" compare "$work/out.pfm" "$ref" --json | python3 -c 'import json,sys; print("%.3e" % json.load(sys.stdin)["relmse"])')")
    else
      row+=(error)
    fi
  done
  printf '%-34s %14s %14s\n' "$scene" "${row[0]}" "${row[1]}"
done
