#!/usr/bin/python3
"""Writes scenes/pbrt/rgb_grid.pbrt: a blob of coloured smoke as pbrt-v4's "rgbgrid" (6 x 6 x 6
samples) on make_pbrt_smoke.py's stage. Its absorption's colour changes with every sample (216
colours, more than kasha's 40 bins: kasha tracks it a bin per component), its scattering is one of
two colours times the blob's density (two components). kasha's reference test compares it with
pbrt-v4's volpath render (tests/data/pbrt-v4/rgb_grid.exr).

Usage: scripts/make_pbrt_rgb_grid.py [OUT]   (default scenes/pbrt/rgb_grid.pbrt)
"""
import math
import sys

from make_pbrt_smoke import INTERFACE_BOX, stage

N = 6


def rows(values, per_line=4):
    return "\n".join("        " + "  ".join(values[i:i + per_line]) for i in range(0, len(values), per_line))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/pbrt/rgb_grid.pbrt"
    absorb, scatter = [], []
    for z in range(N):
        for y in range(N):
            for x in range(N):
                f = [(c + 0.5) / N for c in (x, y, z)]
                density = math.exp(-sum((c - 0.5) ** 2 for c in f) / 0.08)
                colour = (0.3 + 0.7 * f[0], 0.3 + 0.7 * f[1], 1.0 - 0.7 * f[2])
                absorb.append(" ".join("%.4f" % (density * c) for c in colour))
                tint = (0.5, 0.6, 0.8) if x < N // 2 else (0.9, 0.6, 0.25)
                scatter.append(" ".join("%.4f" % (density * c) for c in tint))
    with open(out, "w") as f:
        f.write("""# A colour grid in pbrt-v4's scene format (docs/media.md#colour-grids): an "rgbgrid" of 6 x 6 x 6
# samples, a blob of smoke whose absorption changes colour across it (a colour per sample) and whose
# scattering is blue-grey on one side and amber on the other, on a grey floor under a lamp and a
# dim sky. Written by scripts/make_pbrt_rgb_grid.py. The reference (tests/data/pbrt-v4/rgb_grid.exr)
# is pbrt-v4's volpath render.
# `kasha render scenes/pbrt/rgb_grid.pbrt --integrator backward -o rgb_grid.exr`
""" + stage("0 1.2 3.0", "0.1 0.1 0.1", "3 3 3") + """
AttributeBegin
    Translate 0 0.05 0
    Rotate 20 0 1 0
    MakeNamedMedium "smoke" "string type" "rgbgrid"
        "integer nx" %d "integer ny" %d "integer nz" %d
        "point3 p0" [-0.5 0 -0.5] "point3 p1" [0.5 1 0.5]
        "float scale" 4 "float g" 0.3
        "rgb sigma_a" [
%s
        ]
        "rgb sigma_s" [
%s
        ]
""" % (N, N, N, rows(absorb), rows(scatter)) + INTERFACE_BOX)


if __name__ == "__main__":
    main()
