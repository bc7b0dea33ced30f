#!/usr/bin/python3
"""The error-against-time figure of `kasha converge -o DIR`: RMSE and relMSE against rendering
seconds on log-log axes, every run of every integrator, from DIR/log_<integrator>_<run>.csv.

Usage: plot_convergence.py DIR   (Debian's python3 with numpy and matplotlib)
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLOURS = {"backward": "tab:blue", "forward": "tab:orange", "photon": "tab:green"}


def main():
    directory = sys.argv[1]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    labelled = set()
    for path in sorted(glob.glob(os.path.join(directory, "log_*.csv"))):
        data = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)
        data = np.atleast_1d(data)
        name = str(data["integrator"][0])
        t = data["seconds"].astype(float)
        for ax, column in zip(axes, ["rmse", "relmse"]):
            e = data[column].astype(float)
            keep = (t > 0) & (e > 0)
            label = name if (name, column) not in labelled else None
            labelled.add((name, column))
            ax.loglog(t[keep], e[keep], color=COLOURS.get(name, "k"), lw=1, alpha=0.8, label=label)
    for ax, title in zip(axes, ["RMSE (X, Y, Z)", "relMSE"]):
        ax.set_xlabel("rendering time (s)")
        ax.set_ylabel(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("error against run time")
    fig.tight_layout()
    fig.savefig(os.path.join(directory, "convergence.png"), dpi=110)


if __name__ == "__main__":
    main()
