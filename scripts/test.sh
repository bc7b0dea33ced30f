#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite on the PoCL CPU device with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export POCL_CACHE_DIR="$PWD/build/kernel-cache"
ctest --test-dir build --output-on-failure -j "$(nproc)"

