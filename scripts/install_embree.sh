#!/usr/bin/env bash
# Idempotent: installs Embree 3 from Debian (libembree-dev, 3.13.5 on Debian 12) for the
# optional comparison bench `cargo bench -p tessera-benches --features embree --bench embree`.
# Tessera itself never links Embree; CI does not need it.
set -euo pipefail
if [ -e /usr/include/embree3/rtcore.h ] && ldconfig -p | grep -q libembree3; then
    echo "libembree-dev already installed"
    exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update
$SUDO apt-get install -y libembree-dev
