#!/usr/bin/env bash
# The fuzz harness in a build with AddressSanitizer and UBSan (a finding aborts the run), with more
# cases than ctest's run of it. Not part of CI (scripts/test.sh): the second build alone is about
# 40 minutes on 2 cores, past CI's budget; run it before landing a change to a reader.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# At -O1: the sanitizers need no more, and its files compile in a third to a half less time than
# at -O3. PoCL's own allocations are not ours to check for leaks.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DKASHA_SANITIZE=ON
cmake --build build-asan -j "$(nproc)" --target kasha kasha_fuzz
# OpenVDB (not instrumented) allocates what a mutated .vdb file's header says, up to terabytes:
# without the sanitizer a std::bad_alloc, which kasha reports in one line (ctest's fuzz run), but
# AddressSanitizer's operator new aborts instead of throwing, so the .vdb seed stays whole here
# (and the .nvdb one: NanoVDB's zip reader allocates the compressed size its data claims).
KASHA_FUZZ_VDB_WHOLE=1 ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 KASHA_FUZZ_CASES="${KASHA_FUZZ_CASES:-2000}" \
  POCL_CACHE_DIR="$PWD/build-asan/kernel-cache" build-asan/tests/kasha_fuzz
