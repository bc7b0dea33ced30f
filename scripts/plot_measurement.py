#!/usr/bin/python3
"""Figures of `kasha measure --plots DIR`, drawn from the CSVs it writes into DIR.

Usage: plot_measurement.py DIR RANK1_RESIDUAL   (Debian's python3 with numpy and matplotlib)
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_matrix(path):
    with open(path) as f:
        ex = np.array([float(x) for x in f.readline().strip().split(",")[1:]])
    data = np.genfromtxt(path, delimiter=",", skip_header=1)
    data = np.atleast_2d(data)
    return ex, data[:, 0], data[:, 1:]


def read_spectrum(path):
    data = np.atleast_2d(np.genfromtxt(path, delimiter=",", skip_header=1))
    return data[:, 0], data[:, 1]


def matrix_figure(directory, name, title, label, symmetric=False):
    ex, em, v = read_matrix(os.path.join(directory, name + ".csv"))
    fig, ax = plt.subplots(figsize=(6, 5))
    finite = v[np.isfinite(v)]
    if symmetric and finite.size:
        lim = np.max(np.abs(finite)) or 1.0
        mesh = ax.pcolormesh(ex, em, v, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="nearest")
    else:
        mesh = ax.pcolormesh(ex, em, v, cmap="magma", shading="nearest")
    ax.plot([ex.min(), ex.max()], [ex.min(), ex.max()], color="w", lw=0.5, ls="--")
    ax.set_xlabel("excitation λi (nm)")
    ax.set_ylabel("emission λo (nm)")
    ax.set_title(title)
    fig.colorbar(mesh, ax=ax, label=label)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, name + ".png"), dpi=110)
    plt.close(fig)


def spectrum_figure(directory, name, title, ylabel):
    nm, v = read_spectrum(os.path.join(directory, name + ".csv"))
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(nm, v, marker=".", lw=1)
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(directory, name + ".png"), dpi=110)
    plt.close(fig)


def main():
    directory, residual = sys.argv[1], float(sys.argv[2])
    matrix_figure(directory, "raw_matrix", "raw excitation–emission matrix", "reading")
    matrix_figure(directory, "offband_matrix", "fluorescence, band and 2nd order removed", "f^f")
    matrix_figure(directory, "fit_residual", "rank-1 fit residual (relative %.3f)" % residual, "f^f − e·aᵀ",
                  symmetric=True)
    spectrum_figure(directory, "passive", "passive reflectance ρ(λ)", "ρ")
    spectrum_figure(directory, "excitation", "excitation a(λ) (energy yield)", "a")
    spectrum_figure(directory, "emission", "emission e(λ), Σ e Δλ = 1", "e (1/nm)")


if __name__ == "__main__":
    main()
