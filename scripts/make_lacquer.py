#!/usr/bin/env python3
"""Writes the smooth-shaded meshes of scenes/lacquered_vase.json (OBJ with `vn` shading normals,
docs/formats.md#shading-normals), standard library only:
  scenes/meshes/lacquered_vase.obj: a vase, a surface of revolution about +y (open at the top),
      48 segments around and 24 rings, the exact normals of the surface at its vertices;
  scenes/meshes/smooth_sphere.obj: a coarse UV sphere (24 around, 12 rings) whose vertex normals
      make it look round.
    python3 scripts/make_lacquer.py [OUT_DIR]
"""
import math
import os
import sys

out_dir = sys.argv[1] if len(sys.argv) > 1 else "scenes/meshes"


def write_revolution(path, radius, slope, y0, y1, rings, segments, comment, caps=False):
    """A surface x = r(y) cos t, z = r(y) sin t; faces wound counter-clockwise seen from the
    outside, normals (cos t, -r'(y), sin t) normalized; with caps, fans closing both ends at
    points on the axis (normals along it)."""
    lines = [f"# {comment} (scripts/make_lacquer.py)"]
    for i in range(rings + 1):
        y = y0 + (y1 - y0) * i / rings
        r, dr = radius(y), slope(y)
        for k in range(segments):
            t = 2 * math.pi * k / segments
            c, s = math.cos(t), math.sin(t)
            n = (c, -dr, s)
            ln = math.sqrt(sum(v * v for v in n))
            lines.append(f"v {r * c:.6f} {y:.6f} {r * s:.6f}")
            lines.append(f"vn {n[0] / ln:.6f} {n[1] / ln:.6f} {n[2] / ln:.6f}")
    def idx(i, k):
        return i * segments + k % segments + 1
    for i in range(rings):
        for k in range(segments):
            a, b, c, d = idx(i, k), idx(i, k + 1), idx(i + 1, k + 1), idx(i + 1, k)
            # Seen from outside (+radial), going up y and around t: (a, d, c) and (a, c, b).
            for tri in ((a, d, c), (a, c, b)):
                lines.append("f " + " ".join(f"{v}//{v}" for v in tri))
    if caps:
        n = (rings + 1) * segments
        lines.append(f"v 0 {y0 - 1e-3:.6f} 0\nvn 0 -1 0\nv 0 {y1 + 1e-3:.6f} 0\nvn 0 1 0")
        bottom, top = n + 1, n + 2
        for k in range(segments):
            a, b = idx(0, k), idx(0, k + 1)
            lines.append(f"f {bottom}//{bottom} {a}//{a} {b}//{b}")
            a, b = idx(rings, k), idx(rings, k + 1)
            lines.append(f"f {top}//{top} {b}//{b} {a}//{a}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


def vase_r(y):
    return 0.1 + 0.12 * math.sin(math.pi * (0.15 + 0.8 * y / 0.8)) ** 2


def vase_dr(y):
    u = math.pi * (0.15 + 0.8 * y / 0.8)
    return 0.12 * 2 * math.sin(u) * math.cos(u) * math.pi * 0.8 / 0.8


os.makedirs(out_dir, exist_ok=True)
write_revolution(os.path.join(out_dir, "lacquered_vase.obj"), vase_r, vase_dr, 0.0, 0.8, 24, 48,
                 "a vase, 0.8 high, open at the top")
# The sphere of radius 1 about the origin, poles excluded by a hair so every ring has a radius.
e = 1e-3
write_revolution(os.path.join(out_dir, "smooth_sphere.obj"),
                 lambda y: math.sqrt(max(0.0, 1 - y * y)),
                 lambda y: -y / math.sqrt(max(1e-12, 1 - y * y)), -1 + e, 1 - e, 12, 24,
                 "a coarse sphere of radius 1 with smooth normals", caps=True)
