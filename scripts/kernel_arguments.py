#!/usr/bin/env python3
"""Positional arguments of every __kernel entry in kernels/, its parameter macros expanded.

    python3 scripts/kernel_arguments.py [KERNEL_DIR]

Runs the C preprocessor (cpp) over each .cl file with the include path and the build options
kernels are compiled with (a 4-bin scene, every mode at its default: vcm's kernels with merging
and connecting, so the largest of their modes), then counts the top-level commas of each entry's
parameter list. Prints `COUNT name file`, largest first; exits 0.
"""
import glob
import os
import re
import subprocess
import sys

kernels = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "kernels")
defines = ["-DKASHA_BINS=4", "-DKASHA_FILM_ROWS=3", "-DKASHA_SPECTRAL_FILM=0", "-D__OPENCL_VERSION__=120"]
counts = {}
for path in sorted(glob.glob(os.path.join(kernels, "**", "*.cl"), recursive=True)):
    text = subprocess.run(["cpp", "-P", "-w", "-I", kernels] + defines + [path], capture_output=True,
                          text=True).stdout
    for m in re.finditer(r"__kernel\s+void\s+(\w+)\s*\(", text):
        i, depth, commas = m.end(), 1, 0
        while depth:
            c = text[i]
            depth += c == "("
            depth -= c == ")"
            commas += c == "," and depth == 1
            i += 1
        name = m.group(1)
        if commas + 1 > counts.get(name, (0, ""))[0]:
            counts[name] = (commas + 1, os.path.relpath(path, kernels))
for name, (n, path) in sorted(counts.items(), key=lambda kv: -kv[1][0]):
    print(f"{n:3d} {name} {path}")
