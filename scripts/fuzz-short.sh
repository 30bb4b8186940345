#!/usr/bin/env bash
# Run every fuzz target (or the ones named) for SECONDS each, one at a time,
# starting from the committed seeds in fuzz/seeds/<target>/ (the corpus grown
# during the run is thrown away). Fails on the first crash, hang (-timeout)
# or BZJ_ERR_INTERNAL (the targets assert on it); the input that failed is
# copied to fuzz/artifacts/ for reproduction:
#   cargo +nightly fuzz run <target> fuzz/artifacts/<file>
#
#   scripts/fuzz-short.sh [SECONDS=20] [TARGET...]
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
PER_TARGET="${1:-20}"
shift || true

if ! rustup toolchain list | grep '^nightly' >/dev/null; then
    rustup toolchain install nightly --profile minimal
fi
if ! command -v cargo-fuzz >/dev/null; then
    cargo install cargo-fuzz --locked
fi

# Targets with an open finding in another module (docs/reliability.md); they
# run only when named explicitly. Empty this list when the finding is fixed.
KNOWN_OPEN=()
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
    for t in $(cargo +nightly fuzz list); do
        if printf '%s\n' "${KNOWN_OPEN[@]}" | grep -x "$t" >/dev/null; then
            echo "fuzz: skipping $t (open finding, see docs/reliability.md)" >&2
        else
            targets+=("$t")
        fi
    done
fi
cargo +nightly fuzz build

WORK="$(mktemp -d /tmp/bezjoin-fuzz.XXXXXX)"
trap 'rm -rf "$WORK"' EXIT
for t in "${targets[@]}"; do
    mkdir -p "$WORK/corpus-$t"
    seeds="fuzz/seeds/$t"
    [ -d "$seeds" ] || seeds=""
    echo "--- fuzz $t for ${PER_TARGET}s" >&2
    if ! cargo +nightly fuzz run "$t" "$WORK/corpus-$t" $seeds -- \
        -max_total_time="$PER_TARGET" -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$WORK/artifact-$t-" >"$WORK/$t.log" 2>&1; then
        tail -n 60 "$WORK/$t.log" >&2
        mkdir -p fuzz/artifacts
        cp "$WORK"/artifact-"$t"-* fuzz/artifacts/ 2>/dev/null || true
        echo "fuzz target $t FAILED; input(s) in fuzz/artifacts/" >&2
        exit 1
    fi
    grep -E '^(stat::number_of_executed_units|stat::average_exec_per_sec|Done)' "$WORK/$t.log" >&2 || true
    grep -E '^#[0-9]+ +DONE' "$WORK/$t.log" | tail -n 1 >&2 || true
done
echo "fuzzing: ${#targets[@]} targets x ${PER_TARGET}s, no findings" >&2
