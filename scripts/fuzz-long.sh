#!/usr/bin/env bash
# Exploration outside CI: every fuzz target (or the ones named) with a RANDOM
# libFuzzer seed, for a number of executions (default 10^7) or a time, with a
# corpus that persists between runs in fuzz/corpus/<target>/ (git-ignored)
# and starts from the committed seeds. Every run appends a line to
# fuzz/long-runs.tsv (git-ignored): date, target, seed, executions, seconds,
# result. A finding's input is copied to fuzz/artifacts/; the script goes on
# with the next target and exits 1 at the end if anything was found. Put a
# fixed finding's input into fuzz/regressions/ and fuzz/seeds/<target>/ so
# that CI (scripts/fuzz-short.sh) replays it from then on.
#
#   scripts/fuzz-long.sh [--runs N] [--seconds S] [--jobs J] [TARGET...]
# --runs N     executions per target (default 10000000; -1: no limit)
# --seconds S  stop a target after S seconds as well (default: no limit)
# --jobs J     libFuzzer worker processes per target (-fork=J; default 1)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
RUNS=10000000
SECONDS_LIMIT=0
JOBS=1
targets=()
while [ $# -gt 0 ]; do
    case "$1" in
        --runs) RUNS="$2"; shift 2 ;;
        --seconds) SECONDS_LIMIT="$2"; shift 2 ;;
        --jobs) JOBS="$2"; shift 2 ;;
        -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
        *) targets+=("$1"); shift ;;
    esac
done

bash scripts/fuzz-tools.sh
if [ "${#targets[@]}" -eq 0 ]; then
    mapfile -t targets < <(cargo +nightly fuzz list)
fi
cargo +nightly fuzz build

LOG=fuzz/long-runs.tsv
[ -f "$LOG" ] || printf 'date\ttarget\tseed\texecutions\tseconds\tresult\n' >"$LOG"
found=0
for t in "${targets[@]}"; do
    corpus="fuzz/corpus/$t"
    mkdir -p "$corpus" fuzz/artifacts
    seed="$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')"
    out="$(mktemp /tmp/bezjoin-fuzz-long.XXXXXX)"
    # ASan's RSS creeps up over long runs with no live heap behind it
    # (finding F7, docs/reliability.md): allow 8 GB of RSS, but still stop
    # any single allocation above 2 GB.
    args=(-seed="$seed" -runs="$RUNS" -timeout=10 -rss_limit_mb=8192 -malloc_limit_mb=2048
          -print_final_stats=1
          -artifact_prefix="fuzz/artifacts/$t-")
    [ "$SECONDS_LIMIT" != 0 ] && args+=(-max_total_time="$SECONDS_LIMIT")
    [ "$JOBS" != 1 ] && args+=(-fork="$JOBS" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
    echo "--- fuzz-long $t: seed $seed, runs $RUNS, seconds ${SECONDS_LIMIT/#0/unlimited}, jobs $JOBS" >&2
    start=$SECONDS
    if cargo +nightly fuzz run "$t" "$corpus" "fuzz/seeds/$t" -- "${args[@]}" >"$out" 2>&1; then
        result=ok
    else
        result=FINDING
    fi
    # -fork mode prints no final stats: take the last status line's count.
    execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$out" | tail -n 1)"
    [ -n "$execs" ] || execs="$(grep -oE '^#[0-9]+' "$out" | tail -n 1 | tr -d '#')"
    if [ "$JOBS" != 1 ] && grep -E 'crash-|timeout-|oom-' "$out" | grep -v 'INFO' >/dev/null; then
        result=FINDING
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$t" "$seed" "${execs:-0}" \
        "$((SECONDS - start))" "$result" | tee -a "$LOG" >&2
    if [ "$result" != ok ]; then
        found=1
        tail -n 40 "$out" >&2
        cp "$out" "fuzz/artifacts/$t-seed$seed.log"
    fi
    rm -f "$out"
done
exit "$found"
