#!/usr/bin/python3
"""Crater growth and final profiles of impact runs (craterkit simulate output directories).

Usage: plot_crater_runs.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...] [--scale L] [--title TEXT]

Left: crater radius against time (crater_growth.csv); right: the azimuthally averaged final surface
profile z(r) (crater_profile.csv), with the measured crater radius marked (runs stopped before their end
have no profile: growth curve only). RUN_DIR needs crater_growth.csv. --scale divides lengths by L
(e.g. the predicted radius) so that runs of different sizes share the axes.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path, newline="") as f:
        return [row for row in csv.DictReader(f)]


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    out = argv[1]
    scale, title, runs = 1.0, None, []
    args = iter(argv[2:])
    for a in args:
        if a == "--scale":
            scale = float(next(args))
        elif a == "--title":
            title = next(args)
        else:
            label, _, directory = a.partition("=")
            runs.append((label, directory))
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5))
    for label, directory in runs:
        growth = read_rows(os.path.join(directory, "crater_growth.csv"))
        t = [float(r["time"]) for r in growth]
        radius = [float(r["crater_radius"]) / scale for r in growth]
        line, = left.plot(t, radius, label=label)
        if not os.path.isfile(os.path.join(directory, "crater_profile.csv")):
            continue  # a run stopped before its end: growth curve only
        profile = read_rows(os.path.join(directory, "crater_profile.csv"))
        r = [float(p["radius_m"]) / scale for p in profile]
        z = [float(p["mean_height_m"]) / scale for p in profile]
        right.plot(r, z, color=line.get_color(), label=label)
        with open(os.path.join(directory, "crater.json")) as f:
            crater = json.load(f)
        R = crater.get("crater_radius")
        if R is not None and math.isfinite(R):
            right.axvline(R / scale, color=line.get_color(), ls=":", lw=1)
    unit = "m" if scale == 1.0 else "/ L"
    left.set_xlabel("t (s)")
    left.set_ylabel(f"crater radius ({unit})")
    left.set_xscale("log")
    left.grid(alpha=0.3)
    left.legend(fontsize=8)
    right.axhline(0.0, color="k", lw=0.5)
    right.set_xlabel(f"r ({unit})")
    right.set_ylabel(f"mean surface height z(r) ({unit})")
    right.grid(alpha=0.3)
    right.set_aspect("equal", adjustable="datalim")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
