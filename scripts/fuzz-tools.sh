#!/usr/bin/env bash
# What the fuzz scripts need on a fresh machine: a nightly toolchain and
# cargo-fuzz (from crates.io). Installs only what is missing.
set -euo pipefail
if ! rustup toolchain list | grep '^nightly' >/dev/null; then
    rustup toolchain install nightly --profile minimal
fi
if ! command -v cargo-fuzz >/dev/null; then
    cargo install cargo-fuzz --locked
fi
