#!/usr/bin/env python3
"""Writes a variant of a pbrt-v4 scene for comparisons: another film resolution, integrator,
path length or pixel filter, the rest of the file as it is.

Usage: scripts/pbrt_variant.py SCENE OUT [--res W H] [--integrator NAME] [--maxdepth N]
                                         [--box-filter]
OUT should be in SCENE's folder: Include and file names resolve against the main file's folder.
--res keeps the scene's aspect ratio when H is 0. --box-filter sets pbrt-v4's box filter of
radius 0.5 (kasha's pixels are box-filtered): both renderers then average the same pixel area.
"""
import re
import sys

from pbrt_statements import statements


def param(toks, name):
    """The first value of parameter `name` (e.g. "integer xresolution"), or None."""
    for i, t in enumerate(toks):
        if t.startswith('"') and t.strip('"').split() and t.strip('"').split()[-1] == name:
            j = i + 1
            if toks[j] == "[":
                j += 1
            return toks[j]
    return None


def main():
    a = sys.argv[1:]
    if len(a) < 2:
        sys.exit(__doc__)
    src, out, opts = a[0], a[1], a[2:]
    res = integrator = maxdepth = None
    box = False
    i = 0
    while i < len(opts):
        if opts[i] == "--res":
            res = (int(opts[i + 1]), int(opts[i + 2]))
            i += 3
        elif opts[i] == "--integrator":
            integrator = opts[i + 1]
            i += 2
        elif opts[i] == "--maxdepth":
            maxdepth = int(opts[i + 1])
            i += 2
        elif opts[i] == "--box-filter":
            box = True
            i += 1
        else:
            sys.exit("unknown option " + opts[i])
    text = open(src, encoding="utf-8", errors="surrogateescape").read()
    pieces, last = [], 0
    integ = None
    for start, end, directive, toks in statements(text):
        new = None
        if directive == "Film" and res:
            w0 = float(param(toks, "xresolution") or 1280)
            h0 = float(param(toks, "yresolution") or 720)
            w, h = res[0], res[1] or max(1, round(res[0] * h0 / w0))
            kept = [t for t in toks]
            body = " ".join(kept)
            body = re.sub(r'"integer [xy]resolution"\s*\[?\s*[-0-9.e+]+\s*\]?', "", body)
            new = 'Film %s "integer xresolution" [ %d ] "integer yresolution" [ %d ]' % (body, w, h)
        elif directive == "Integrator" and (integrator or maxdepth is not None):
            integ = True
            old_depth = param(toks, "maxdepth")
            depth = maxdepth if maxdepth is not None else (int(old_depth) if old_depth else 5)
            new = ('# (pbrt_variant) ' + text[start:end].replace("\n", "\n# ") + "\n" +
                   'Integrator "%s" "integer maxdepth" [ %d ]' % (integrator or toks[0].strip('"'), depth))
        elif directive == "PixelFilter" and box:
            new = 'PixelFilter "box" "float xradius" [ 0.5 ] "float yradius" [ 0.5 ]'
        if new is not None:
            pieces.append(text[last:start] + new)
            last = end
    pieces.append(text[last:])
    text = "".join(pieces)
    if (integrator or maxdepth is not None) and not integ:
        text = 'Integrator "%s" "integer maxdepth" [ %d ]\n' % (integrator or "volpath", 5 if maxdepth is None else maxdepth) + text
    if box and "PixelFilter" not in text:
        text = 'PixelFilter "box" "float xradius" [ 0.5 ] "float yradius" [ 0.5 ]\n' + text
    with open(out, "w", encoding="utf-8", errors="surrogateescape") as f:
        f.write(text)


if __name__ == "__main__":
    main()
