#!/usr/bin/env bash
# Instructions per call of cases of freecad/bench/bench_conversions.py, repeatable
# whatever the machine load: each case runs under valgrind --tool=callgrind in
# freecadcmd with 200 and 1200 calls; the difference of the totals / 1000 is
# the cost of one call (start-up and warm-up cancel out).
#
#   bash freecad/bench/callgrind.sh [CASE[:NATIVE] ...]
#
# CASE is a function of bench_conversions.py (default: the blend both ways and
# the conversions); ":0" runs it with BEZJOIN_NATIVE=0 (the ctypes route).
# Needs valgrind and the release library (cargo build --release -p bezjoin-ffi).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$ROOT"
export BEZJOIN_LIBRARY="${BEZJOIN_LIBRARY:-$ROOT/target/release/libbezjoin.so}"
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
    cases=(freecad_blend ours_edges_given ours_edges_given:0 ours_from ours_from:0
           ours_to ours_to:0)
fi
WORK="$(mktemp -d /tmp/bezjoin-callgrind.XXXXXX)"
trap 'rm -rf "$WORK"' EXIT
count() {
    PYTHONHASHSEED=0 BEZJOIN_NATIVE="$2" BEZJOIN_CG_CASE="$1" BEZJOIN_CG_N="$3" \
        valgrind --tool=callgrind --callgrind-out-file="$WORK/out" \
        freecadcmd freecad/bench/callgrind_case.py >"$WORK/log" 2>&1
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$WORK/log"
}
printf '%-24s %-7s %14s\n' case route "instr./call"
for entry in "${cases[@]}"; do
    name="${entry%%:*}"
    native=1
    [[ "$entry" == *:0 ]] && native=0
    low="$(count "$name" "$native" 200)"
    high="$(count "$name" "$native" 1200)"
    route=compiled
    [ "$native" = 0 ] && route=ctypes
    printf '%-24s %-7s %14d\n' "$name" "$route" $(( (high - low) / 1000 ))
done
