#!/usr/bin/env bash
# The real-browser check of `tessera view` (not part of .ci/run: it installs a browser).
# Installs Debian's chromium and chromium-driver and Python's selenium when absent (no browser is
# downloaded by any other means), starts `tessera view` on the Cornell box on a free port, and runs
# scripts/view_browser_check.py: headless Chromium waits for the image, checks it shows the scene,
# orbits with a drag, recolours the floor, and saves docs/images/view.png.
# Usage: scripts/view_browser_check.sh [path/to/tessera]   (default: target/release/tessera)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-target/release/tessera}
[ -x "$BIN" ] || { echo "no $BIN: cargo build --release first" >&2; exit 1; }
if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver >/dev/null
fi
python3 -c "import selenium" 2>/dev/null || pip install -q selenium
WORK=$(mktemp -d)
cleanup() { [ -n "${VIEW_PID:-}" ] && kill "$VIEW_PID" 2>/dev/null; rm -rf "$WORK"; }
trap cleanup EXIT
"$BIN" view scenes/cbox.xml -D res=256 --port 0 --threads 2 >"$WORK/out" 2>"$WORK/err" &
VIEW_PID=$!
for _ in $(seq 100); do grep -q http "$WORK/out" && break; sleep 0.1; done
URL=$(grep -o 'http://[^ ]*' "$WORK/out") || { cat "$WORK/err" >&2; exit 1; }
echo "tessera view at $URL"
python3 scripts/view_browser_check.py "$URL" "$WORK/profile" docs/images/view.png
