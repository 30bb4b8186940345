#!/usr/bin/env bash
# Install bezjoin for C/C++ hosts into PREFIX (Linux/ELF).
#
#   scripts/install.sh PREFIX        (DESTDIR is honoured for staged installs)
#
# Builds the release library (cargo build --release -p bezjoin-ffi) and installs
#   PREFIX/include/bezjoin.h, PREFIX/include/bezjoin.hpp (when the repo has it)
#   PREFIX/lib/libbezjoin.so.MAJOR.MINOR.PATCH  (SONAME libbezjoin.so.MAJOR)
#   PREFIX/lib/libbezjoin.so.MAJOR -> libbezjoin.so.MAJOR.MINOR.PATCH
#   PREFIX/lib/libbezjoin.so       -> libbezjoin.so.MAJOR
#   PREFIX/lib/libbezjoin.a
#   PREFIX/lib/pkgconfig/bezjoin.pc
#   PREFIX/lib/cmake/bezjoin/bezjoinConfig.cmake, bezjoinConfigVersion.cmake
# The CMake package is relocatable; the .pc file records PREFIX.
set -euo pipefail

if [ $# -ne 1 ] || [ -z "$1" ]; then
    echo "usage: $0 PREFIX" >&2
    exit 2
fi
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
PREFIX="$(realpath -m "$1")"
DEST="${DESTDIR:-}${PREFIX}"
cd "$ROOT"

# Version: the header's macros (a test keeps them equal to Cargo's version).
HEADER="$ROOT/include/bezjoin.h"
macro() { sed -n "s/^#define $1 \([0-9][0-9]*\)\$/\1/p" "$HEADER"; }
MAJOR="$(macro BZJ_VERSION_MAJOR)"
MINOR="$(macro BZJ_VERSION_MINOR)"
PATCH="$(macro BZJ_VERSION_PATCH)"
if [ -z "$MAJOR" ] || [ -z "$MINOR" ] || [ -z "$PATCH" ]; then
    echo "install.sh: BZJ_VERSION_MAJOR/MINOR/PATCH not found in $HEADER" >&2
    exit 1
fi
VERSION="$MAJOR.$MINOR.$PATCH"

# System libraries the static archive needs, as rustc reports them for this
# toolchain and target (the cdylib needs nothing beyond its own DT_NEEDED).
echo "install.sh: asking rustc for the static archive's native libraries" >&2
NATIVE_OUT="$(cargo rustc -p bezjoin-ffi --release --lib --crate-type staticlib -- --print native-static-libs 2>&1)" || {
    echo "$NATIVE_OUT" >&2
    exit 1
}
NATIVE_LIBS="$(printf '%s\n' "$NATIVE_OUT" | sed -n 's/.*native-static-libs: //p' | tail -n 1 | tr -s ' ' | sed 's/ *$//')"
if [ -z "$NATIVE_LIBS" ]; then
    # The list rustc printed for x86_64-unknown-linux-gnu (checked by scripts/ci-embedding.sh,
    # which links the static archive through the CMake package).
    NATIVE_LIBS="-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc"
    echo "install.sh: rustc printed no list; using the known Linux list: $NATIVE_LIBS" >&2
fi
# The same list as CMake library names (-lfoo -> foo).
NATIVE_CMAKE="$(printf '%s' "$NATIVE_LIBS" | tr ' ' '\n' | sed -n 's/^-l//p' | paste -sd ';' -)"

echo "install.sh: cargo build --release -p bezjoin-ffi" >&2
cargo build --release -p bezjoin-ffi
TARGET_DIR="${CARGO_TARGET_DIR:-$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')}"
TARGET_DIR="${TARGET_DIR:-$ROOT/target}"
SO="$TARGET_DIR/release/libbezjoin.so"
AR="$TARGET_DIR/release/libbezjoin.a"
for f in "$SO" "$AR"; do
    [ -f "$f" ] || { echo "install.sh: $f was not built" >&2; exit 1; }
done

SONAME="$(readelf -d "$SO" | sed -n 's/.*(SONAME).*\[\(.*\)\].*/\1/p')"
if [ "$SONAME" != "libbezjoin.so.$MAJOR" ]; then
    echo "install.sh: $SO has SONAME '$SONAME', expected libbezjoin.so.$MAJOR (crates/bezjoin-ffi/build.rs)" >&2
    exit 1
fi

install -d "$DEST/include" "$DEST/lib/pkgconfig" "$DEST/lib/cmake/bezjoin"
install -m 644 "$HEADER" "$DEST/include/bezjoin.h"
if [ -f "$ROOT/include/bezjoin.hpp" ]; then
    install -m 644 "$ROOT/include/bezjoin.hpp" "$DEST/include/bezjoin.hpp"
fi
install -m 755 "$SO" "$DEST/lib/libbezjoin.so.$VERSION"
ln -sfn "libbezjoin.so.$VERSION" "$DEST/lib/libbezjoin.so.$MAJOR"
ln -sfn "libbezjoin.so.$MAJOR" "$DEST/lib/libbezjoin.so"
install -m 644 "$AR" "$DEST/lib/libbezjoin.a"

subst() {
    sed -e "s|@PREFIX@|$PREFIX|g" \
        -e "s|@VERSION@|$VERSION|g" \
        -e "s|@MAJOR@|$MAJOR|g" \
        -e "s|@NATIVE_LIBS@|$NATIVE_LIBS|g" \
        -e "s|@NATIVE_CMAKE@|$NATIVE_CMAKE|g" \
        "$1"
}
subst "$ROOT/packaging/bezjoin.pc.in" > "$DEST/lib/pkgconfig/bezjoin.pc"
subst "$ROOT/packaging/bezjoinConfig.cmake.in" > "$DEST/lib/cmake/bezjoin/bezjoinConfig.cmake"
subst "$ROOT/packaging/bezjoinConfigVersion.cmake.in" > "$DEST/lib/cmake/bezjoin/bezjoinConfigVersion.cmake"
chmod 644 "$DEST/lib/pkgconfig/bezjoin.pc" "$DEST/lib/cmake/bezjoin/"*.cmake

echo "install.sh: installed bezjoin $VERSION (SONAME $SONAME) into $DEST" >&2
