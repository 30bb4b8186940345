#!/usr/bin/env bash
# Test of scripts/install-freecad.sh on a fresh FreeCAD user folder: install
# into a new HOME (FreeCAD's own user Mod folder, as freecadcmd reports it),
# then, with no BEZJOIN_* variable set, start freecadcmd there and check
# that the workbench, the Python package and the library all come from the
# installed folder and that a blend of two edges works; install again (it
# replaces its own install) and check that a foreign Mod/Bezjoin folder is
# left alone. The first install must carry the compiled fast path
# (bezjoin._native, used by the installed package) whenever a C compiler and
# the headers of FreeCAD's Python are present; the reinstall is made without
# it (BEZJOIN_NATIVE_BUILD=0) and must work through the ctypes route.
# Exits 0 when every check passed. Run by .ci/run.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"

if ! command -v freecadcmd >/dev/null 2>&1; then
    echo "freecad/test-install.sh: freecadcmd missing (freecad/run-tests.sh installs it)" >&2
    exit 1
fi
# cargo and rustup live in the real HOME.
export RUSTUP_HOME="${RUSTUP_HOME:-$HOME/.rustup}"
export CARGO_HOME="${CARGO_HOME:-$HOME/.cargo}"
WORK="$(mktemp -d /tmp/bezjoin-install-test.XXXXXX)"
trap 'rm -rf "$WORK"' EXIT
FAKE_HOME="$WORK/home"
mkdir -p "$FAKE_HOME"

run_install() { env -u BEZJOIN_LIBRARY -u BEZJOIN_PYTHON_PATH HOME="$FAKE_HOME" bash scripts/install-freecad.sh "$@"; }

# Whether the compiled fast path can be built here (the install must then build it).
EXPECT_NATIVE=0
if command -v "${CC:-cc}" >/dev/null 2>&1; then
    PY_INCLUDE="$(freecadcmd -c 'import sysconfig; print("BEZJOIN_INC=" + sysconfig.get_paths()["include"])' 2>/dev/null \
        | sed -n 's/^BEZJOIN_INC=//p' | tail -n 1)" || PY_INCLUDE=""
    if [ -n "$PY_INCLUDE" ] && [ -f "$PY_INCLUDE/Python.h" ]; then
        EXPECT_NATIVE=1
    fi
fi
echo "freecad/test-install.sh: compiled fast path expected: $EXPECT_NATIVE" >&2

run_install
MOD_BEZJOIN="$(find "$FAKE_HOME" -type d -path '*/Mod/Bezjoin' | head -n 1)"
if [ -z "$MOD_BEZJOIN" ] || [ ! -f "$MOD_BEZJOIN/INSTALLED_BY_BEZJOIN" ]; then
    echo "freecad/test-install.sh: no installed Mod/Bezjoin under $FAKE_HOME" >&2
    exit 1
fi

cat >"$WORK/check.py" <<'PY'
import os
import sys
import traceback

import FreeCAD

result = os.environ["BEZJOIN_INSTALL_RESULT"]
try:
    mod = os.path.realpath(os.path.join(FreeCAD.getUserAppDataDir(), "Mod", "Bezjoin"))
    import bezjoin_workbench
    import bezjoin_workbench.operations as operations

    bezjoin = bezjoin_workbench.ensure_bindings_importable()
    where = {
        "workbench": os.path.realpath(bezjoin_workbench.__file__),
        "package": os.path.realpath(bezjoin.__file__),
        "library": os.path.realpath(bezjoin._library.library_path()),
    }
    from bezjoin import _freecad

    import Part  # noqa: E402

    fast = _freecad.native()
    expect_native = os.environ["BEZJOIN_INSTALL_EXPECT_NATIVE"] == "1"
    assert (fast is not None) == expect_native, \
        f"compiled fast path {'missing' if expect_native else 'present'}: {fast!r}"
    if fast is not None:
        where["native"] = os.path.realpath(fast.__file__)
    for name, path in where.items():
        assert path.startswith(mod + os.sep), f"{name} from {path}, not from {mod}"
    p_curve, q_curve = Part.BezierCurve(), Part.BezierCurve()
    p_curve.setPoles([FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 1, 0), FreeCAD.Vector(2, 0, 0)])
    q_curve.setPoles([FreeCAD.Vector(3, 0, 0), FreeCAD.Vector(4, 1, 0), FreeCAD.Vector(5, 0, 0)])
    joined = bezjoin.connect_edges(p_curve.toShape(), 1.0, q_curve.toShape(), 0.0)
    assert joined.StartPoint.distanceToPoint(FreeCAD.Vector(2, 0, 0)) < 1e-12, joined.StartPoint
    assert joined.EndPoint.distanceToPoint(FreeCAD.Vector(3, 0, 0)) < 1e-12, joined.EndPoint

    first = Part.LineSegment(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(10, 0, 0)).toShape()
    second = Part.LineSegment(FreeCAD.Vector(12, 2, 0), FreeCAD.Vector(12, 10, 0)).toShape()
    blend = operations.blend_edges(first, second)
    shape = getattr(blend, "shape", blend)
    start = shape.Vertexes[0].Point if hasattr(shape, "Vertexes") else None
    assert start is not None, f"blend_edges returned {blend!r}"
    assert min(start.distanceToPoint(FreeCAD.Vector(10, 0, 0)),
               start.distanceToPoint(FreeCAD.Vector(12, 2, 0))) < 1e-9, f"blend starts at {start}"
    with open(result, "w") as out:
        out.write("OK " + " ".join(f"{k}={v}" for k, v in where.items()) + "\n")
except Exception:
    with open(result, "w") as out:
        out.write("FAILED\n" + traceback.format_exc())
PY
check() {
    rm -f "$WORK/result"
    env -u BEZJOIN_LIBRARY -u BEZJOIN_PYTHON_PATH -u BEZJOIN_NATIVE HOME="$FAKE_HOME" \
        BEZJOIN_INSTALL_RESULT="$WORK/result" BEZJOIN_INSTALL_EXPECT_NATIVE="$1" \
        freecadcmd "$WORK/check.py" >"$WORK/freecad.log" 2>&1 || true
    if ! grep -q '^OK ' "$WORK/result" 2>/dev/null; then
        echo "freecad/test-install.sh: the installed workbench failed in FreeCAD:" >&2
        cat "$WORK/result" "$WORK/freecad.log" >&2 2>/dev/null || true
        exit 1
    fi
    sed 's/^/freecad\/test-install.sh: /' "$WORK/result" >&2
}
check "$EXPECT_NATIVE"

# A second install replaces the first; this one without the compiled fast path.
echo stale >"$MOD_BEZJOIN/stale-file"
BEZJOIN_NATIVE_BUILD=0 run_install
[ ! -e "$MOD_BEZJOIN/stale-file" ] || { echo "freecad/test-install.sh: reinstall kept a stale file" >&2; exit 1; }
if ls "$MOD_BEZJOIN"/bezjoin/_native*.so >/dev/null 2>&1; then
    echo "freecad/test-install.sh: BEZJOIN_NATIVE_BUILD=0 still installed the compiled module" >&2
    exit 1
fi
check 0

# A folder the script did not install is left alone.
rm -rf "$MOD_BEZJOIN"
mkdir -p "$MOD_BEZJOIN"
echo mine >"$MOD_BEZJOIN/user-file"
if run_install 2>"$WORK/refused.log"; then
    echo "freecad/test-install.sh: a foreign Mod/Bezjoin was replaced" >&2
    exit 1
fi
grep -q "was not installed by this script" "$WORK/refused.log"
[ -f "$MOD_BEZJOIN/user-file" ]
echo "freecad/test-install.sh: OK (install with the compiled fast path: $EXPECT_NATIVE, FreeCAD without BEZJOIN_* variables, reinstall without it, foreign folder kept)" >&2
