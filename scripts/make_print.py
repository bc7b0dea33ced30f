#!/usr/bin/env python3
"""Writes the two textures of scenes/fluorescent_print.json (docs/textures.md), 8-bit sRGB PNGs:
scenes/data/print_colour.png, a colour print of cyan, magenta and yellow discs and a black bar on
white paper, and scenes/data/print_ink.png, the mask of an invisible fluorescent ink: a white
five-pointed star on black. Standard library only.
    python3 scripts/make_print.py [OUT_DIR]
"""
import math
import os
import struct
import sys
import zlib

out_dir = sys.argv[1] if len(sys.argv) > 1 else "scenes/data"
N = 256


def write_png(path, rows):
    raw = b"".join(b"\0" + bytes(v for px in row for v in px) for row in rows)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 8, 2, 0, 0, 0))
           + chunk(b"sRGB", b"\0") + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)
    print("wrote", path)


def colour(x, y):
    # Subtractive: each disc's ink takes away one primary; overlaps take away both.
    r = g = b = 250
    for cx, cy, ink in ((0.36, 0.4, "c"), (0.64, 0.4, "m"), (0.5, 0.64, "y")):
        if (x - cx) ** 2 + (y - cy) ** 2 < 0.2 ** 2:
            if ink == "c":
                r = int(r * 0.15)
            if ink == "m":
                g = int(g * 0.15)
            if ink == "y":
                b = int(b * 0.1)
    if 0.15 < x < 0.85 and 0.86 < y < 0.9:
        r = g = b = 20
    return (r, g, b)


def in_star(x, y):
    # A five-pointed star centred at (0.5, 0.5): inside where the polar radius is below the
    # star's outline at that angle.
    dx, dy = x - 0.5, 0.52 - y
    r, a = math.hypot(dx, dy), math.atan2(dy, dx) - math.pi / 2
    k = (a % (2 * math.pi / 5)) / (2 * math.pi / 5)
    outer, inner = 0.42, 0.17
    t = abs(k - 0.5) * 2  # 1 at a point, 0 between two
    return r < inner + (outer - inner) * t ** 1.6


os.makedirs(out_dir, exist_ok=True)
write_png(os.path.join(out_dir, "print_colour.png"),
          [[colour((i + 0.5) / N, (j + 0.5) / N) for i in range(N)] for j in range(N)])
write_png(os.path.join(out_dir, "print_ink.png"),
          [[(255, 255, 255) if in_star((i + 0.5) / N, (j + 0.5) / N) else (0, 0, 0)
            for i in range(N)] for j in range(N)])
