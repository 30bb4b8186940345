#!/usr/bin/env bash
# Install the Debian packages the checks need, only those that are missing.
# Runs as root (CI and the developers' machines); apt-get update comes first.
set -euo pipefail
wanted=(cmake pkg-config g++ valgrind libtbb-dev
        libocct-foundation-dev libocct-modeling-data-dev
        libocct-modeling-algorithms-dev libocct-data-exchange-dev)
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep "install ok installed" >/dev/null || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "all present: ${wanted[*]}"
fi
