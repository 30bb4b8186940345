#!/usr/bin/env bash
# Build and run the bezjoin C++ demo against OpenCASCADE 7.6, then run it again
# under valgrind to show that bezjoin leaks nothing.
#
#   bash cpp-demo/run.sh            (from anywhere; root on a fresh Debian 12 machine)
#
# 1. installs what the machine lacks (apt-get, only when a package is missing);
# 2. cargo build --release -p bezjoin-ffi;
# 3. cmake + make the demo (cpp-demo/build, not committed);
# 4. runs the demo: checks against OCCT (PASS/FAIL rows), timings, STEP file
#    cpp-demo/build/output/bezjoin-demo.step;
# 5. runs it once more (--quick) under valgrind --leak-check=full with
#    OCCT's own leaks suppressed (cpp-demo/valgrind-occt.supp): any other
#    definite/indirect leak or memory error fails;
# 6. proves step 5 can fail: a run that leaks one bezjoin curve on purpose must
#    be reported by valgrind, with bzj_curve_new on the allocation stack.
# Exit status: 0 only if every step passed.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
build="$here/build"
output="$build/output"
jobs="${BEZJOIN_DEMO_JOBS:-2}"

say() { printf '\n== %s\n' "$*"; }

# ---- 1. system packages ------------------------------------------------------
packages=(g++ make cmake libtbb-dev
          libocct-foundation-dev libocct-modeling-data-dev
          libocct-modeling-algorithms-dev libocct-data-exchange-dev
          valgrind)
missing=()
for package in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep "install ok installed" >/dev/null; then
        missing+=("$package")
    fi
done
if ((${#missing[@]})); then
    say "installing: ${missing[*]}"
    if [[ $(id -u) -ne 0 ]]; then
        echo "run.sh: need root to install ${missing[*]} (or install them first)" >&2
        exit 1
    fi
    export DEBIAN_FRONTEND=noninteractive
    apt-get update
    apt-get install -y --no-install-recommends "${missing[@]}"
fi
if ! command -v cargo >/dev/null; then
    echo "run.sh: cargo not found (a Rust toolchain >= 1.85 is needed)" >&2
    exit 1
fi

# ---- 2. the Rust library -----------------------------------------------------
say "cargo build --release -p bezjoin-ffi"
(cd "$root" && cargo build --release -p bezjoin-ffi)
# Where cargo put it: CARGO_TARGET_DIR when set (relative to the root, where
# cargo ran), else the workspace's target/.
target_dir="${CARGO_TARGET_DIR:-target}"
[[ "$target_dir" = /* ]] || target_dir="$root/$target_dir"

# ---- 3. the demo --------------------------------------------------------------
say "building the demo"
mkdir -p "$build"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -U BEZJOIN_LIBRARY \
      -DBEZJOIN_LIBRARY_DIR="$target_dir/release" >"$build/cmake.log" 2>&1 \
    || { cat "$build/cmake.log"; exit 1; }
cmake --build "$build" -j "$jobs"
mkdir -p "$output"
demo="$build/bezjoin_demo"

status=0

# ---- 4. normal run -------------------------------------------------------------
say "demo"
if ! "$demo" --step "$output/bezjoin-demo.step"; then
    echo "run.sh: the demo reported FAIL rows" >&2
    status=1
fi

# ---- 5. leak check -------------------------------------------------------------
valgrind_flags=(--leak-check=full --show-leak-kinds=definite,indirect
                --errors-for-leak-kinds=definite,indirect --error-exitcode=97
                --num-callers=30 --suppressions="$here/valgrind-occt.supp")
say "demo under valgrind (log: $output/valgrind.log)"
set +e
valgrind "${valgrind_flags[@]}" --log-file="$output/valgrind.log" \
    "$demo" --quick --step "$output/bezjoin-demo-valgrind.step" >"$output/valgrind-demo.out" 2>&1
code=$?
set -e
grep -E "definitely lost|indirectly lost|ERROR SUMMARY" "$output/valgrind.log" || true
case $code in
    0) echo "valgrind: no leak and no memory error outside OpenCASCADE" ;;
    97) echo "run.sh: valgrind found a leak or memory error (see $output/valgrind.log)" >&2
        grep -n "bzj_\|bezjoin" "$output/valgrind.log" | head -20 >&2 || true
        status=1 ;;
    *) echo "run.sh: the demo under valgrind exited with $code (see $output/valgrind-demo.out)" >&2
       tail -20 "$output/valgrind-demo.out" >&2
       status=1 ;;
esac

# ---- 6. the leak check can fail ----------------------------------------------
say "leak check self-test: one bezjoin curve leaked on purpose must be caught"
set +e
valgrind "${valgrind_flags[@]}" --log-file="$output/valgrind-selftest.log" \
    "$demo" --leak-on-purpose >/dev/null 2>&1
code=$?
set -e
if [[ $code -eq 97 ]] && grep -q "bzj_curve_new" "$output/valgrind-selftest.log"; then
    echo "valgrind caught the planted leak (allocated in bzj_curve_new): the check works"
else
    echo "run.sh: valgrind did not report the planted bezjoin leak (exit $code): the leak check is blind" >&2
    status=1
fi

say "$([[ $status -eq 0 ]] && echo "cpp-demo: all passed" || echo "cpp-demo: FAILED")"
exit $status
