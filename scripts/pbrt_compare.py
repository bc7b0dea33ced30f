#!/usr/bin/python3
"""Compares kasha's image of a pbrt-v4 scene with pbrt-v4's, as issue 41's tables do.

Usage: scripts/pbrt_compare.py IMGTOOL REFERENCE IMAGE [IMAGE ...] [--percentile P]

REFERENCE and each IMAGE are EXR files with R, G, B channels in linear sRGB (kasha's and
pbrt-v4's both write them); IMGTOOL is pbrt-v4's `imgtool` (built beside `pbrt`), used to turn
each EXR into a PFM that numpy reads. Over the pixels whose reference luminance is below the
reference's P-th percentile (99.5: the lamps and their sharp reflections left out, where one
firefly moves a mean), prints per image its channel means relative to the reference's (1 = the
same), and its RMSE against the reference over those pixels and over all pixels.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        n = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, n)[::-1].astype(np.float64)


def read_exr(imgtool, path):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "image.pfm")
        subprocess.run([imgtool, "convert", "--channels", "R,G,B", "--outfile", out, path],
                       check=True, capture_output=True)
        return read_pfm(out)


def main():
    args = [a for a in sys.argv[1:]]
    percentile = 99.5
    if "--percentile" in args:
        i = args.index("--percentile")
        percentile = float(args[i + 1])
        del args[i:i + 2]
    if len(args) < 3:
        sys.exit(__doc__)
    imgtool, reference, images = args[0], args[1], args[2:]
    ref = read_exr(imgtool, reference)
    lum = ref @ np.array([0.2126, 0.7152, 0.0722])
    mask = lum <= np.percentile(lum, percentile)
    ref_means = ref[mask].mean(axis=0)
    print("reference %s: %dx%d, %d pixels below the %.1fth luminance percentile, means %s"
          % (reference, ref.shape[1], ref.shape[0], mask.sum(), percentile,
             " ".join("%.5g" % m for m in ref_means)))
    rmses = {}
    for path in images:
        img = read_exr(imgtool, path)
        if img.shape != ref.shape:
            print("%s: %dx%d, not the reference's size" % (path, img.shape[1], img.shape[0]))
            continue
        ratio = img[mask].mean(axis=0) / ref_means
        rmse_masked = np.sqrt(((img[mask] - ref[mask]) ** 2).mean())
        rmse_all = np.sqrt(((img - ref) ** 2).mean())
        print("%s: means R %.4f G %.4f B %.4f of the reference; RMSE %.5g (masked) %.5g (all)"
              % (path, ratio[0], ratio[1], ratio[2], rmse_masked, rmse_all))
        rmses[path] = rmse_all
    # Images named *.pbrt-INTEGRATOR.exr are pbrt-v4's (scripts/equal_time_pbrt.sh): the others'
    # RMSE against the best of them.
    theirs = [r for p, r in rmses.items() if ".pbrt-" in os.path.basename(p)]
    if theirs:
        for p, r in rmses.items():
            if ".pbrt-" not in os.path.basename(p):
                print("%s: RMSE %.3f x pbrt-v4's best" % (p, r / min(theirs)))


if __name__ == "__main__":
    main()
