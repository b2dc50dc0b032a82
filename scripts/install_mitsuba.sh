#!/usr/bin/env bash
# Idempotent: installs the pinned Mitsuba 3 (and numpy) only if `import mitsuba` fails.
set -euo pipefail
PYTHON="${PYTHON:-python3}"
if "$PYTHON" -c "import mitsuba" >/dev/null 2>&1; then
    echo "mitsuba already installed: $("$PYTHON" -c 'import mitsuba; print(mitsuba.__version__)')"
    exit 0
fi
"$PYTHON" -m pip install "mitsuba==3.9.1" numpy
