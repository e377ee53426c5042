#!/usr/bin/env python3
"""Draws docs/figures/helical_h501.png: the mesh stiffness of examples/helical_h501.toml over one
mesh period by the slices (route A, N = 4 and 32) and by the face integral (route B), with the
summed contact-line length below (docs/helical.md).

    scripts/helical_figure.py PROGRAM OUTPUT.png
"""

import csv
import io
import pathlib
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[1]


def curve(program, slices):
    text = (REPO / "examples" / "helical_h501.toml").read_text()
    with tempfile.TemporaryDirectory() as folder:
        case = pathlib.Path(folder) / "helical.toml"
        case.write_text(text.replace("face_slices = 32", f"face_slices = {slices}"))
        out = subprocess.run([program, "mesh-stiffness", "--case-file", str(case), "--samples",
                              "2000"], check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def main():
    program, output = sys.argv[1], sys.argv[2]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    rows32 = curve(program, 32)
    rows4 = curve(program, 4)
    frac = [float(r["fraction"]) for r in rows32]
    top.plot(frac, [float(r["k_face_n_m"]) / 1e9 for r in rows32], "k-", label="route B (face integral)")
    top.plot(frac, [float(r["k_slices_n_m"]) / 1e9 for r in rows32], "b-", lw=0.8,
             label="route A, N = 32")
    top.plot(frac, [float(r["k_slices_n_m"]) / 1e9 for r in rows4], "r-", lw=0.8, label="route A, N = 4")
    top.set_ylabel("mesh stiffness, GN/m")
    top.legend(fontsize=8)
    top.set_title("H501 (beta 15 deg, eps_alpha 1.47, eps_beta 0.54), yang-lin-1987 slices")
    bottom.plot(frac, [float(r["contact_line_length_m"]) * 1e3 for r in rows32], "k-", label="exact")
    bottom.plot(frac, [float(r["contact_line_length_slices_m"]) * 1e3 for r in rows4], "r-", lw=0.8,
                label="N = 4 slices")
    bottom.set_ylabel("contact-line length, mm")
    bottom.set_xlabel("fraction of the mesh period (theta1 = 0: mid-face contact at the pitch point)")
    bottom.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(output, dpi=110)


if __name__ == "__main__":
    main()
