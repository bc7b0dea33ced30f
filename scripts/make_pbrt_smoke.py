#!/usr/bin/python3
"""Writes scenes/pbrt/smoke.pbrt: a grid medium (pbrt-v4's "uniformgrid") of smoke, 12 x 10 x 14
samples of a lopsided blob with ripples (so that a transposed or mirrored grid shows), in a
turned and stretched interface box on a grey floor, under a lamp and a dim sky. kasha's reference
test compares it with pbrt-v4's volpath render (tests/data/pbrt-v4/smoke.exr).

Usage: scripts/make_pbrt_smoke.py [OUT]   (default scenes/pbrt/smoke.pbrt)
"""
import math
import sys

NX, NY, NZ = 12, 10, 14


def stage(eye, sky, lamp):
    """The grid scenes' stage: the camera at `eye` looking at the box, a dim sky, a lamp above,
    a grey floor (make_pbrt_rgb_grid.py shares it)."""
    return """LookAt %s  0 0.5 0  0 1 0
Camera "perspective" "float fov" 38
Film "rgb" "integer xresolution" 96 "integer yresolution" 64

PixelFilter "box" "float xradius" [0.5] "float yradius" [0.5]

WorldBegin

LightSource "infinite" "rgb L" [%s]

AttributeBegin
    AreaLightSource "diffuse" "rgb L" [%s]
    Material "diffuse" "rgb reflectance" [0 0 0]
    Shape "trianglemesh" "point3 P" [-0.3 1.8 -0.3  0.3 1.8 -0.3  0.3 1.8 0.3  -0.3 1.8 0.3]
        "integer indices" [0 1 2  0 2 3]
AttributeEnd

Material "diffuse" "rgb reflectance" [0.5 0.5 0.5]
Shape "trianglemesh" "point3 P" [-3 0 -3  3 0 -3  3 0 3  -3 0 3] "integer indices" [0 2 1  0 3 2]
""" % (eye, sky, lamp)


# The medium "smoke" in its box [-0.5, 0.5] x [0, 1] x [-0.5, 0.5], bounded by interface
# triangles, its normals outwards; it closes the grid's AttributeBegin.
INTERFACE_BOX = """    MediumInterface "smoke" ""
    Material "interface"
    # the grid's box, its normals outwards
    Shape "trianglemesh" "point3 P" [-0.5 0 -0.5  0.5 0 -0.5  0.5 1 -0.5  -0.5 1 -0.5
                                     -0.5 0 0.5  0.5 0 0.5  0.5 1 0.5  -0.5 1 0.5]
        "integer indices" [0 2 1  0 3 2  4 5 6  4 6 7  0 1 5  0 5 4  3 7 6  3 6 2  0 4 7  0 7 3  1 2 6  1 6 5]
AttributeEnd
"""


def density(x, y, z):
    """The smoke at the cell centre (x, y, z) in the unit cube."""
    r2 = (x - 0.45) ** 2 + 2 * (y - 0.4) ** 2 + 0.7 * (z - 0.55) ** 2
    return max(0.0, 2.5 * math.exp(-r2 / 0.05) * (1 + 0.6 * math.sin(11 * x + 4 * z + 3 * y)))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/pbrt/smoke.pbrt"
    values = [density((i + 0.5) / NX, (j + 0.5) / NY, (k + 0.5) / NZ)
              for k in range(NZ) for j in range(NY) for i in range(NX)]
    lines = []
    for start in range(0, len(values), NX):
        lines.append("        " + " ".join("%.4f" % v for v in values[start:start + NX]))
    with open(out, "w") as f:
        f.write("""# A grid medium in pbrt-v4's scene format (docs/media.md#grid-media): smoke on a grid of
# %d x %d x %d density samples ("uniformgrid", x fastest), blue-white and forward-scattering, in an
# interface box turned 25 degrees and stretched, on a grey floor under a lamp and a dim sky.
# Written by scripts/make_pbrt_smoke.py. The reference (tests/data/pbrt-v4/smoke.exr) is
# pbrt-v4's volpath render.
# `kasha render scenes/pbrt/smoke.pbrt --integrator backward -o smoke.exr`
""" % (NX, NY, NZ) + stage("0 1.3 3.4", "0.2 0.2 0.2", "6 6 5") + """
AttributeBegin
    Translate 0 0.05 0
    Rotate 25 0 1 0
    Scale 1.3 1.1 0.9
    MakeNamedMedium "smoke" "string type" "uniformgrid" "rgb sigma_a" [0.1 0.1 0.1]
        "rgb sigma_s" [1.2 1.5 2.0] "float scale" 1.5 "float g" 0.4
        "integer nx" %d "integer ny" %d "integer nz" %d
        "point3 p0" [-0.5 0 -0.5] "point3 p1" [0.5 1 0.5]
        "float density" [
%s
        ]
""" % (NX, NY, NZ, "\n".join(lines)) + INTERFACE_BOX)


if __name__ == "__main__":
    main()
