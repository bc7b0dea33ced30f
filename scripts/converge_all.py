#!/usr/bin/python3
"""Runs `kasha converge` on every scene in scenes/ and collects the summaries into one table.

Usage: scripts/converge_all.py [--time SECONDS] [--out DIR] [--kasha build/kasha] [extra converge options]

Furnace scenes (scenes/furnace_*.json) are measured against the analytic furnace; the others
against a reference rendered once and cached next to the scene (see `kasha converge`). Writes
DIR/<scene>/ for each scene and DIR/table.md, a Markdown table with a row per scene and integrator.
"""
import argparse
import csv
import glob
import os
import subprocess
import sys


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--time", type=float, default=10.0, help="seconds per integrator (default 10)")
    parser.add_argument("--out", default=os.path.join(root, "out", "converge"), help="output directory")
    parser.add_argument("--kasha", default=os.path.join(root, "build", "kasha"), help="the kasha binary")
    args, extra = parser.parse_known_args()

    rows = []
    for scene in sorted(glob.glob(os.path.join(root, "scenes", "*.json"))):
        name = os.path.splitext(os.path.basename(scene))[0]
        out = os.path.join(args.out, name)
        command = [args.kasha, "converge", scene, "--time", str(args.time), "-o", out] + extra
        if name.startswith("furnace_"):
            command += ["--reference", "furnace"]
        print(" ".join(command), flush=True)
        result = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if result.returncode != 0:
            sys.stderr.write(result.stderr)
            sys.exit(f"converge failed on {scene}")
        with open(os.path.join(out, "summary.csv")) as f:
            for row in csv.DictReader(f):
                rows.append((name, row))

    os.makedirs(args.out, exist_ok=True)
    table = os.path.join(args.out, "table.md")
    with open(table, "w") as f:
        f.write(f"{args.time:g} s per integrator on each scene; RMSE over X, Y, Z; slopes of log error over log "
                "time (theory −1/2, and −α/2 down to −(1 − α) for photon mapping).\n\n")
        f.write("| scene | integrator | final RMSE | final relMSE | RMSE slope | time to worst final RMSE (s) "
                "| camera paths/s | photons/s |\n|---|---|---|---|---|---|---|---|\n")
        for name, r in rows:
            f.write(f"| {name} | {r['integrator']} | {r['final_rmse']} | {r['final_relmse']} | {r['slope_rmse']} | "
                    f"{r['time_to_target'] or 'not reached'} | {r['camera_paths_per_s']} | {r['photons_per_s']} |\n")
    print(f"wrote {table}")


if __name__ == "__main__":
    main()
