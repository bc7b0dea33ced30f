#!/usr/bin/python3
"""Per-region comparison of kasha's image of a pbrt-v4 scene with pbrt-v4's (issue 41).

Usage: scripts/pbrt_regions.py KASHA IMGTOOL SCENE.pbrt REFERENCE IMAGE [--min-pixels N]

`kasha regions` groups the pixels by the shape they see (from SCENE, whose camera made both
images). For each shape seen by at least N pixels (default 200) this prints the reference's mean
Y, the image's mean relative to it, and the difference in units of its standard error. The
standard error is that of the per-pixel difference image (IMAGE − REFERENCE), so the scene's own
structure cancels and what is left is the two renders' noise: |z| above 4 is a difference the noise
does not explain. IMGTOOL is pbrt-v4's (reads and writes the EXR files).
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pbrt_compare import read_exr  # noqa: E402


def write_exr(imgtool, path, img, tmp):
    pfm = os.path.join(tmp, "diff.pfm")
    h, w, _ = img.shape
    with open(pfm, "wb") as f:
        f.write(b"PF\n%d %d\n-1\n" % (w, h))
        f.write(img[::-1].astype("<f4").tobytes())
    subprocess.run([imgtool, "convert", "--outfile", path, pfm], check=True, capture_output=True)


def regions(kasha, scene, image, tmp, name):
    out = os.path.join(tmp, name + ".json")
    subprocess.run([kasha, "regions", scene, image, "--json", out], check=True,
                   capture_output=True)
    with open(out) as f:
        return {r["shape"]: r for r in json.load(f)["regions"]}


def main():
    args = sys.argv[1:]
    min_pixels = 200
    if "--min-pixels" in args:
        i = args.index("--min-pixels")
        min_pixels = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 5:
        sys.exit(__doc__)
    kasha, imgtool, scene, reference, image = args
    ref, img = read_exr(imgtool, reference), read_exr(imgtool, image)
    if ref.shape != img.shape:
        sys.exit("%s is not the reference's size" % image)
    with tempfile.TemporaryDirectory() as tmp:
        diff_path = os.path.join(tmp, "diff.exr")
        write_exr(imgtool, diff_path, img - ref, tmp)
        base = regions(kasha, os.path.abspath(scene), os.path.abspath(reference), tmp, "ref")
        diff = regions(kasha, os.path.abspath(scene), diff_path, tmp, "diff")
    worst = 0.0
    print("%5s  %-28s %7s  %10s  %8s  %6s" % ("shape", "material", "pixels", "ref Y", "image/ref",
                                               "z"))
    for shape, r in sorted(base.items()):
        if r["pixels"] < min_pixels or r.get("emitter") or shape not in diff:
            continue
        y, d, se = r["XYZ"][1], diff[shape]["XYZ"][1], diff[shape]["standard_error"][1]
        z = d / se if se > 0 else 0.0
        worst = max(worst, abs(z))
        print("%5d  %-28s %7d  %10.5g  %8.4f  %+6.2f" % (shape, r["material"][:28], r["pixels"], y,
                                                        1 + d / y if y else float("nan"), z))
    print("largest |z|: %.2f" % worst)


if __name__ == "__main__":
    main()
