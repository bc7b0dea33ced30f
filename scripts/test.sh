#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite on the PoCL CPU device with ctest, then the fuzz
# harness under AddressSanitizer + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export POCL_CACHE_DIR="$PWD/build/kernel-cache"
ctest --test-dir build --output-on-failure -j "$(nproc)"

# The fuzz harness again, with more cases, in a build with AddressSanitizer and UBSan (a finding
# aborts the run). PoCL's own allocations are not ours to check for leaks. At -O1: the sanitizers
# need no more, and its files compile in a third to a half less time than at -O3 (CI's budget).
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DKASHA_SANITIZE=ON
cmake --build build-asan -j "$(nproc)" --target kasha kasha_fuzz
ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 KASHA_FUZZ_CASES=2000 \
  POCL_CACHE_DIR="$PWD/build-asan/kernel-cache" build-asan/tests/kasha_fuzz
