#!/usr/bin/env bash
# Equal-time comparison of kasha with pbrt-v4 on one pbrt-v4 scene (issue 41's table).
# Usage: scripts/equal_time_pbrt.sh SCENE.pbrt REFERENCE.exr SECONDS OUTDIR [KASHA_INTEGRATORS...]
# Env: PBRT, IMGTOOL (pbrt-v4's binaries; default /work/pbrt/build/{pbrt,imgtool}), KASHA,
# PBRT_INTEGRATORS (pbrt-v4's integrators to run; default "path bdpt"; sppm's samples are its
# iterations).
# The scene is used as it is (make a variant with scripts/pbrt_variant.py: resolution, maxdepth,
# the integrator pbrt-v4 should run). kasha renders with `--time SECONDS` for each integrator named
# (default: vcm, kasha's default); pbrt-v4 renders with `path` and `bdpt`, each at the sample
# count that takes SECONDS on this machine, found from a short calibration run, and a seed of its
# own (a reference made by pbrt-v4 with its default seed shares its first samples with a shorter
# render at that seed: its error would look far smaller than it is). Prints each
# image's channel means against the reference and its RMSE, then the ratios of kasha's RMSEs
# to pbrt-v4's best.
set -euo pipefail
scene=$1 ref=$2 secs=$3 out=$4
shift 4
integrators=("${@:-vcm}")
here=$(cd "$(dirname "$0")" && pwd)
kasha=${KASHA:-$here/../build/kasha}
pbrt=${PBRT:-/work/pbrt/build/pbrt}
imgtool=${IMGTOOL:-/work/pbrt/build/imgtool}
mkdir -p "$out"
name=$(basename "$(dirname "$(dirname "$scene")")")
images=()
for integ in "${integrators[@]}"; do
  "$kasha" render "$scene" --integrator "$integ" --time "$secs" -o "$out/$name.kasha-$integ.exr" > /dev/null 2>&1
  images+=("$out/$name.kasha-$integ.exr")
done
for integ in ${PBRT_INTEGRATORS:-path bdpt}; do
  variant=$(dirname "$scene")/_et_$integ.pbrt
  python3 "$here/pbrt_variant.py" "$scene" "$variant" --integrator "$integ"
  # Calibrate: 4 and 16 samples per pixel; their difference is 12 samples' rendering without the
  # scene's loading, which kasha's --time leaves out too.
  t0=$(date +%s.%N)
  "$pbrt" --nthreads 2 --spp 4 --outfile "$out/_calibrate.exr" "$variant" > /dev/null 2>&1
  t1=$(date +%s.%N)
  "$pbrt" --nthreads 2 --spp 16 --outfile "$out/_calibrate.exr" "$variant" > /dev/null 2>&1
  t2=$(date +%s.%N)
  spp=$(python3 -c "print(max(1, int(12 * $secs / max(($t2 - $t1) - ($t1 - $t0), 1e-3))))")
  t0=$(date +%s.%N)
  "$pbrt" --nthreads 2 --seed 20261206 --spp "$spp" --outfile "$out/$name.pbrt-$integ.exr" "$variant" > /dev/null 2>&1
  echo "pbrt-v4 $integ: $spp spp in $(echo "$(date +%s.%N) - $t0" | bc | cut -c1-6) s"
  images+=("$out/$name.pbrt-$integ.exr")
  rm -f "$variant" "$out/_calibrate.exr"
done
/usr/bin/python3 "$here/pbrt_compare.py" "$imgtool" "$ref" "${images[@]}"
