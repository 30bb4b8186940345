#!/usr/bin/env bash
# pytest of the bezjoin Python package (no FreeCAD needed), against the release library.
set -euo pipefail

repository="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$repository"

if ! python3 -m pytest --version >/dev/null 2>&1; then
    python3 -m pip install --quiet pytest
fi

library="$repository/target/release/libbezjoin.so"
if [[ -n "${BEZJOIN_LIBRARY:-}" ]]; then
    library="$BEZJOIN_LIBRARY"
elif [[ ! -f "$library" ]] || [[ -n "$(find crates/bezjoin/src crates/bezjoin-ffi/src \
        -newer "$library" -print -quit)" ]]; then
    cargo build --release -p bezjoin-ffi
fi
export BEZJOIN_LIBRARY="$library"

# Exit status 5 ("no tests collected") is a failure like any other non-zero status.
python3 -m pytest -q -p no:cacheprovider --doctest-modules bindings/python/bezjoin bindings/python/tests
