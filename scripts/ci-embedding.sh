#!/usr/bin/env bash
# Embedding kit check (issue 10): install into a temporary prefix, build and
# run a C consumer (pkg-config) and a C++ consumer (CMake package, shared and
# static, and after moving the prefix), the thread stress test (plain,
# ThreadSanitizer on the C++ side, helgrind on fewer iterations), memcheck of
# the C consumer, of every C program in tests/c/ (with a planted-leak
# self-test) and of the stress test, and a reproducible run of every fuzz
# target (fixed seed and execution counts, scripts/fuzz-short.sh).
#
#   bash scripts/ci-embedding.sh
# Environment: FUZZ_SCALE (multiplies every target's execution count,
#              default 1; 0 skips fuzzing),
#              STRESS_ITERATIONS (per thread, default 100000),
#              KEEP_TMP=1 keeps the temporary directory.
set -euo pipefail
# Never `cmd | grep -q`: grep -q exits at the first match, cmd may then die
# of SIGPIPE and pipefail fails the script (seen once in CI at the ldd check);
# `grep ... >/dev/null` reads all of its input.
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
FUZZ_SCALE="${FUZZ_SCALE:-1}"
STRESS_ITERATIONS="${STRESS_ITERATIONS:-100000}"
step() { printf '\n=== %s\n' "$*" >&2; }

# --- tools a fresh machine may lack --------------------------------------
missing=()
command -v cmake >/dev/null || missing+=(cmake)
command -v pkg-config >/dev/null || missing+=(pkg-config)
command -v g++ >/dev/null || missing+=(g++)
command -v valgrind >/dev/null || missing+=(valgrind)
command -v readelf >/dev/null || missing+=(binutils)
if [ "${#missing[@]}" -gt 0 ]; then
    step "apt-get install ${missing[*]}"
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
fi

TMP="$(mktemp -d /tmp/bezjoin-embedding.XXXXXX)"
if [ "${KEEP_TMP:-0}" != 1 ]; then trap 'rm -rf "$TMP"' EXIT; fi
PREFIX="$TMP/prefix"

# --- install ---------------------------------------------------------------
step "scripts/install.sh $PREFIX"
bash scripts/install.sh "$PREFIX"
MAJOR="$(sed -n 's/^#define BZJ_VERSION_MAJOR \([0-9]*\)$/\1/p' include/bezjoin.h)"
VERSION="$(sed -n 's/^Version: //p' "$PREFIX/lib/pkgconfig/bezjoin.pc")"
for f in include/bezjoin.h "lib/libbezjoin.so.$VERSION" lib/libbezjoin.a \
         lib/pkgconfig/bezjoin.pc lib/cmake/bezjoin/bezjoinConfig.cmake \
         lib/cmake/bezjoin/bezjoinConfigVersion.cmake; do
    [ -f "$PREFIX/$f" ] || { echo "missing $PREFIX/$f" >&2; exit 1; }
done
[ "$(readlink "$PREFIX/lib/libbezjoin.so")" = "libbezjoin.so.$MAJOR" ]
[ "$(readlink "$PREFIX/lib/libbezjoin.so.$MAJOR")" = "libbezjoin.so.$VERSION" ]
readelf -d "$PREFIX/lib/libbezjoin.so.$VERSION" | grep "Library soname: \[libbezjoin.so.$MAJOR\]" >/dev/null
# Only the C API is exported: nothing else can clash with a host's symbols.
others="$(nm -D --defined-only "$PREFIX/lib/libbezjoin.so.$VERSION" | awk '{print $3}' | grep -v '^bzj_' || true)"
if [ -n "$others" ]; then
    echo "libbezjoin.so exports symbols outside the bzj_ namespace:" >&2
    echo "$others" >&2
    exit 1
fi
echo "layout, symlinks, SONAME libbezjoin.so.$MAJOR and exported symbols OK" >&2

VALGRIND=(valgrind --error-exitcode=3 --leak-check=full --errors-for-leak-kinds=definite,indirect
          --show-leak-kinds=definite,indirect -q)

# --- C consumer through pkg-config ----------------------------------------
step "C consumer (pkg-config)"
export PKG_CONFIG_PATH="$PREFIX/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
[ "$(pkg-config --modversion bezjoin)" = "$VERSION" ]
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -pedantic scripts/consumer/c/smoke.c -o "$TMP/smoke" \
    $(pkg-config --cflags --libs bezjoin) -lm -Wl,-rpath,"$(pkg-config --variable=libdir bezjoin)"
"$TMP/smoke"
ldd "$TMP/smoke" | grep "libbezjoin.so.$MAJOR => $PREFIX/lib/" >/dev/null
step "C consumer under valgrind memcheck"
"${VALGRIND[@]}" "$TMP/smoke"

# --- C consumer linked against the build tree ---------------------------------
# The C contract says the library is built into target/release/; a host linked
# there (-L target/release -lbezjoin) records the SONAME libbezjoin.so.MAJOR,
# which the build tree must hold (crates/bezjoin-ffi/build.rs links it).
step "C consumer linked against the build tree (target/release)"
BUILD_TREE="${CARGO_TARGET_DIR:-target}"
[[ "$BUILD_TREE" = /* ]] || BUILD_TREE="$ROOT/$BUILD_TREE"
BUILD_TREE="$BUILD_TREE/release"
[ "$(readlink "$BUILD_TREE/libbezjoin.so.$MAJOR")" = "libbezjoin.so" ]
cc -std=c11 -Wall -Wextra -Werror -pedantic scripts/consumer/c/smoke.c -o "$TMP/smoke_tree" \
    -Iinclude -L"$BUILD_TREE" -lbezjoin -lm -Wl,-rpath,"$BUILD_TREE"
"$TMP/smoke_tree"
ldd "$TMP/smoke_tree" | grep "libbezjoin.so.$MAJOR => $BUILD_TREE/" >/dev/null

# --- the C programs of tests/c/ under memcheck -------------------------------
# cargo test (tests/tests/c_programs.rs) builds them against the static
# archive and runs them without valgrind. Here each one is built as smoke.c
# is (same flags as c_programs.rs: C11, -Wall -Wextra -Werror -pedantic, the
# installed header, no defines) against the installed shared library, and
# run under memcheck: it must exit 0 with no invalid access and no definite
# or indirect leak (exit 3 = valgrind found an error).
c_programs=(tests/c/*.c)
[ -f "${c_programs[0]}" ] || { echo "no C programs in tests/c/" >&2; exit 1; }
for src in "${c_programs[@]}"; do
    name="$(basename "$src" .c)"
    step "tests/c/$name.c under valgrind memcheck"
    # shellcheck disable=SC2046
    cc -std=c11 -O1 -g -Wall -Wextra -Werror -pedantic "$src" -o "$TMP/c-$name" \
        $(pkg-config --cflags --libs bezjoin) -lm -Wl,-rpath,"$PREFIX/lib"
    set +e
    "${VALGRIND[@]}" --log-file="$TMP/c-$name.valgrind" "$TMP/c-$name" >"$TMP/c-$name.out" 2>&1
    code=$?
    set -e
    if [ "$code" -ne 0 ]; then
        cat "$TMP/c-$name.out" "$TMP/c-$name.valgrind" >&2
        echo "tests/c/$name.c under memcheck: exit $code (3 = memory error or leak)" >&2
        exit 1
    fi
    echo "tests/c/$name.c: exit 0, memcheck clean" >&2
done
step "memcheck self-test: a bezjoin curve leaked on purpose must be caught"
# shellcheck disable=SC2046
cc -std=c11 -g -Wall -Wextra -Werror -pedantic scripts/consumer/c/leak_on_purpose.c \
    -o "$TMP/leak_on_purpose" $(pkg-config --cflags --libs bezjoin) -Wl,-rpath,"$PREFIX/lib"
set +e
"${VALGRIND[@]}" --num-callers=30 --log-file="$TMP/leak_on_purpose.valgrind" "$TMP/leak_on_purpose" >/dev/null 2>&1
code=$?
set -e
if [ "$code" -ne 3 ] || ! grep "bzj_curve_new" "$TMP/leak_on_purpose.valgrind" >/dev/null; then
    cat "$TMP/leak_on_purpose.valgrind" >&2
    echo "memcheck did not report the planted leak (exit $code): the leak check is blind" >&2
    exit 1
fi
echo "memcheck caught the planted leak (exit 3, allocated in bzj_curve_new): the check works" >&2

# --- C++ consumer through the CMake package --------------------------------
cmake_consumer() {  # $1 = build name, $2 = prefix, rest = extra cmake args
    local name="$1" prefix="$2"
    shift 2
    rm -rf "$TMP/$name"
    cp -r scripts/consumer/cmake "$TMP/$name"
    cmake -S "$TMP/$name" -B "$TMP/$name/build" -DCMAKE_PREFIX_PATH="$prefix" \
        -DCMAKE_BUILD_TYPE=Release "$@" >"$TMP/$name.log" || { cat "$TMP/$name.log"; return 1; }
    cmake --build "$TMP/$name/build" >>"$TMP/$name.log" || { cat "$TMP/$name.log"; return 1; }
    "$TMP/$name/build/consumer"
}
step "C++ consumer (find_package(bezjoin CONFIG), shared)"
cmake_consumer cmake-shared "$PREFIX"
ldd "$TMP/cmake-shared/build/consumer" | grep "libbezjoin.so.$MAJOR" >/dev/null
step "C++ consumer (static archive, BEZJOIN_USE_STATIC_LIBS=ON)"
cmake_consumer cmake-static "$PREFIX" -DBEZJOIN_USE_STATIC_LIBS=ON
if ldd "$TMP/cmake-static/build/consumer" | grep libbezjoin >/dev/null; then
    echo "static consumer still loads libbezjoin.so" >&2
    exit 1
fi
step "C++ consumer against a moved prefix (relocatable CMake package)"
cp -a "$PREFIX" "$TMP/moved"
cmake_consumer cmake-moved "$TMP/moved"
ldd "$TMP/cmake-moved/build/consumer" | grep "$TMP/moved/lib/libbezjoin.so.$MAJOR" >/dev/null
step "find_package(bezjoin 1.0) must refuse a $VERSION install"
mkdir -p "$TMP/version-check"
printf 'cmake_minimum_required(VERSION 3.16)\nproject(v NONE)\nfind_package(bezjoin %s CONFIG QUIET)\nif(bezjoin_FOUND)\n  message(FATAL_ERROR "accepted")\nendif()\n' \
    "$((MAJOR + 1)).0" > "$TMP/version-check/CMakeLists.txt"
cmake -S "$TMP/version-check" -B "$TMP/version-check/build" -DCMAKE_PREFIX_PATH="$PREFIX" >/dev/null

# --- thread stress test ----------------------------------------------------
STRESS_SRC=tests/stress/stress.cpp
step "stress test: 8 threads x $STRESS_ITERATIONS calls"
# shellcheck disable=SC2046
g++ -std=c++17 -O2 -g -Wall -Wextra -Werror -pthread "$STRESS_SRC" -o "$TMP/stress" \
    $(pkg-config --cflags --libs bezjoin) -Wl,-rpath,"$PREFIX/lib"
"$TMP/stress" "$STRESS_ITERATIONS" 8
step "stress test, ThreadSanitizer on the C++ side (library not instrumented)"
# shellcheck disable=SC2046
g++ -std=c++17 -O1 -g -fsanitize=thread -pthread "$STRESS_SRC" -o "$TMP/stress-tsan" \
    $(pkg-config --cflags --libs bezjoin) -Wl,-rpath,"$PREFIX/lib"
TSAN_OPTIONS="halt_on_error=1 exitcode=4" "$TMP/stress-tsan" 20000 8
step "stress test under helgrind (8 threads x 5000 calls)"
valgrind --tool=helgrind --error-exitcode=5 -q "$TMP/stress" 5000 8
step "stress test under memcheck (8 threads x 5000 calls)"
"${VALGRIND[@]}" "$TMP/stress" 5000 8

# --- fuzzing -----------------------------------------------------------------
if [ "$FUZZ_SCALE" != 0 ]; then
    step "fuzz targets: seed replay, then fixed seed and execution counts (x$FUZZ_SCALE)"
    bash scripts/fuzz-short.sh "$FUZZ_SCALE"
fi
step "embedding checks passed"
