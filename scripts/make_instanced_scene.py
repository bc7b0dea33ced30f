#!/usr/bin/env python3
"""Writes a pbrt-v4 scene that instances one object many times, for measuring how loading scales
with instances (issue 41; docs/pbrt-import.md#bitterlis-collection).

Usage: scripts/make_instanced_scene.py OUT.pbrt [N]

The object is a UV sphere of 200 triangles (`ObjectBegin`), placed N times (default 100 000,
rounded down to a square grid: 99 856) with `ObjectInstance` on a grid 3 units apart, under a
uniform sky, seen by a 64 × 64 camera.
"""
import math
import sys


def ball(nu=10, nv=10):
    points, indices = [], []
    for j in range(nv + 1):
        theta = math.pi * j / nv
        for i in range(nu):
            phi = 2 * math.pi * i / nu
            points.append((math.sin(theta) * math.cos(phi), math.cos(theta),
                           math.sin(theta) * math.sin(phi)))
    for j in range(nv):
        for i in range(nu):
            a, b = j * nu + i, j * nu + (i + 1) % nu
            c, d = (j + 1) * nu + i, (j + 1) * nu + (i + 1) % nu
            indices += [a, c, b, b, c, d]
    return points, indices


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    side = int(math.isqrt(int(sys.argv[2]) if len(sys.argv) == 3 else 100000))
    points, indices = ball()
    with open(sys.argv[1], "w") as f:
        f.write('LookAt 0 120 -400  0 0 0  0 1 0\nCamera "perspective" "float fov" 40\n'
                'Film "rgb" "integer xresolution" 64 "integer yresolution" 64\n'
                'WorldBegin\nLightSource "infinite" "rgb L" [1 1 1]\n')
        f.write('ObjectBegin "ball"\nMaterial "diffuse"\nShape "trianglemesh" "point3 P" [%s] '
                '"integer indices" [%s]\nObjectEnd\n'
                % (" ".join("%g %g %g" % p for p in points), " ".join(map(str, indices))))
        for x in range(side):
            for z in range(side):
                f.write('AttributeBegin\nTranslate %d 0 %d\nObjectInstance "ball"\nAttributeEnd\n'
                        % (3 * (x - side // 2), 3 * (z - side // 2)))


if __name__ == "__main__":
    main()
