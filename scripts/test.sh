#!/usr/bin/env bash
# Sets up, builds and runs the test suite on the PoCL CPU device with ctest: CI's tier (what
# .ci/run runs), or with --full every test, the long tier (tests/long_tests.cmake) too. The fuzz
# harness under AddressSanitizer + UBSan is scripts/sanitize.sh, outside CI's budget.
set -euo pipefail
cd "$(dirname "$0")/.."
tier=(-LE long)
if [[ "${1:-}" == "--full" ]]; then
  tier=()
elif [[ $# -gt 0 ]]; then
  echo "usage: scripts/test.sh [--full]" >&2
  exit 2
fi
bash scripts/build.sh
export POCL_CACHE_DIR="$PWD/build/kernel-cache"
ctest --test-dir build --output-on-failure -j "$(nproc)" "${tier[@]}"
