#!/usr/bin/python3
"""The seed paper's experiment in kasha's light booth (scenes/light_booth.json).

For every lamp of the booth it renders three images with the backward integrator:
  fluorescent  the booth as it is (the measured Post-it, the brightened paper, a grey card);
  as is        the two papers replaced by their "as is" materials (the total radiance factor under
               the booth's D65 lamp as a plain reflectance, `kasha colorimetry --as-is`);
  white        the three samples replaced by a perfect white diffuser: the white reference that a
               measurement in a booth takes in the sample's place.
`kasha regions` measures each sample over pixels well inside it, relative to the white reference
at the same pixels (Y = 100), and `kasha colorimetry` gives the same samples in open geometry
(a uniform hemisphere of the lamp's light, nothing else). The difference between the two is what
the booth's walls add. It writes a contact sheet (PNG) and the tables (Markdown).

Usage: /usr/bin/python3 scripts/light_booth.py [--kasha build/kasha] [--out out/light_booth]
           [--size 128] [--passes 8] [--spp 32] [--margin 3] [--docs DIR]
"""
import argparse
import copy
import json
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes", "light_booth.json")
# The booth's samples: material name in the scene -> label in the tables.
SAMPLES = {"postit": "Post-it", "paper": "brightened paper", "grey_card": "grey card"}
AS_IS_LAMP = "D65"  # the lamp a plain reflectance measurement would use
VARIANTS = ("fluorescent", "as_is", "white")


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"light_booth.py: {' '.join(cmd)}\n{result.stderr}")
    return result.stdout


def absolute_paths(node, base):
    """The scene with every "csv" and "file" path made absolute, so copies can live elsewhere."""
    if isinstance(node, dict):
        return {k: (os.path.join(base, v) if k in ("csv", "file") and isinstance(v, str)
                    and not os.path.isabs(v) else absolute_paths(v, base))
                for k, v in node.items()}
    if isinstance(node, list):
        return [absolute_paths(v, base) for v in node]
    return node


def write_json(path, value):
    with open(path, "w") as f:
        json.dump(value, f, indent=1)
    return path


def delta_e(kasha, lab1, lab2):
    text = [",".join(f"{v:.6f}" for v in lab) for lab in (lab1, lab2)]
    return float(run([kasha, "delta-e", "--"] + text))


def fmt(v, digits=2):
    return " ".join(f"{x:.{digits}f}" for x in v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--kasha", default=os.path.join(ROOT, "build", "kasha"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "light_booth"))
    ap.add_argument("--size", type=int, default=128, help="image width and height")
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--spp", type=int, default=32, help="camera paths per pixel per pass")
    ap.add_argument("--margin", type=float, default=3, help="pixels kept clear of sample edges")
    ap.add_argument("--docs", help="also copy the contact sheet and tables here")
    a = ap.parse_args()
    start = time.time()
    out = os.path.abspath(a.out)
    for sub in ("materials", "colorimetry", "scenes", "renders", "regions"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    with open(SCENE) as f:
        scene = absolute_paths(json.load(f), os.path.dirname(SCENE))
    scene["camera"]["width"] = scene["camera"]["height"] = a.size
    lamps = scene["lamps"]
    lamp_names = list(lamps)  # as written in the scene
    illuminant_args = []
    for name in lamp_names:
        illuminant_args += ["--illuminant", json.dumps(lamps[name])]

    # Open geometry: each sample under each lamp, its "as is" material, and that material too.
    materials, colorimetry = {}, {}
    for key in SAMPLES:
        m = scene["materials"][key]
        path = m["file"] if "file" in m else write_json(
            os.path.join(out, "materials", key + ".json"), dict(m, kasha_material=1, name=key))
        as_is = os.path.join(out, "materials", key + "_as_is.json")
        result = os.path.join(out, "colorimetry", key + ".json")
        run([a.kasha, "colorimetry", path] + illuminant_args +
            ["--as-is", json.dumps(lamps[AS_IS_LAMP]), "--write-as-is", as_is, "--json", result])
        result_as_is = os.path.join(out, "colorimetry", key + "_as_is.json")
        run([a.kasha, "colorimetry", as_is] + illuminant_args + ["--json", result_as_is])
        materials[key] = {"fluorescent": path, "as_is": as_is}
        with open(result) as f:
            colorimetry[(key, "fluorescent")] = json.load(f)
        with open(result_as_is) as f:
            colorimetry[(key, "as_is")] = json.load(f)

    # The three booths.
    scenes = {}
    for variant in VARIANTS:
        s = copy.deepcopy(scene)
        for key in SAMPLES:
            if variant == "as_is":
                s["materials"][key] = {"file": materials[key]["as_is"]}
            elif variant == "white":
                s["materials"][key] = {"passive": {"reflectance": 1}}
        scenes[variant] = write_json(os.path.join(out, "scenes", f"booth_{variant}.json"), s)

    regions = {}
    for lamp in lamp_names:
        for variant in VARIANTS:
            exr = os.path.join(out, "renders", f"{variant}_{lamp}.exr")
            # The white reference gets more samples: its noise is not in the error bars.
            spp = a.spp * (2 if variant == "white" else 1)
            run([a.kasha, "render", scenes[variant], "--lamp", lamp, "--integrator", "backward",
                 "--passes", str(a.passes), "--spp", str(spp), "--seed", "1", "-o", exr])
        for variant in ("fluorescent", "as_is"):
            result = os.path.join(out, "regions", f"{variant}_{lamp}.json")
            run([a.kasha, "regions", scenes[variant],
                 os.path.join(out, "renders", f"{variant}_{lamp}.exr"), "--white",
                 os.path.join(out, "renders", f"white_{lamp}.exr"), "--margin", str(a.margin),
                 "--json", result])
            with open(result) as f:
                for r in json.load(f)["regions"]:
                    for key in SAMPLES:
                        if r["material"] == key:
                            regions[(lamp, variant, key)] = r
        # One exposure for both booths under a lamp: the brightest of the white reference and the
        # samples at Y = 0.8 (under the UV lamp, the glowing samples; elsewhere, the white).
        brightest = max(max(regions[(lamp, v, key)]["white_XYZ"][1],
                            regions[(lamp, v, key)]["XYZ"][1])
                        for v in ("fluorescent", "as_is") for key in SAMPLES)
        for variant in ("fluorescent", "as_is"):
            exr = os.path.join(out, "renders", f"{variant}_{lamp}.exr")
            run([a.kasha, "preview", exr, "-o", exr[:-4] + ".png", "--scale",
                 f"{0.8 / brightest:.6g}"])

    # Tables.
    open_of = {}
    for (key, variant), c in colorimetry.items():
        per = c["illuminants"]
        for lamp, entry in zip(lamp_names, per):
            open_of[(lamp, variant, key)] = entry
    rows1 = ["| lamp | sample | pixels | image X Y Z | open X Y Z | image L\\* a\\* b\\* | "
             "open L\\* a\\* b\\* | Y image / open | ΔE00 image vs open |",
             "|---|---|---|---|---|---|---|---|---|"]
    rows2 = ["| lamp | sample | as is, image L\\* a\\* b\\* | fluorescent, image L\\* a\\* b\\* | "
             "ΔE00 as is vs fluorescent, images | ΔE00, open geometry | ΔE00 as is: image vs open |",
             "|---|---|---|---|---|---|---|"]
    summary = {}
    for lamp in lamp_names:
        for key, label in SAMPLES.items():
            img, opn = regions[(lamp, "fluorescent", key)], open_of[(lamp, "fluorescent", key)]
            de = delta_e(a.kasha, img["Lab"], opn["Lab"])
            ratio = img["XYZ_relative"][1] / opn["XYZ"][1]
            se = img["standard_error_relative"][1] / opn["XYZ"][1]
            rows1.append(f"| {lamp} | {label} | {img['pixels']} | {fmt(img['XYZ_relative'])} | "
                         f"{fmt(opn['XYZ'])} | {fmt(img['Lab'])} | {fmt(opn['Lab'])} | "
                         f"{ratio:.4f} ± {se:.4f} | {de:.2f} |")
            summary[(lamp, key, "image_vs_open")] = de
            if key == "grey_card":
                continue
            asis_img, asis_open = regions[(lamp, "as_is", key)], open_of[(lamp, "as_is", key)]
            de_img = delta_e(a.kasha, asis_img["Lab"], img["Lab"])
            de_open = opn["as_is"]["delta_E00"]
            de_asis = delta_e(a.kasha, asis_img["Lab"], asis_open["Lab"])
            rows2.append(f"| {lamp} | {label} | {fmt(asis_img['Lab'])} | {fmt(img['Lab'])} | "
                         f"{de_img:.2f} | {de_open:.2f} | {de_asis:.2f} |")
    clipped = {key: colorimetry[(key, "fluorescent")]["as_is_material"]["clipped_nm"]
               for key in SAMPLES}
    notes = [f"- {SAMPLES[k]}: as-is reflectance clipped to 1 at "
             f"{', '.join(f'{nm:g}' for nm in v)} nm" if v else
             f"- {SAMPLES[k]}: as-is reflectance needs no clipping" for k, v in clipped.items()]
    settings = (f"{a.size} × {a.size} pixels, backward, {a.passes} passes × {a.spp} paths per "
                f"pixel (white reference {2 * a.spp}), regions {a.margin:g} px inside each sample")
    tables = "\n".join(
        [f"Booth renders: {settings}. Image values are relative to the white reference at the "
         "same pixels (Y = 100), open-geometry values from `kasha colorimetry` (CIE 1931 2°); "
         "± is the image's standard error.", "", *rows1, "",
         f"\"As is\": each paper's total radiance factor under the booth's {AS_IS_LAMP} lamp "
         "as a plain reflectance (the seed paper's Figure 8).", "", *notes, "", *rows2, ""])
    with open(os.path.join(out, "tables.md"), "w") as f:
        f.write(tables)

    # Contact sheet: the fluorescent and the as-is booth under every lamp.
    fig, axes = plt.subplots(2, len(lamp_names), figsize=(3 * len(lamp_names), 6.4))
    for col, lamp in enumerate(lamp_names):
        for row, variant in enumerate(("fluorescent", "as_is")):
            ax = axes[row][col]
            ax.imshow(mpimg.imread(os.path.join(out, "renders", f"{variant}_{lamp}.png")))
            ax.set_xticks([])
            ax.set_yticks([])
            if row == 0:
                ax.set_title(lamp)
            if col == 0:
                ax.set_ylabel("fluorescent" if variant == "fluorescent" else f"as is ({AS_IS_LAMP})")
    fig.suptitle("kasha light booth: Post-it, brightened paper, grey card", fontsize=11)
    fig.tight_layout()
    sheet = os.path.join(out, "contact_sheet.png")
    fig.savefig(sheet, dpi=100)
    if a.docs:
        os.makedirs(a.docs, exist_ok=True)
        for name in ("contact_sheet.png", "tables.md"):
            with open(os.path.join(out, name), "rb") as src, \
                    open(os.path.join(a.docs, name), "wb") as dst:
                dst.write(src.read())
    print(tables)
    print(f"wrote {sheet} and {os.path.join(out, 'tables.md')} in {time.time() - start:.0f} s")


if __name__ == "__main__":
    main()
