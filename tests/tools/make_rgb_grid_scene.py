#!/usr/bin/env python3
"""Writes scenes/pbrt/rgb_grid.pbrt: a blob of coloured smoke as pbrt-v4's "rgbgrid" (6 x 6 x 6
samples). Its absorption's colour changes with every sample (216 colours, more than kasha's 40 bins:
kasha tracks it a bin per component), its scattering is one of two colours times the blob's
density (two components). Usage: python3 tests/tools/make_rgb_grid_scene.py > scenes/pbrt/rgb_grid.pbrt"""
import math

N = 6
HEADER = """# A colour grid in pbrt-v4's scene format (docs/media.md#colour-grids): an "rgbgrid" of 6 x 6 x 6
# samples, a blob of smoke whose absorption changes colour across it (a colour per sample) and whose
# scattering is blue-grey on one side and amber on the other, on a grey floor under a lamp and a
# dim sky. Written by tests/tools/make_rgb_grid_scene.py; the reference
# (tests/data/pbrt-v4/rgb_grid.exr) is pbrt-v4's volpath render.
# `kasha render scenes/pbrt/rgb_grid.pbrt --integrator backward -o rgb_grid.exr`
LookAt 0 1.2 3.0  0 0.5 0  0 1 0
Camera "perspective" "float fov" 38
Film "rgb" "integer xresolution" 96 "integer yresolution" 64

PixelFilter "box" "float xradius" [0.5] "float yradius" [0.5]

WorldBegin

LightSource "infinite" "rgb L" [0.1 0.1 0.1]

AttributeBegin
    AreaLightSource "diffuse" "rgb L" [3 3 3]
    Material "diffuse" "rgb reflectance" [0 0 0]
    Shape "trianglemesh" "point3 P" [-0.3 1.8 -0.3  0.3 1.8 -0.3  0.3 1.8 0.3  -0.3 1.8 0.3]
        "integer indices" [0 1 2  0 2 3]
AttributeEnd

Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-3 0 -3  3 0 -3  3 0 3  -3 0 3] "integer indices" [0 2 1  0 3 2]
"""


def rows(values, per_line=4):
    out = []
    for i in range(0, len(values), per_line):
        out.append("        " + "  ".join(values[i:i + per_line]))
    return "\n".join(out)


def main():
    absorb, scatter = [], []
    for z in range(N):
        for y in range(N):
            for x in range(N):
                f = [(c + 0.5) / N for c in (x, y, z)]
                r2 = sum((c - 0.5) ** 2 for c in f)
                density = math.exp(-r2 / 0.08)
                colour = (0.3 + 0.7 * f[0], 0.3 + 0.7 * f[1], 1.0 - 0.7 * f[2])
                absorb.append(" ".join("%.4f" % (density * c) for c in colour))
                tint = (0.5, 0.6, 0.8) if x < N // 2 else (0.9, 0.6, 0.25)
                scatter.append(" ".join("%.4f" % (density * c) for c in tint))
    print(HEADER)
    print("AttributeBegin")
    print("    Translate 0 0.05 0")
    print("    Rotate 20 0 1 0")
    print('    MakeNamedMedium "smoke" "string type" "rgbgrid"')
    print('        "integer nx" %d "integer ny" %d "integer nz" %d' % (N, N, N))
    print('        "point3 p0" [-0.5 0 -0.5] "point3 p1" [0.5 1 0.5]')
    print('        "float scale" 4 "float g" 0.3')
    print('        "rgb sigma_a" [')
    print(rows(absorb))
    print("        ]")
    print('        "rgb sigma_s" [')
    print(rows(scatter))
    print("        ]")
    print('    MediumInterface "smoke" ""')
    print('    Material "interface"')
    print('    Shape "trianglemesh" "point3 P" [-0.5 0 -0.5  0.5 0 -0.5  0.5 1 -0.5  -0.5 1 -0.5')
    print('                                     -0.5 0 0.5  0.5 0 0.5  0.5 1 0.5  -0.5 1 0.5]')
    print('        "integer indices" [0 2 1  0 3 2  4 5 6  4 6 7  0 1 5  0 5 4  3 7 6  3 6 2')
    print('                           0 4 7  0 7 3  1 2 6  1 6 5]')
    print("AttributeEnd")


main()
