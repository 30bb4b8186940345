#!/usr/bin/env bash
# Instructions per fillet of the NURBS-vs-Bezier driver
# (crates/bezjoin/tests/fillet_instructions.rs) under callgrind:
# (count at 110 fillets - count at 10) / 100, for each FILLET_MODE given
# (default: 0 1 2 3 4). Needs valgrind. Usage: scripts/fillet-instructions.sh [MODE...]
set -euo pipefail
cd "$(dirname "$0")/.."
modes=("$@")
((${#modes[@]})) || modes=(0 1 2 3 4)
bin=$(cargo test --release -p bezjoin-core --test fillet_instructions --no-run 2>&1 |
  sed -n 's/.*Executable .*(\(.*\))$/\1/p' | tail -n 1)
[ -x "$bin" ] || { echo "no test binary found" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for mode in "${modes[@]}"; do
  for n in 10 110; do
    FILLET_MODE=$mode FILLET_REPEATS=$n valgrind --tool=callgrind \
      --callgrind-out-file="$out/cg.$mode.$n" "$bin" --ignored --exact fillet_work \
      >/dev/null 2>&1
  done
  a=$(awk '/^(summary|totals):/ {print $2; exit}' "$out/cg.$mode.10")
  b=$(awk '/^(summary|totals):/ {print $2; exit}' "$out/cg.$mode.110")
  echo "mode $mode: $(((b - a) / 100)) instructions per fillet"
done
