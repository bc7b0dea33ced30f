#!/usr/bin/python3
"""Writes the shipped dye tables (scenes/dyes/*.csv) from the PubSpectra compilation.

The spectra are PhotochemCAD's (absorption and emission at 1 nm), as compiled in PubSpectra
(McNamara et al. 2006) and stored as MATLAB files in ISET/isetfluorescence
(data/McNamara-Boswell/, commit 5507e63). The shapes are relative; the scale of the absorption
is the published molar absorption coefficient at the band's maximum, which the source's records
give (scenes/dyes/SOURCES.md). Needs python3-scipy:

  git -C isetfluorescence show HEAD:'data/McNamara-Boswell/Fluorescein(EtOH)+basicEtOH.mat' > f.mat
  git -C isetfluorescence show HEAD:'data/McNamara-Boswell/QuinineSulfate(0.5MH2SO4)+0.5MH2SO4.mat' > q.mat
  /usr/bin/python3 scripts/make_dye_tables.py f.mat q.mat scenes/dyes
"""
import os
import sys

import numpy as np
import scipy.io

# (output name, nm range written, band whose maximum is scaled, ε there in L/mol/cm)
DYES = [
    ("fluorescein_basic_ethanol", (250, 720), (450, 520), 92300.0),
    ("quinine_sulfate_0.5M_H2SO4", (250, 620), (320, 380), 5700.0),
]


def table(mat_path, nm_range, band, epsilon):
    m = scipy.io.loadmat(mat_path, squeeze_me=True)
    w, ex, em = m["wave"], m["excitation"], m["emission"]
    if (ex < 0).any() or (em < 0).any():
        raise SystemExit(f"{mat_path}: negative values")
    in_band = (w >= band[0]) & (w <= band[1])
    scale = epsilon / ex[in_band].max()
    keep = (w >= nm_range[0]) & (w <= nm_range[1])
    return m["name"], w[keep], ex[keep] * scale, em[keep] / em.max()


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    out_dir = sys.argv[3]
    for (name, nm_range, band, eps), mat in zip(DYES, sys.argv[1:3]):
        source_name, w, molar, emission = table(mat, nm_range, band, eps)
        path = os.path.join(out_dir, name + ".csv")
        with open(path, "w") as f:
            f.write(f"# {source_name}: PhotochemCAD via PubSpectra; see SOURCES.md\n")
            f.write("nm,molar_absorption,emission\n")
            for x, a, e in zip(w, molar, emission):
                f.write(f"{x:.0f},{a:.5g},{e:.5g}\n")
        print(path, len(w), "rows")


if __name__ == "__main__":
    main()
