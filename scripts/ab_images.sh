#!/usr/bin/env bash
# Renders a fixed set of images with one kasha binary into a folder, or compares two such folders
# byte for byte: the check that a change which should not alter any image alters none.
#   bash scripts/ab_images.sh render KASHA OUT_DIR     # render the set with binary KASHA
#   bash scripts/ab_images.sh compare DIR_A DIR_B      # cmp every EXR; exit 1 on a difference
# The set: the demo (scripts/demo.sh's command), one analytic furnace per integrator, the mirror
# caustic and the glossy box (photon, backward), the host gather, the independent sampler, two
# queues on one device, vcm, bpt and ppm on a furnace, the mirror caustic and a pbrt-v4 scene (each
# --merges of vcm, its test hooks), and two MPI ranks where mpirun exists.
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=scenes
case "${1:-}" in
render)
  kasha=$(realpath "$2"); out=$3; mkdir -p "$out"
  export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$PWD/build/kernel-cache}
  # An image already in OUT_DIR is kept: a set cut short resumes where it stopped.
  r() { local name=$1; shift; [ -f "$out/$name.exr" ] && return 0; echo "== $name: kasha render $*" >&2
        "$kasha" render "$@" -o "$out/$name.exr" 2>>"$out/log.txt"; }
  r demo $scenes/cornell_box.json --passes 40
  for i in backward forward photon debug; do
    r furnace_$i $scenes/furnace_fluorescent.json --integrator $i --passes 4
  done
  r furnace_uv_photon $scenes/furnace_uv.json --passes 4
  r mirror_photon $scenes/mirror_caustic.json --integrator photon --passes 2
  r mirror_backward $scenes/mirror_caustic.json --integrator backward --passes 2
  r glossy_photon $scenes/glossy_cornell_box.json --integrator photon --passes 2
  r glossy_backward $scenes/glossy_cornell_box.json --integrator backward --passes 2 --spectral
  r glossy_forward $scenes/glossy_cornell_box.json --integrator forward --passes 2
  r lacquer_forward $scenes/lacquered_vase.json --integrator forward --passes 2
  r lacquer_photon $scenes/lacquered_vase.json --integrator photon --passes 2
  r cornell_host_gather $scenes/cornell_box.json --integrator photon --gather host --passes 2
  r cornell_independent $scenes/cornell_box.json --integrator backward --sampler independent --passes 2
  r cornell_two_queues $scenes/cornell_box.json --device 0,0 --passes 3
  r cornell_forward_two_queues $scenes/cornell_box.json --integrator forward --device 0,0 --passes 3
  for i in vcm bpt ppm; do
    r furnace_$i $scenes/furnace_fluorescent.json --integrator $i --passes 4
    r mirror_$i $scenes/mirror_caustic.json --integrator $i --passes 2
    r pbrt_rough_$i $scenes/pbrt/rough_metals.pbrt --integrator $i --passes 2
    r pbrt_textured_$i $scenes/pbrt/textured.pbrt --integrator $i --passes 2
  done
  for m in caustic first every; do
    r cornell_vcm_$m $scenes/cornell_box.json --merges $m --passes 2
  done
  r glass_vcm $scenes/glass_caustic.json --passes 2
  r lacquer_vcm $scenes/lacquered_vase.json --passes 2
  r booth_uv_vcm $scenes/light_booth_uv_spot.json --passes 2
  r sunlit_vcm $scenes/sunlit_table.json --passes 2
  r cornell_vcm_small_memory $scenes/cornell_box.json --memory 2MiB --passes 2
  r cornell_vcm_two_queues $scenes/cornell_box.json --device 0,0 --passes 3
  if command -v mpirun >/dev/null; then
    echo "== mpi_photon: mpirun -np 2 kasha render cornell_box --passes 3" >&2
    mpirun --allow-run-as-root --oversubscribe -np 2 "$kasha" render $scenes/cornell_box.json \
      --passes 3 -o "$out/mpi_photon.exr" 2>>"$out/log.txt"
  fi
  ;;
compare)
  status=0
  for a in "$2"/*.exr; do
    b="$3/$(basename "$a")"
    if cmp -s "$a" "$b"; then echo "identical  $(basename "$a")"; else echo "DIFFERENT  $(basename "$a")"; status=1; fi
  done
  exit $status
  ;;
*) sed -n 2,8p "$0"; exit 2 ;;
esac
