#!/usr/bin/env bash
# Sets up, builds and renders the demo scene to out/cornell_box.exr and out/cornell_box.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
./build/kasha render scenes/cornell_box.json --passes 20 \
  -o out/cornell_box.exr --png out/cornell_box.png
