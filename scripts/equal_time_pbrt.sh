#!/usr/bin/env bash
# Equal-time comparison of kasha with pbrt-v4 on one pbrt-v4 scene (issue 41's table).
# Usage: scripts/equal_time_pbrt.sh SCENE.pbrt REFERENCE.exr SECONDS OUTDIR [KASHA_INTEGRATORS...]
# Env: PBRT, IMGTOOL (pbrt-v4's binaries; default /work/pbrt/build/{pbrt,imgtool}), KASHA,
# KASHA_ARGS (more options for kasha's renders, e.g. "--max-depth scene"),
# PBRT_INTEGRATORS (pbrt-v4's integrators to run; default "path bdpt"; sppm's samples are its
# iterations).
# The scene is used as it is (make a variant with scripts/pbrt_variant.py: resolution, maxdepth,
# the integrator pbrt-v4 should run). kasha renders with `--time SECONDS` for each integrator named
# (default: vcm, kasha's default); pbrt-v4 renders with `path` and `bdpt`, each at the sample
# count that takes SECONDS of its rendering on this machine (two calibration runs), and a seed of its
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
# The seconds pbrt-v4's last progress line reports: "Rendering: [+++] (50.7s)".
render_seconds() { tr '\r' '\n' < "$1" | grep -o '([0-9.]*s)' | tail -1 | tr -d '()s'; }
for integ in "${integrators[@]}"; do
  # shellcheck disable=SC2086
  "$kasha" render "$scene" --integrator "$integ" --time "$secs" ${KASHA_ARGS:-} -o "$out/$name.kasha-$integ.exr" > /dev/null 2>&1
  images+=("$out/$name.kasha-$integ.exr")
done
for integ in ${PBRT_INTEGRATORS:-path bdpt}; do
  variant=$(dirname "$scene")/_et_$integ.pbrt
  python3 "$here/pbrt_variant.py" "$scene" "$variant" --integrator "$integ"
  # Calibrate from pbrt-v4's own rendering time (its progress line: loading left out, as kasha's
  # --time leaves it out): 16 samples per pixel, then enough for about 8 s.
  n=16
  "$pbrt" --nthreads 2 --spp $n --outfile "$out/_calibrate.exr" "$variant" > "$out/_calibrate.log" 2>&1
  t=$(render_seconds "$out/_calibrate.log")
  n=$(python3 -c "print(max(16, int($n * 8 / max($t, 0.05))))")
  "$pbrt" --nthreads 2 --spp $n --outfile "$out/_calibrate.exr" "$variant" > "$out/_calibrate.log" 2>&1
  t=$(render_seconds "$out/_calibrate.log")
  spp=$(python3 -c "print(max(1, int($n * $secs / $t)))")
  t0=$(date +%s.%N)
  "$pbrt" --nthreads 2 --seed 20261206 --spp "$spp" --outfile "$out/$name.pbrt-$integ.exr" "$variant" > /dev/null 2>&1
  echo "pbrt-v4 $integ: $spp spp in $(echo "$(date +%s.%N) - $t0" | bc | cut -c1-6) s"
  images+=("$out/$name.pbrt-$integ.exr")
  rm -f "$variant" "$out/_calibrate.exr" "$out/_calibrate.log"
done
/usr/bin/python3 "$here/pbrt_compare.py" "$imgtool" "$ref" "${images[@]}"
