#!/usr/bin/env bash
# Install the bezjoin workbench into FreeCAD in one command:
#
#   bash scripts/install-freecad.sh [MOD_FOLDER]
#
# Builds the release library (cargo build --release -p bezjoin-ffi) and
# installs a self-contained copy of the workbench as MOD_FOLDER/Bezjoin:
#
#   Bezjoin/Init.py, InitGui.py, bezjoin_workbench/   (freecad/Bezjoin)
#   Bezjoin/bezjoin/                                  (bindings/python/bezjoin)
#   Bezjoin/bezjoin/libbezjoin.so                     (the library, found next
#                                                      to the package)
#   Bezjoin/bezjoin/_native.<python suffix>.so        (the compiled fast path of
#                                                      the FreeCAD conversions, when
#                                                      a C compiler and the headers of
#                                                      FreeCAD's Python are present)
#   Bezjoin/INSTALLED_BY_BEZJOIN                      (version and source)
#
# No environment variable is needed afterwards: the workbench finds the
# package in its own folder and the package finds the library inside itself.
# MOD_FOLDER defaults to FreeCAD's user Mod folder as FreeCAD reports it
# (FreeCAD.getUserAppDataDir() + "Mod", asked through freecadcmd), else
# ~/.local/share/FreeCAD/Mod. A previous install (or the developer's
# symbolic link) at MOD_FOLDER/Bezjoin is replaced; any other folder of
# that name is left alone and the script stops.
#
# The compiled fast path (bindings/python/build-native.sh) is optional: without
# a C compiler or Python.h (Debian: apt-get install gcc python3-dev) the
# script says so and installs the package without it (its ctypes route gives
# the same results, slower). BEZJOIN_NATIVE_BUILD=0 skips it on purpose.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"

if [ $# -gt 1 ]; then
    echo "usage: $0 [MOD_FOLDER]" >&2
    exit 2
fi
if [ $# -eq 1 ]; then
    MOD="$1"
else
    MOD=""
    if command -v freecadcmd >/dev/null 2>&1; then
        # freecadcmd prints its banner too: keep the one marked line.
        MOD="$(freecadcmd -c 'import FreeCAD, os; print("BEZJOIN_MOD=" + os.path.join(FreeCAD.getUserAppDataDir(), "Mod"))' 2>/dev/null \
            | sed -n 's/^BEZJOIN_MOD=//p' | tail -n 1)" || MOD=""
    fi
    MOD="${MOD:-$HOME/.local/share/FreeCAD/Mod}"
fi
MOD="$(realpath -m "$MOD")"
TARGET="$MOD/Bezjoin"
MARKER="INSTALLED_BY_BEZJOIN"

echo "install-freecad.sh: cargo build --release -p bezjoin-ffi" >&2
cargo build --release -p bezjoin-ffi
TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
LIBRARY="$TARGET_DIR/release/libbezjoin.so"
if [ ! -f "$LIBRARY" ]; then
    echo "install-freecad.sh: no library at $LIBRARY after the build" >&2
    exit 1
fi

if [ -L "$TARGET" ]; then
    rm "$TARGET"
elif [ -e "$TARGET" ]; then
    if [ ! -f "$TARGET/$MARKER" ]; then
        echo "install-freecad.sh: $TARGET exists and was not installed by this script; move it away first" >&2
        exit 1
    fi
    rm -rf "$TARGET"
fi

mkdir -p "$MOD"
STAGE="$(mktemp -d "$MOD/.Bezjoin.XXXXXX")"
trap 'rm -rf "$STAGE"' EXIT
cp -R freecad/Bezjoin/. "$STAGE/"
cp -R bindings/python/bezjoin "$STAGE/bezjoin"
cp "$LIBRARY" "$STAGE/bezjoin/libbezjoin.so"
find "$STAGE" -name '__pycache__' -type d -prune -exec rm -rf {} +
# A module built in the source tree may be for another Python: build afresh.
rm -f "$STAGE"/bezjoin/_native*.so
NATIVE="not built"
if [ "${BEZJOIN_NATIVE_BUILD:-1}" = "0" ]; then
    NATIVE="not built (BEZJOIN_NATIVE_BUILD=0)"
    echo "install-freecad.sh: the compiled fast path is not built (BEZJOIN_NATIVE_BUILD=0)" >&2
else
    native_status=0
    bash bindings/python/build-native.sh "$STAGE/bezjoin" || native_status=$?
    if [ "$native_status" -eq 0 ]; then
        NATIVE="built"
    elif [ "$native_status" -eq 3 ]; then
        NATIVE="not built (no C compiler or Python headers)"
        echo "install-freecad.sh: installing without the compiled fast path (the ctypes route is used: same results, slower)" >&2
    else
        # Another Python may lack what the module uses: the package still works.
        NATIVE="not built (the build failed, see above)"
        echo "install-freecad.sh: building the compiled fast path failed; installing without it (the ctypes route is used: same results, slower)" >&2
    fi
fi
VERSION="$(sed -n 's/^version = "\(.*\)"$/\1/p' Cargo.toml | head -n 1)"
COMMIT="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
printf 'bezjoin %s (commit %s), installed by scripts/install-freecad.sh from %s\ncompiled fast path: %s\n' \
    "${VERSION:-unknown}" "$COMMIT" "$ROOT" "$NATIVE" >"$STAGE/$MARKER"
chmod -R u+rwX,go+rX "$STAGE"
mv "$STAGE" "$TARGET"
trap - EXIT
echo "install-freecad.sh: installed the Bezjoin workbench in $TARGET (compiled fast path: $NATIVE; restart FreeCAD)" >&2
