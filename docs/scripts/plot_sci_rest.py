#!/usr/bin/env python3
"""The SCI crater from its end of growth to rest (docs/validation.md, "After the end of growth the wall relaxes
towards the angle of repose"): the radius of the growth samples (data/validation/sci_creep_growth.csv, runs
rest_*) and the wall slope of the snapshots (data/validation/sci_rest_walls.csv).

    /usr/bin/python3 docs/scripts/plot_sci_rest.py data/validation/sci_creep_growth.csv \\
        data/validation/sci_rest_walls.csv docs/figures/sci_rest.png
"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "rest_dx1.0": ("dx_max = 1.0 m, f = 0.55", "C0", "-"),
    "rest_dx0.7": ("dx_max = 0.7 m, f = 0.55", "C5", "-"),
    "rest_dx0.5": ("dx_max = 0.5 m (sci.toml), f = 0.55", "C1", "--"),
    "rest_dx1.0_f0.8": ("dx_max = 1.0 m, f = 0.8", "C2", "-"),
    "rest_dx1.0_tensile_porosity": ("dx_max = 1.0 m, f = 0.55, tensile porosity", "C3", ":"),
    "rest_dx1.0_mohr_coulomb": ("dx_max = 1.0 m, f = 0.55, Mohr-Coulomb yield (study build)", "C4", "-."),
}


def read(path, column):
    curves = defaultdict(list)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["run"] in LABELS and row[column] not in ("", "nan"):
                curves[row["run"]].append((float(row["time_s"]), float(row[column])))
    return curves


def main(growth, walls, figure):
    radius = read(growth, "crater_radius_m")
    slope = read(walls, "wall_slope_deg")
    frictions = {}
    with open(walls, newline="") as f:
        for row in csv.DictReader(f):
            frictions[row["run"]] = float(row["friction"])
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 4.8))
    for run, (label, colour, style) in LABELS.items():
        if run in radius:
            pts = sorted(radius[run])
            ax.plot([t for t, _ in pts if t >= 100], [r for t, r in pts if t >= 100], color=colour, ls=style,
                    label=label)
        if run in slope:
            pts = sorted(slope[run])
            bx.plot([t for t, _ in pts if t >= 100], [s for t, s in pts if t >= 100], "o" + style, color=colour,
                    ms=4, label=label)
    for f in sorted(set(frictions.values())):
        bx.axhline(math.degrees(math.atan(f)), color="grey", lw=0.8, ls=":")
        bx.text(110, math.degrees(math.atan(f)) + 0.3, f"atan {f} = {math.degrees(math.atan(f)):.1f} deg",
                fontsize=8, color="grey")
    ax.set_title("crater radius at the pre-impact level (growth samples)", fontsize=10)
    ax.set_ylabel("crater radius (m)")
    bx.set_title("wall slope: least squares over 20-80 % of the depth (snapshots)", fontsize=10)
    bx.set_ylabel("wall slope (degrees)")
    for a in (ax, bx):
        a.set_xlabel("time (s)")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(figure, dpi=120)


if __name__ == "__main__":
    main(*sys.argv[1:4])
