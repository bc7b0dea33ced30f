#!/usr/bin/env python3
"""Writes scenes/data/sky_sun.exr: a procedural daylight sky for the environment-light scenes, in
the latitude-longitude mapping (docs/lights.md#environment-images; +z up, azimuth from +x towards
+y), linear sRGB in an uncompressed scanline OpenEXR of 32-bit float R, G, B channels.

The sky: a blue zenith fading to a pale horizon, a small warm sun (about 40 000 times the sky's
luminance per texel at 256 x 128: it brings about two thirds of the light reaching the ground),
and a dark brown ground below the horizon. Standard library only.
    python3 scripts/make_sky.py [OUT.exr] [WIDTH]
"""
import math
import struct
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "scenes/data/sky_sun.exr"
width = int(sys.argv[2]) if len(sys.argv) > 2 else 256
height = width // 2

sun = (math.cos(math.radians(35)) * math.cos(math.radians(-50)),
       math.cos(math.radians(35)) * math.sin(math.radians(-50)),
       math.sin(math.radians(35)))  # 35 degrees above the horizon
sun_radius = math.radians(2.5)


def radiance(x, y, z):
    if z < 0:  # the ground
        return (0.08, 0.06, 0.045)
    horizon = (0.75, 0.82, 0.95)
    zenith = (0.18, 0.32, 0.75)
    t = z ** 0.5
    rgb = [h * (1 - t) + k * t for h, k in zip(horizon, zenith)]
    cos_sun = x * sun[0] + y * sun[1] + z * sun[2]
    if cos_sun > math.cos(sun_radius):
        return (900.0, 800.0, 620.0)
    # A glow around the sun.
    glow = 0.6 * math.exp(-(1 - cos_sun) * 40)
    return tuple(c + glow * w for c, w in zip(rgb, (1.0, 0.9, 0.7)))


pixels = []
for row in range(height):
    theta = (row + 0.5) / height * math.pi
    line = []
    for col in range(width):
        phi = (col + 0.5) / width * 2 * math.pi
        line.append(radiance(math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                             math.cos(theta)))
    pixels.append(line)


def attribute(name, kind, data):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data


channels = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
header = (struct.pack("<ii", 20000630, 2)
          + attribute("channels", "chlist", channels)
          + attribute("compression", "compression", b"\0")
          + attribute("dataWindow", "box2i", box)
          + attribute("displayWindow", "box2i", box)
          + attribute("lineOrder", "lineOrder", b"\0")
          + attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
          + attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
          + attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
          + b"\0")
line_bytes = 3 * 4 * width
table_at = len(header)
first = table_at + 8 * height
offsets = b"".join(struct.pack("<Q", first + y * (8 + line_bytes)) for y in range(height))
body = b""
for y, line in enumerate(pixels):
    data = b""
    for channel in (2, 1, 0):  # channels are stored in alphabetical order: B, G, R
        data += struct.pack("<%df" % width, *[p[channel] for p in line])
    body += struct.pack("<ii", y, len(data)) + data
with open(out, "wb") as f:
    f.write(header + offsets + body)
print("wrote %s: %dx%d" % (out, width, height))
