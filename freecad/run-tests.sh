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

# The optional compiled fast path (bezjoin/_native.c) against the headers of
# FreeCAD's Python: Debian's python3-dev is installed when missing (as
# freecad-python3 above). The tests compare it with the ctypes route, in the
# same process; BEZJOIN_EXPECT_NATIVE=1 makes a module that was built but is
# not used a failure. BEZJOIN_NATIVE_BUILD=0: test the ctypes route alone.
if [[ "${BEZJOIN_NATIVE_BUILD:-1}" != "0" ]]; then
    include="$(freecadcmd -c 'import sysconfig; print("BEZJOIN_INC=" + sysconfig.get_paths()["include"])' 2>/dev/null \
        | sed -n 's/^BEZJOIN_INC=//p' | tail -n 1)" || include=""
    if [[ -n "$include" && ! -f "$include/Python.h" ]] && command -v apt-get >/dev/null 2>&1 \
            && [[ "$(id -u)" == 0 ]]; then
        echo "freecad/run-tests.sh: installing python3-dev (Python.h for the compiled fast path)"
        export DEBIAN_FRONTEND=noninteractive
        apt-get update
        apt-get install -y --no-install-recommends python3-dev
    fi
    native_status=0
    bash bindings/python/build-native.sh || native_status=$?
    if [[ $native_status -eq 0 ]]; then
        export BEZJOIN_EXPECT_NATIVE=1
    elif [[ $native_status -ne 3 ]]; then
        echo "freecad/run-tests.sh: building the compiled fast path failed" >&2
        exit 1
    fi
else
    rm -f bindings/python/bezjoin/_native*.so
fi

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
