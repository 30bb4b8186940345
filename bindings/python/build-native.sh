#!/usr/bin/env bash
# Build the optional compiled fast path of the FreeCAD conversions,
# bezjoin/_native.c, as bezjoin/_native<EXT_SUFFIX> next to the package's
# Python files (or in OUTPUT_FOLDER):
#
#   bash bindings/python/build-native.sh [OUTPUT_FOLDER]
#
# It is built against the headers of the Python FreeCAD runs (asked through
# freecadcmd: sysconfig's include folder and extension suffix), else of
# BEZJOIN_NATIVE_PYTHON (a Python executable), else of python3. It does not
# link libbezjoin (the package hands it the loaded library's functions).
# Exit status 0: built; 3: not built because a C compiler or Python.h is
# missing (the message says which; the package then uses its ctypes route);
# anything else: the build failed.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
OUTPUT="${1:-$HERE/bezjoin}"

CC="${CC:-cc}"
if ! command -v "$CC" >/dev/null 2>&1; then
    echo "build-native.sh: no C compiler ($CC); the compiled fast path is not built" >&2
    exit 3
fi

QUERY='import sysconfig; print("BEZJOIN_PY=" + sysconfig.get_paths()["include"] + "|" + sysconfig.get_config_var("EXT_SUFFIX"))'
answer=""
if [ -n "${BEZJOIN_NATIVE_PYTHON:-}" ]; then
    answer="$("$BEZJOIN_NATIVE_PYTHON" -c "$QUERY" 2>/dev/null | sed -n 's/^BEZJOIN_PY=//p' | tail -n 1)" || answer=""
    source="$BEZJOIN_NATIVE_PYTHON"
elif command -v freecadcmd >/dev/null 2>&1; then
    # freecadcmd prints its banner too: keep the one marked line.
    answer="$(freecadcmd -c "$QUERY" 2>/dev/null | sed -n 's/^BEZJOIN_PY=//p' | tail -n 1)" || answer=""
    source="freecadcmd"
else
    answer="$(python3 -c "$QUERY" 2>/dev/null | sed -n 's/^BEZJOIN_PY=//p' | tail -n 1)" || answer=""
    source="python3"
fi
if [ -z "$answer" ]; then
    echo "build-native.sh: could not ask $source for its Python include folder; the compiled fast path is not built" >&2
    exit 3
fi
INCLUDE="${answer%%|*}"
SUFFIX="${answer#*|}"
if [ ! -f "$INCLUDE/Python.h" ]; then
    echo "build-native.sh: no Python.h in $INCLUDE (the Python of $source; on Debian: apt-get install python3-dev); the compiled fast path is not built" >&2
    exit 3
fi

mkdir -p "$OUTPUT"
TARGET="$OUTPUT/_native$SUFFIX"
TEMPORARY="$(mktemp "$OUTPUT/._native.XXXXXX")"
trap 'rm -f "$TEMPORARY"' EXIT
"$CC" -O2 -fPIC -shared -std=c11 -Wall -Wextra -Werror -fvisibility=hidden \
    -I"$INCLUDE" -I"$ROOT/include" "$HERE/bezjoin/_native.c" -o "$TEMPORARY"
mv "$TEMPORARY" "$TARGET"
trap - EXIT
echo "build-native.sh: built $TARGET (Python of $source, $INCLUDE)" >&2
