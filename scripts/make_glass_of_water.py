#!/usr/bin/python3
"""Writes the meshes of scenes/glass_of_water.json: a clear tumbler, 60 % full of water.

The tumbler is a lathe (surface of revolution about the y axis, 96 segments around): outer
radius 0.23 at the foot widening to 0.25 at the rim, wall 0.015 thick, base 0.04 thick, height
0.6, a rounded foot edge, a half-round lip and a fillet where the inner wall meets the base.
The water fills 60 % of the inside depth (water line at y = 0.376). The mesh stands on y = 0
(the scene lifts it by 1 mm so that its foot is not coplanar with the floor).

The glass and the water are not modelled as two solids but as their three interfaces, one OBJ
each, because a kasha dielectric is one interface: its eta is the index BEHIND the surface over
the index IN FRONT of it, the front being the side the triangle normal (v1 - v0) x (v2 - v0)
points to (docs/materials.md).

  OBJ (scenes/meshes/)               surface                               front    eta
  glass_of_water_glass.obj           foot, outer wall, lip, inner wall     air      1.5
                                     above the water line
  glass_of_water_glass_water.obj     inner wall below the water line,      water    1.5 / 1.33
                                     inner base
  glass_of_water_water_surface.obj   the water's free surface (a disc)     air, +y  1.33

The three meet on shared rings of identical vertices (the same numbers printed the same way),
so the interfaces are watertight: glass + glass_water enclose the glass, glass_water +
water_surface enclose the water, with no gap or overlap. Before writing, the script checks the
winding of every triangle (see check()) and the closedness and orientation of both solids.

Usage: python3 scripts/make_glass_of_water.py [--segments 96] [--out scenes/meshes]
"""
import argparse
import math
import os
import sys

# Dimensions (scene units; the Cornell box is 2 wide).
R_FOOT = 0.23       # outer radius at y = 0
R_RIM = 0.25        # outer radius at y = HEIGHT
WALL = 0.015        # wall thickness (horizontal)
BASE = 0.04         # thickness of the base
HEIGHT = 0.6        # overall height, lip included
FILL = 0.6          # fraction of the inside depth (BASE .. HEIGHT) filled with water
FOOT_ROUND = 0.006  # radius of the rounded outer foot edge
FILLET = 0.012      # radius of the fillet between inner wall and inner base
ARC_FOOT = 4        # profile segments of the foot rounding
ARC_LIP = 8         # profile segments of the half-round lip
ARC_FILLET = 4      # profile segments of the inner fillet

ETA_GLASS = 1.5
ETA_WATER = 1.33
WATER_LINE = BASE + FILL * (HEIGHT - BASE)


def r_out(y):
    return R_FOOT + (R_RIM - R_FOOT) * y / HEIGHT


def r_in(y):
    return r_out(y) - WALL


def arc(cr, cy, radius, deg0, deg1, n):
    """Points of a circular arc in the (r, y) plane, the first one left out."""
    pts = []
    for i in range(1, n + 1):
        a = math.radians(deg0 + (deg1 - deg0) * i / n)
        pts.append((cr + radius * math.cos(a), cy + radius * math.sin(a)))
    return pts


def profiles():
    """The meridian profiles (r, y), each running so that the glass lies on its left when r
    points right and y up (counter-clockwise around the glass's cross-section)."""
    # air | glass: from the foot's centre out, up the outer wall, over the lip, down the inside
    # to the water line.
    glass = [(0.0, 0.0)]
    foot_y = FOOT_ROUND
    foot_c = (r_out(foot_y) - FOOT_ROUND, foot_y)
    glass.append((foot_c[0], 0.0))
    glass += arc(foot_c[0], foot_c[1], FOOT_ROUND, -90.0, 0.0, ARC_FOOT)   # ends at (r_out, foot_y)
    lip_y = HEIGHT - WALL / 2
    glass.append((r_out(lip_y), lip_y))
    lip_c = ((r_out(lip_y) + r_in(lip_y)) / 2, lip_y)
    glass += arc(lip_c[0], lip_c[1], WALL / 2, 0.0, 180.0, ARC_LIP)        # ends at (r_in, lip_y)
    water_ring = (r_in(WATER_LINE), WATER_LINE)
    glass.append(water_ring)
    # glass | water: from the water line down the inner wall, round the fillet, to the centre
    # of the inner base.
    fil_y = BASE + FILLET
    fil_c = (r_in(fil_y) - FILLET, fil_y)
    gw = [water_ring, (r_in(fil_y), fil_y)]
    gw += arc(fil_c[0], fil_c[1], FILLET, 0.0, -90.0, ARC_FILLET)          # ends at (fil_c.r, BASE)
    gw.append((0.0, BASE))
    # water | air: the surface, from the wall's ring to the axis.
    surface = [water_ring, (0.0, WATER_LINE)]
    return glass, gw, surface


def fmt(x):
    s = "%.7f" % x
    return "0.0000000" if s == "-0.0000000" else s


class Mesh:
    """Triangles over vertices named by their printed coordinates: two meshes that print a
    vertex the same way share it exactly once loaded (the renderer parses the same text)."""

    def __init__(self):
        self.index = {}
        self.verts = []
        self.tris = []

    def vertex(self, r, y, j, segments):
        if r == 0.0:
            p = (fmt(0.0), fmt(y), fmt(0.0))
        else:
            a = 2.0 * math.pi * (j % segments) / segments
            p = (fmt(r * math.cos(a)), fmt(y), fmt(r * math.sin(a)))
        if p not in self.index:
            self.index[p] = len(self.verts)
            self.verts.append(p)
        return self.index[p]

    def lathe(self, profile, segments):
        """Revolves the profile about y. The triangles' normals point to the profile's right
        (the profile's direction turned clockwise in the (r, y) plane)."""
        for (r0, y0), (r1, y1) in zip(profile, profile[1:]):
            for j in range(segments):
                a0 = self.vertex(r0, y0, j, segments)
                a1 = self.vertex(r0, y0, j + 1, segments)
                b0 = self.vertex(r1, y1, j, segments)
                b1 = self.vertex(r1, y1, j + 1, segments)
                if r0 != 0.0:
                    self.tris.append((a0, b0, a1))
                if r1 != 0.0:
                    self.tris.append((a1, b0, b1))

    def flipped(self):
        m = Mesh()
        m.index, m.verts = dict(self.index), list(self.verts)
        m.tris = [(a, c, b) for a, b, c in self.tris]
        return m

    def pos(self, i):
        return tuple(float(c) for c in self.verts[i])

    def triangles(self):
        for t in self.tris:
            yield tuple(self.pos(i) for i in t)

    def write(self, path, comment):
        with open(path, "w") as f:
            for line in comment:
                f.write("# %s\n" % line)
            for v in self.verts:
                f.write("v %s %s %s\n" % v)
            for a, b, c in self.tris:
                f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normal_and_centroid(t):
    n = cross(sub(t[1], t[0]), sub(t[2], t[0]))
    c = tuple((t[0][k] + t[1][k] + t[2][k]) / 3 for k in range(3))
    return n, c


def inside(poly, r, y):
    """Even-odd test of the point (r, y) against a closed polygon in the (r, y) plane."""
    hit = False
    for (r0, y0), (r1, y1) in zip(poly, poly[1:] + poly[:1]):
        if (y0 > y) != (y1 > y) and r < r0 + (y - y0) * (r1 - r0) / (y1 - y0):
            hit = not hit
    return hit


def closed_and_oriented(name, meshes):
    """Every directed edge of the union (by vertex position) has exactly one reverse twin."""
    edges = {}
    for m in meshes:
        for a, b, c in m.tris:
            for e in ((a, b), (b, c), (c, a)):
                key = (m.verts[e[0]], m.verts[e[1]])
                edges[key] = edges.get(key, 0) + 1
    bad = [e for e, k in edges.items() if k != 1 or edges.get((e[1], e[0])) != 1]
    assert not bad, "%s: %d edges unpaired or repeated, e.g. %s" % (name, len(bad), bad[:2])


def volume(meshes):
    v = 0.0
    for m in meshes:
        for t in m.triangles():
            v += dot(t[0], cross(t[1], t[2])) / 6.0
    return v


def pappus(poly):
    """Volume of the solid swept by the closed (r, y) polygon: 2 pi * area * centroid radius."""
    s = 0.0
    for (r0, y0), (r1, y1) in zip(poly, poly[1:] + poly[:1]):
        a = r0 * y1 - r1 * y0
        s += a * (r0 + r1)
    return math.pi * abs(s) / 3.0


def check(glass, gw, surface, p_glass, p_gw, p_surface, segments):
    """Winding checks. Raises AssertionError on the first wrong triangle."""
    glass_poly = p_glass[:-1] + p_gw            # the glass's cross-section, closed along the axis
    water_poly = p_gw + [p_surface[-1]]         # the water's: down the wall, the axis, the surface
    eps = 1e-3  # well above the facets' sag (r (1 - cos(pi / segments)) ~ 1.3e-4), below the wall
    count = {}

    def radial(c):
        d = math.hypot(c[0], c[2])
        return (c[0] / d, 0.0, c[2] / d)

    def side_test(t, n, c, solid, outward, what):
        # A point just in front of the triangle must be outside `solid` (outward) or inside it.
        ln = math.sqrt(dot(n, n))
        assert ln > 0, "%s: a zero-area triangle" % what
        r_c = math.hypot(c[0], c[2])
        front = (c[0] + eps * n[0] / ln, c[1] + eps * n[1] / ln, c[2] + eps * n[2] / ln)
        back = (c[0] - eps * n[0] / ln, c[1] - eps * n[1] / ln, c[2] - eps * n[2] / ln)
        f_in = inside(solid, math.hypot(front[0], front[2]), front[1])
        b_in = inside(solid, math.hypot(back[0], back[2]), back[1])
        assert f_in != outward and b_in == outward, \
            "%s: triangle at r=%.4f y=%.4f faces the wrong way" % (what, r_c, c[1])

    for t in glass.triangles():
        n, c = normal_and_centroid(t)
        side_test(t, n, c, glass_poly, True, "glass (air|glass)")
        rc = math.hypot(c[0], c[2])
        if c[1] < 1e-9:                                          # outer foot, flat part
            assert n[1] < 0 and abs(n[0]) + abs(n[2]) < 1e-9 * abs(n[1]), "foot faces -y"
            count["foot"] = count.get("foot", 0) + 1
        elif FOOT_ROUND < c[1] < HEIGHT - WALL / 2 and rc > r_out(c[1]) - WALL / 2:
            assert dot(n, radial(c)) > 0, "outer wall faces away from the axis"  # outer wall
            count["outer wall"] = count.get("outer wall", 0) + 1
        elif WATER_LINE < c[1] < HEIGHT - WALL / 2 and rc < r_in(c[1]) + WALL / 2:
            assert dot(n, radial(c)) < 0, "inner wall (air) faces the axis"      # inner, air
            count["inner wall, air"] = count.get("inner wall, air", 0) + 1
    for t in gw.triangles():
        n, c = normal_and_centroid(t)
        side_test(t, n, c, glass_poly, True, "glass_water (glass|water)")
        side_test(t, n, c, water_poly, False, "glass_water (glass|water)")
        if c[1] > BASE + FILLET:                                     # inner wall, water
            assert dot(n, radial(c)) < 0, "glass-water wall faces the axis"
            count["inner wall, water"] = count.get("inner wall, water", 0) + 1
        elif abs(c[1] - BASE) < 1e-9:                               # inner base
            assert n[1] > 0 and abs(n[0]) + abs(n[2]) < 1e-9 * n[1], "inner base faces +y"
            count["inner base"] = count.get("inner base", 0) + 1
    for t in surface.triangles():
        n, c = normal_and_centroid(t)
        side_test(t, n, c, water_poly, True, "water_surface (water|air)")
        assert n[1] > 0 and abs(n[0]) + abs(n[2]) < 1e-9 * n[1], "water surface faces +y"
        count["water surface"] = count.get("water surface", 0) + 1
    for part, want in (("foot", segments), ("outer wall", 2 * segments),
                       ("inner wall, air", 2 * segments), ("inner wall, water", 2 * segments),
                       ("inner base", segments), ("water surface", segments)):
        assert count.get(part) == want, "%s: %s triangles checked, %d expected" % (
            part, count.get(part), want)

    # Both solids closed, consistently wound, fronts outward: glass + glass_water bound the
    # glass with normals out of the glass; water_surface + glass_water (reversed) bound the
    # water with normals out of the water.
    closed_and_oriented("glass solid", [glass, gw])
    closed_and_oriented("water solid", [surface, gw.flipped()])
    facet = segments * math.sin(2 * math.pi / segments) / (2 * math.pi)  # polygon / circle area
    for name, meshes, poly in (("glass", [glass, gw], glass_poly),
                               ("water", [surface, gw.flipped()], water_poly)):
        v, v0 = volume(meshes), pappus(poly) * facet
        assert v > 0 and abs(v - v0) < 1e-3 * v0, "%s volume %.6g, expected %.6g" % (name, v, v0)
        print("%s: volume %.6f (lathe %.6f), closed, fronts outward" % (name, v, v0))
    return count


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--segments", type=int, default=96)
    ap.add_argument("--out", default=os.path.join(here, "..", "scenes", "meshes"))
    args = ap.parse_args()
    if args.segments < 3:
        sys.exit("--segments must be at least 3")

    p_glass, p_gw, p_surface = profiles()
    glass, gw, surface = Mesh(), Mesh(), Mesh()
    glass.lathe(p_glass, args.segments)
    gw.lathe(p_gw, args.segments)
    surface.lathe(p_surface, args.segments)
    count = check(glass, gw, surface, p_glass, p_gw, p_surface, args.segments)

    head = "glass of water (scripts/make_glass_of_water.py, %d segments): " % args.segments
    files = (
        ("glass_of_water_glass.obj", glass,
         ["air | glass: foot, outer wall, lip, inner wall above the water line",
          "front = air, material eta = %g" % ETA_GLASS]),
        ("glass_of_water_glass_water.obj", gw,
         ["glass | water: inner wall below the water line, inner base",
          "front = water, material eta = %g / %g = %.6f" % (ETA_GLASS, ETA_WATER,
                                                          ETA_GLASS / ETA_WATER)]),
        ("glass_of_water_water_surface.obj", surface,
         ["water | air: the water surface at y = %g, front = air (+y)" % WATER_LINE,
          "material eta = %g" % ETA_WATER]),
    )
    os.makedirs(args.out, exist_ok=True)
    for name, mesh, comment in files:
        path = os.path.join(args.out, name)
        mesh.write(path, [head + comment[0]] + comment[1:])
        print("%s: %d vertices, %d triangles" % (os.path.normpath(path), len(mesh.verts),
                                                 len(mesh.tris)))
    print("checked: " + ", ".join("%s %d" % kv for kv in sorted(count.items())))


if __name__ == "__main__":
    main()
