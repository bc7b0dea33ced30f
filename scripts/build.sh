#!/usr/bin/env bash
# Installs the dependencies (scripts/setup.sh), then configures and builds kasha in build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
