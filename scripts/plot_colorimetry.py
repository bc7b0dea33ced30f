#!/usr/bin/python3
"""Figure of `kasha colorimetry --plot FILE.png`: the total radiance factor β(λ) under each
illuminant, its reflected part ρ and, with --as-is, the "as is" reflectance.

Usage: plot_colorimetry.py RESULT.json OUT.png   (Debian's python3 with numpy and matplotlib)
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def values(spectrum):
    return np.array(spectrum["nm"]), np.array(
        [np.nan if v is None else v for v in spectrum["value"]], dtype=float)


def main(result_path, out_path):
    with open(result_path) as f:
        r = json.load(f)
    per_illuminant = r.get("illuminants", [r])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, ill in enumerate(per_illuminant):
        nm, beta = values(ill["beta"])
        ax.plot(nm, beta, color=f"C{k}", lw=1.6, label=f"β under {ill['illuminant']}")
    nm, rho = values(per_illuminant[0]["beta_reflected"])
    ax.plot(nm, rho, color="k", lw=1.0, ls="--", label="reflected part ρ (every lamp)")
    if "as_is_material" in r:
        a = r["as_is_material"]
        nm, asis = values(a["reflectance"])
        ax.plot(nm, asis, color="0.5", lw=1.0, ls=":", label=f"as is (β under {a['lamp']}, clipped)")
    ax.axhline(1.0, color="0.8", lw=0.8)
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel("radiance factor")
    ax.set_title(f"{r['material']} — {r['observer']}", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_path, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
