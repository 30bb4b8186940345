#!/usr/bin/env bash
# FreeCAD-side tests of the bezjoin bindings and workbench, run headless by freecadcmd.
# Installs FreeCAD (Debian's freecad-python3) if missing, builds the release library
# (cargo build --release -p bezjoin-ffi; a no-op when it is up to date) unless
# BEZJOIN_LIBRARY names one, and fails unless every test passed.
# freecadcmd exits 0 even when a script raises, so the outcome is read from both the
# exit status and a marker file the test runner writes only on success.
set -euo pipefail

repository="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repository"

if ! command -v freecadcmd >/dev/null 2>&1; then
    echo "freecad/run-tests.sh: installing freecad-python3"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update
    apt-get install -y --no-install-recommends freecad-python3
fi

if [[ -n "${BEZJOIN_LIBRARY:-}" ]]; then
    library="$BEZJOIN_LIBRARY"
else
    # Always (re)build: cargo does nothing when the library is up to date.
    cargo build --release -p bezjoin-ffi
    library="$repository/target/release/libbezjoin.so"
fi
if [[ ! -f "$library" ]]; then
    echo "freecad/run-tests.sh: no library at $library" >&2
    exit 1
fi
export BEZJOIN_LIBRARY="$library"

marker="$(mktemp)"
rm -f "$marker"
trap 'rm -f "$marker"' EXIT
status=0
BEZJOIN_FREECAD_MARKER="$marker" freecadcmd freecad/tests/run_in_freecad.py || status=$?
if [[ $status -ne 0 ]]; then
    echo "freecad/run-tests.sh: freecadcmd exited with $status" >&2
    exit 1
fi
if [[ ! -s "$marker" ]] || ! grep -q '^OK [1-9]' "$marker"; then
    echo "freecad/run-tests.sh: the test runner did not report success" >&2
    exit 1
fi
echo "freecad/run-tests.sh: $(cat "$marker")"
