#!/usr/bin/env python3
"""Assembles Benedikt Bitterli's rendering resources in pbrt-v4 form (the public snapshot of
gonsolo/bitterli) into a folder both kasha and pbrt-v4 can render.

Usage: scripts/assemble_bitterli.py GIT_DIR OUT_DIR
  GIT_DIR: the snapshot's git directory (what `fetch github:gonsolo/bitterli` returns).
  OUT_DIR: gets one folder per scene, each with the scene's pbrt/ folder.

The snapshot leaves out blobs over its size limit. In the copy, for both renderers alike:
- a missing texture or environment map becomes a small neutral stand-in of the same format
  (TGA, PNG, PFM, EXR: mid grey 0.5, linear for float formats);
- a Shape statement whose mesh file is missing is commented out;
- an Include/Import of a missing file is commented out (the hair scenes).
Everything else is the snapshot's bytes. Prints one line per stand-in and left-out shape, and
writes OUT_DIR/ASSEMBLED.txt listing them.
"""
import os
import struct
import subprocess
import sys
import zlib

TEXTURE_FORMATS = (".tga", ".png", ".pfm", ".exr")


def git(gitdir, *args, binary=False):
    out = subprocess.run(["git", "-C", gitdir, *args], capture_output=True, check=False)
    return out.stdout if binary else out.stdout.decode()


def write_tga(path, size=4, grey=128):
    # Uncompressed 24-bit true-colour TGA.
    header = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, size, size, 24, 0)
    with open(path, "wb") as f:
        f.write(header + bytes([grey]) * (3 * size * size))


def write_png(path, size=4, grey=128):
    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes([grey]) * (3 * size) for _ in range(size))
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def write_pfm(path, size=8, value=0.5):
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (size, size))
        f.write(struct.pack("<%df" % (3 * size * size), *([value] * (3 * size * size))))


def write_exr(path, size=8, value=0.5):
    # A scanline, uncompressed, 32-bit float RGB OpenEXR file.
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chans = b"".join(bytes([c]) + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in b"BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, size - 1, size - 1)
    header = b"\x76\x2f\x31\x01" + struct.pack("<i", 2)
    header += attr("channels", "chlist", chans) + attr("compression", "compression", b"\0")
    header += attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box)
    header += attr("lineOrder", "lineOrder", b"\0") + attr("pixelAspectRatio", "float", struct.pack("<f", 1))
    header += attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
    header += attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0"
    line = struct.pack("<%df" % (3 * size), *([value] * (3 * size)))
    first = len(header) + 8 * size
    offsets = b"".join(struct.pack("<Q", first + y * (8 + len(line))) for y in range(size))
    body = b"".join(struct.pack("<ii", y, len(line)) + line for y in range(size))
    with open(path, "wb") as f:
        f.write(header + offsets + body)


STANDINS = {".tga": write_tga, ".png": write_png, ".pfm": write_pfm, ".exr": write_exr}

from pbrt_statements import statements


def prune_scene(path, scene_dir, log):
    text = open(path, encoding="utf-8", errors="surrogateescape").read()
    out, last = [], 0
    for start, end, directive, toks in statements(text):
        files = [t.strip('"') for t in toks if t.startswith('"')]
        for f in files if directive in ("Texture", "LightSource") else []:
            target = os.path.join(scene_dir, f)
            ext = os.path.splitext(f)[1].lower()
            if ext in STANDINS and not os.path.exists(target):
                # e.g. living-room's "Sky 19.pfm", held only as an absent .xz
                os.makedirs(os.path.dirname(target), exist_ok=True)
                STANDINS[ext](target)
                log.append("stand-in: %s" % os.path.relpath(target))
        if directive == "Shape":
            names = [f for f in files if f.endswith((".ply", ".ply.gz", ".obj"))]
        elif directive in ("Include", "Import"):
            names = files[:1]
        else:
            continue
        missing = [f for f in names if not os.path.exists(os.path.join(scene_dir, f))]
        if not missing:
            continue
        out.append(text[last:start])
        body = text[start:end].replace("\n", "\n# ")
        out.append("# [assemble_bitterli: %s absent] %s" % (missing[0], body))
        last = end
        log.append("left out: %s: %s (%s absent)" % (os.path.relpath(path), directive, missing[0]))
    if out:
        out.append(text[last:])
        with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write("".join(out))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    gitdir, outdir = sys.argv[1], sys.argv[2]
    log = []
    for line in git(gitdir, "ls-tree", "-r", "HEAD").splitlines():
        meta, path = line.split("\t", 1)
        _, kind, sha = meta.split()
        if kind != "blob" or "/pbrt/" not in path:
            continue
        dest = os.path.join(outdir, path)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        data = subprocess.run(["git", "-C", gitdir, "cat-file", "blob", sha], capture_output=True)
        if data.returncode == 0:
            with open(dest, "wb") as f:
                f.write(data.stdout)
            continue
        ext = os.path.splitext(path)[1].lower()
        if ext in STANDINS:
            STANDINS[ext](dest)
            log.append("stand-in: %s" % path)
        else:
            log.append("absent: %s" % path)
    for scene in sorted(os.listdir(outdir)):
        pdir = os.path.join(outdir, scene, "pbrt")
        if not os.path.isdir(pdir):
            continue
        for root, _, names in os.walk(pdir):
            for n in names:
                if n.endswith(".pbrt"):
                    prune_scene(os.path.join(root, n), pdir, log)
    with open(os.path.join(outdir, "ASSEMBLED.txt"), "w") as f:
        f.write("\n".join(log) + "\n")
    print("\n".join(log))


if __name__ == "__main__":
    main()
