#!/usr/bin/env bash
# GUI test of the bezjoin workbench in the real FreeCAD GUI under Xvfb
# (freecad/tests/gui/gui_commands.py: a sketch in a placed Body, each command run
# through FreeCADGui.runCommand on a selection, its form accepted, the parametric
# results checked in model coordinates, screenshots written with saveImage).
#
# Installs what is missing (freecad-python3, xvfb, xauth, Mesa's software OpenGL),
# builds the release library like freecad/run-tests.sh (unless BEZJOIN_LIBRARY names
# one), links the workbench into the Mod folder of a fresh HOME and runs
#   xvfb-run freecad freecad/tests/gui/gui_commands.py
# under a timeout. FreeCAD's exit status says nothing about the macro: the verdict
# is read from the result file the script writes (first line "OK <n> checks").
# Screenshots and the log go to BEZJOIN_GUI_OUTPUT (default /tmp/bezjoin-gui).
# BEZJOIN_GUI_WORKBENCH: the workbench folder to test (default freecad/Bezjoin here).
set -euo pipefail

repository="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repository"
output="${BEZJOIN_GUI_OUTPUT:-/tmp/bezjoin-gui}"
timeout_seconds="${BEZJOIN_GUI_TIMEOUT:-300}"

missing=()
command -v freecad >/dev/null 2>&1 || missing+=(freecad-python3)
command -v xvfb-run >/dev/null 2>&1 || missing+=(xvfb)
command -v xauth >/dev/null 2>&1 || missing+=(xauth)
dpkg -s libgl1-mesa-dri >/dev/null 2>&1 || missing+=(libgl1-mesa-dri)
if [[ ${#missing[@]} -gt 0 ]]; then
    echo "freecad/gui-test.sh: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update
    apt-get install -y --no-install-recommends "${missing[@]}"
fi

if [[ -n "${BEZJOIN_LIBRARY:-}" ]]; then
    library="$BEZJOIN_LIBRARY"
else
    # Always (re)build: cargo does nothing when the library is up to date.
    cargo build --release -p bezjoin-ffi
    library="$repository/target/release/libbezjoin.so"
fi
if [[ ! -f "$library" ]]; then
    echo "freecad/gui-test.sh: no library at $library" >&2
    exit 1
fi

mkdir -p "$output"
result="$output/result.txt"
rm -f "$result" "$output"/*.png
work="$(mktemp -d /tmp/bezjoin-gui-home.XXXXXX)"
trap 'rm -rf "$work"' EXIT
# A fresh user folder: no settings of the real user; the workbench is installed as
# a user would (a link in FreeCAD's user Mod folder).
mod="$work/home/.local/share/FreeCAD/Mod"
mkdir -p "$mod" "$work/runtime"
chmod 700 "$work/runtime"
workbench="${BEZJOIN_GUI_WORKBENCH:-$repository/freecad/Bezjoin}"
ln -s "$workbench" "$mod/Bezjoin"

status=0
env HOME="$work/home" XDG_RUNTIME_DIR="$work/runtime" \
    BEZJOIN_LIBRARY="$library" BEZJOIN_GUI_WORKBENCH="$workbench" \
    BEZJOIN_GUI_OUTPUT="$output" BEZJOIN_GUI_RESULT="$result" \
    QTWEBENGINE_DISABLE_SANDBOX=1 LIBGL_ALWAYS_SOFTWARE=1 \
    timeout --kill-after=10 "$timeout_seconds" \
    xvfb-run -a -s "-screen 0 1280x1024x24" \
    freecad "$repository/freecad/tests/gui/gui_commands.py" >"$output/freecad.log" 2>&1 || status=$?
if [[ $status -eq 124 || $status -eq 137 ]]; then
    echo "freecad/gui-test.sh: FreeCAD did not finish within ${timeout_seconds} s" >&2
fi
if [[ ! -s "$result" ]] || ! head -n 1 "$result" | grep -q '^OK [1-9]'; then
    echo "freecad/gui-test.sh: the GUI test failed (FreeCAD exit status $status):" >&2
    cat "$result" >&2 2>/dev/null || echo "(no result file $result)" >&2
    echo "--- last lines of $output/freecad.log:" >&2
    tail -n 40 "$output/freecad.log" >&2 || true
    exit 1
fi
sed 's/^/freecad\/gui-test.sh: /' "$result"
echo "freecad/gui-test.sh: screenshots in $output"
