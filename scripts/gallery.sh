#!/usr/bin/env bash
# Renders the README's gallery into docs/renders/gallery/ with an existing build of kasha:
#   KASHA_BUILD=build bash scripts/gallery.sh [NAME...]   (the build folder, default build;
#                                                          NAMEs: only those images)
# The demo image is the exact command of scripts/demo.sh at the scene's own 256 × 256; the others
# are shipped scenes at 512 × 512, each with the integrator that converges best on it at equal
# time (docs/integrators.md#which-integrator-for-which-scene). Prints each image's command and
# seconds, and writes them to docs/renders/gallery/times.txt for the README's captions.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${KASHA_BUILD:-build}"
KASHA="$BUILD/kasha"
GALLERY=docs/renders/gallery
EXR=out/gallery  # the EXRs stay out of the source tree's docs
SIZE=512
ONLY=("$@")
[ -x "$KASHA" ] || { echo "gallery: no $KASHA (build kasha first, or set KASHA_BUILD)" >&2; exit 1; }
mkdir -p "$GALLERY" "$EXR"
TIMES="$GALLERY/times.txt"
# Lines of times.txt for the images not rendered this time are kept.
if [ -f "$TIMES" ] && [ ${#ONLY[@]} -gt 0 ]; then cp "$TIMES" "$TIMES.tmp"; else : > "$TIMES.tmp"; fi

# Temporary scene copies live beside their originals (a scene's relative paths resolve against
# its own folder) and are removed however the script ends.
TEMPORARY=()
cleanup() { for f in "${TEMPORARY[@]}"; do rm -f "$f"; done; rm -f "$TIMES.tmp" "$TIMES.tmp2"; }
trap cleanup EXIT

# A copy of scene $1 with the camera at $2 × $3 pixels; prints its path.
resized() {
  local scene="$1" copy
  copy="$(dirname "$scene")/.gallery_$(basename "$scene" .json)_$2x$3.json"
  python3 - "$scene" "$copy" "$2" "$3" <<'EOF'
import json, sys
scene, copy, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
with open(scene) as f:
    d = json.load(f)
d["camera"]["width"], d["camera"]["height"] = width, height
with open(copy, "w") as f:
    json.dump(d, f, indent=1)
EOF
  echo "$copy"
}

# render NAME SHOWN-SCENE SCENE-FILE OPTIONS...: renders to $GALLERY/NAME.png, prints and records
# the command (with the scene as shown) and its wall-clock seconds.
render() {
  local name="$1" shown="$2" scene="$3"
  shift 3
  local start end seconds
  if [ ${#ONLY[@]} -gt 0 ] && [[ " ${ONLY[*]} " != *" $name "* ]]; then return; fi
  start=$(date +%s.%N)
  "$KASHA" render "$scene" "$@" -o "$EXR/$name.exr" --png "$GALLERY/$name.png"
  end=$(date +%s.%N)
  seconds=$(python3 -c "print(f'{$end - $start:.0f}')")
  grep -v "^$name	" "$TIMES.tmp" > "$TIMES.tmp2" || true
  printf '%s\t%s s\tkasha render %s %s\n' "$name" "$seconds" "$shown" "$*" | tee -a "$TIMES.tmp2"
  mv "$TIMES.tmp2" "$TIMES.tmp"
}

# The demo, exactly as scripts/demo.sh renders it (the default, vcm: 20 iterations, 256 × 256).
render cornell_box_demo scenes/cornell_box.json scenes/cornell_box.json --passes 20

# The same box at 512 × 512 with photon mapping (the default when this image was made). Four
# times the pixels of the scene's 256², so four times the default photons per pass: the same
# photons per pixel.
scene=$(resized scenes/cornell_box.json $SIZE $SIZE); TEMPORARY+=("$scene")
render cornell_box_512 "scenes/cornell_box.json (${SIZE}²)" "$scene" --integrator photon \
  --photons 1048576 --time 90

# The light booth under D65: every sample lit directly by a large lamp, where backward's
# next-event estimation has next to no variance.
scene=$(resized scenes/light_booth.json $SIZE $SIZE); TEMPORARY+=("$scene")
render light_booth_512 "scenes/light_booth.json (${SIZE}²)" "$scene" --integrator backward \
  --time 60

# The mirror caustic: light reaches the Post-it tile only by the mirror, and the camera sees it
# only in the mirror; photon mapping carries both halves (backward is noise, forward black).
# More photons per pass, as the 512² camera's gather radii are 8 times smaller than at 64².
scene=$(resized scenes/mirror_caustic.json $SIZE $SIZE); TEMPORARY+=("$scene")
render mirror_caustic_512 "scenes/mirror_caustic.json (${SIZE}²)" "$scene" --integrator photon \
  --photons 1048576 --time 90

# The glossy Cornell box: a tabulated 12° lobe on the floor; backward has the lowest error at
# equal time over all pixels (the lamp and its reflection included).
scene=$(resized scenes/glossy_cornell_box.json $SIZE $SIZE); TEMPORARY+=("$scene")
render glossy_cornell_box_512 "scenes/glossy_cornell_box.json (${SIZE}²)" "$scene" \
  --integrator backward --time 60

# Glass and metal (docs/materials.md): caustics through glass onto the fluorescent floor are what
# photon mapping exists for; light tracing cannot see smooth glass, backward finds the caustics
# only by rare paths.
for name in glass_caustic glass_of_water still_life; do
  scene=$(resized scenes/$name.json $SIZE $SIZE); TEMPORARY+=("$scene")
  render ${name}_512 "scenes/$name.json (${SIZE}²)" "$scene" --integrator photon \
    --photons 1048576 --time 90
done

# Lights that are not shapes (docs/lights.md): the booth's samples under a point-like UV spot
# (invisible; only what fluoresces shows it), and a table in the sun and sky of an environment
# image, whose sun casts a caustic through the glass.
scene=$(resized scenes/light_booth_uv_spot.json $SIZE $SIZE); TEMPORARY+=("$scene")
render light_booth_uv_spot_512 "scenes/light_booth_uv_spot.json (${SIZE}²)" "$scene" \
  --integrator backward --time 60
scene=$(resized scenes/sunlit_table.json $SIZE $SIZE); TEMPORARY+=("$scene")
render sunlit_table_512 "scenes/sunlit_table.json (${SIZE}²)" "$scene" --integrator photon \
  --photons 1048576 --time 90

# Textures (docs/textures.md): a colour print with an invisible fluorescent ink star, under a dim
# D65 and the UV spot.
scene=$(resized scenes/fluorescent_print.json $SIZE $SIZE); TEMPORARY+=("$scene")
render fluorescent_print_512 "scenes/fluorescent_print.json (${SIZE}²)" "$scene" \
  --integrator backward --time 60

# Coated surfaces and shading normals (docs/materials.md#coated-surfaces,
# docs/formats.md#shading-normals): the measured Post-it under a clear lacquer on a smooth-shaded
# vase, a glazed brightened paper on a coarse sphere with smooth normals, a lacquered table.
scene=$(resized scenes/lacquered_vase.json $SIZE $SIZE); TEMPORARY+=("$scene")
render lacquered_vase_512 "scenes/lacquered_vase.json (${SIZE}²)" "$scene" --integrator photon \
  --photons 1048576 --time 90

# A pbrt-v4 scene file (docs/pbrt-import.md): the pbrt Cornell box with its lacquered sphere
# replaced by the measured Post-it from the command line (--material), at 512 × 512 (a copy
# with the Film's resolution changed).
# Participating media: a fluorescent liquid under a lens, and tonic water under a UV spot
# (docs/media.md), at the scenes' 4:3, with vcm (the default): collisions connected and merged
# (docs/media.md#equal-time-the-volumetric-caustic).
for name in volumetric_caustic tonic_under_uv_spot; do
  scene=$(resized scenes/$name.json $SIZE 384); TEMPORARY+=("$scene")
  render ${name}_512 "scenes/$name.json (${SIZE} × 384)" "$scene" --time 90
done

copy=scenes/pbrt/.gallery_cornell_box_${SIZE}.pbrt; TEMPORARY+=("$copy")
sed "s/\"integer xresolution\" \[128\] \"integer yresolution\" \[128\]/\"integer xresolution\" [$SIZE] \"integer yresolution\" [$SIZE]/" \
  scenes/pbrt/cornell_box.pbrt > "$copy"
grep -q "xresolution\" \[$SIZE\]" "$copy" || { echo "gallery: could not resize $copy" >&2; exit 1; }
render pbrt_cornell_box_postit_512 "scenes/pbrt/cornell_box.pbrt (${SIZE}²)" "$copy" \
  --material lacquer=scenes/materials/postit.json --integrator photon --photons 1048576 --time 90

mv "$TIMES.tmp" "$TIMES"
echo "gallery: wrote $GALLERY/*.png and $TIMES"
