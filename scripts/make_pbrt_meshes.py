#!/usr/bin/env python3
"""Writes scenes/pbrt/meshes/torus.ply: scenes/meshes/torus.obj as a binary little-endian PLY
with per-vertex normals (the mean of the faces' normals around each vertex), the kind of file
pbrt-v4 scenes and scanners carry. Run from the repository root; needs no packages."""
import math
import struct

vertices, faces = [], []
with open("scenes/meshes/torus.obj") as obj:
    for line in obj:
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            vertices.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            idx = [int(x.split("/")[0]) - 1 for x in w[1:]]
            for k in range(1, len(idx) - 1):
                faces.append((idx[0], idx[k], idx[k + 1]))

normals = [[0.0, 0.0, 0.0] for _ in vertices]
for a, b, c in faces:
    pa, pb, pc = vertices[a], vertices[b], vertices[c]
    u = [pb[i] - pa[i] for i in range(3)]
    v = [pc[i] - pa[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    for i in (a, b, c):
        for k in range(3):
            normals[i][k] += n[k]
for n in normals:
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    for k in range(3):
        n[k] /= length

with open("scenes/pbrt/meshes/torus.ply", "wb") as ply:
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment scenes/meshes/torus.obj with vertex normals (scripts/make_pbrt_meshes.py)\n"
        f"element vertex {len(vertices)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(faces)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    )
    ply.write(header.encode("ascii"))
    for p, n in zip(vertices, normals):
        ply.write(struct.pack("<6f", *p, *n))
    for f in faces:
        ply.write(struct.pack("<B3i", 3, *f))
print(f"scenes/pbrt/meshes/torus.ply: {len(vertices)} vertices, {len(faces)} triangles")
