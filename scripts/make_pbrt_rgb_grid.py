#!/usr/bin/python3
"""Writes scenes/pbrt/rgb_grid.pbrt: a blob of coloured smoke as pbrt-v4's "rgbgrid" (6 x 6 x 6
samples) on make_pbrt_smoke.py's stage. Its absorption's colour changes with every sample (216
colours, more than kasha's 40 bins: kasha tracks it a bin per component), its scattering is one of
two colours times the blob's density (two components). kasha's reference test compares it with
pbrt-v4's volpath render (tests/data/pbrt-v4/rgb_grid.exr).

With --emitting it writes scenes/pbrt/emitting_rgb_grid.pbrt instead: the same blob also glowing,
its "Le" a colour per sample (orange at the bottom to violet at the top, 6 colours), "Lescale" 0.01,
under a dimmer lamp (reference tests/data/pbrt-v4/emitting_rgb_grid.exr).

Usage: scripts/make_pbrt_rgb_grid.py [--emitting] [OUT]
"""
import math
import sys

from make_pbrt_smoke import INTERFACE_BOX, stage

N = 6


def rows(values, per_line=4):
    return "\n".join("        " + "  ".join(values[i:i + per_line]) for i in range(0, len(values), per_line))


def main():
    args = sys.argv[1:]
    emitting = "--emitting" in args
    args = [a for a in args if a != "--emitting"]
    name = "emitting_rgb_grid" if emitting else "rgb_grid"
    out = args[0] if args else "scenes/pbrt/%s.pbrt" % name
    absorb, scatter, glow = [], [], []
    for z in range(N):
        for y in range(N):
            for x in range(N):
                f = [(c + 0.5) / N for c in (x, y, z)]
                density = math.exp(-sum((c - 0.5) ** 2 for c in f) / 0.08)
                colour = (0.3 + 0.7 * f[0], 0.3 + 0.7 * f[1], 1.0 - 0.7 * f[2])
                absorb.append(" ".join("%.4f" % (density * c) for c in colour))
                tint = (0.5, 0.6, 0.8) if x < N // 2 else (0.9, 0.6, 0.25)
                scatter.append(" ".join("%.4f" % (density * c) for c in tint))
                hue = (1.0 - 0.6 * f[2], 0.5 - 0.3 * f[2], 0.1 + 0.8 * f[2])
                glow.append(" ".join("%.4f" % c for c in hue))
    emission = ""
    if emitting:
        emission = """        "rgb Le" [
%s
        ]
        "float Lescale" 0.01
""" % rows(glow)
    with open(out, "w") as f:
        f.write("""# A colour grid in pbrt-v4's scene format (docs/media.md#colour-grids): an "rgbgrid" of 6 x 6 x 6
# samples, a blob of smoke whose absorption changes colour across it (a colour per sample) and whose
# scattering is blue-grey on one side and amber on the other, on a grey floor under a lamp and a
# dim sky%s. Written by scripts/make_pbrt_rgb_grid.py. The reference
# (tests/data/pbrt-v4/%s.exr) is pbrt-v4's volpath render.
# `kasha render scenes/pbrt/%s.pbrt --integrator backward -o %s.exr`
""" % ("; it glows, an \"Le\" colour per sample" if emitting else "", name, name, name)
                + stage("0 1.2 3.0", "0.1 0.1 0.1", "1 1 1" if emitting else "3 3 3") + """
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
%s""" % (N, N, N, rows(absorb), rows(scatter), emission) + INTERFACE_BOX)


if __name__ == "__main__":
    main()
