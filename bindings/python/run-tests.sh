#!/usr/bin/env bash
# pytest of the bezjoin Python package (no FreeCAD needed), against the release library.
#
# The interpreter is $BEZJOIN_PYTHON, else the first python3 on PATH. When it has no
# pytest, the script tries `pip install pytest` for it; when that fails too (no pip, or an
# EXTERNALLY-MANAGED system Python), it installs Debian's python3-pytest and runs the
# tests with /usr/bin/python3, the interpreter that package installs for (the python3
# first on PATH may be another one, e.g. pyenv's). Every failure stops the script with a
# message and a non-zero status.
set -euo pipefail

repository="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$repository"

say() { echo "bindings/python/run-tests.sh: $*" >&2; }
has_pytest() { "$1" -c 'import pytest' >/dev/null 2>&1; }

python="${BEZJOIN_PYTHON:-python3}"
if ! command -v "$python" >/dev/null 2>&1; then
    say "no $python on PATH"
    exit 1
fi
if ! has_pytest "$python"; then
    say "$python has no pytest; trying pip"
    if "$python" -m pip --version >/dev/null 2>&1 \
            && "$python" -m pip install --quiet pytest && has_pytest "$python"; then
        say "installed pytest with pip for $python"
    else
        system_python=/usr/bin/python3
        say "pip could not install pytest for $python; using Debian's python3-pytest with $system_python"
        if ! has_pytest "$system_python"; then
            if ! command -v apt-get >/dev/null 2>&1; then
                say "no apt-get either: install pytest for $python by hand"
                exit 1
            fi
            export DEBIAN_FRONTEND=noninteractive
            apt-get update
            apt-get install -y --no-install-recommends python3-pytest
        fi
        if ! has_pytest "$system_python"; then
            say "python3-pytest is installed but $system_python still cannot import pytest"
            exit 1
        fi
        python="$system_python"
    fi
fi

if [[ -n "${BEZJOIN_LIBRARY:-}" ]]; then
    library="$BEZJOIN_LIBRARY"
else
    # Always (re)build: cargo does nothing when the library is up to date.
    cargo build --release -p bezjoin-ffi
    library="$repository/target/release/libbezjoin.so"
fi
if [[ ! -f "$library" ]]; then
    say "no library at $library"
    exit 1
fi
export BEZJOIN_LIBRARY="$library"

say "pytest with $("$python" -c 'import sys; print(sys.executable, sys.version.split()[0])')," \
    "library $library"
# Exit status 5 ("no tests collected") is a failure like any other non-zero status.
"$python" -m pytest -q -p no:cacheprovider --doctest-modules bindings/python/bezjoin bindings/python/tests
