"""DEM piles (docs/validation.md, "DEM piles"): the surface profiles of collapsed columns of grains with the
flank line fitted between 20 and 80 % of the pile's height, as dem/column_collapse.cpp measures them.
Usage: /usr/bin/python3 docs/scripts/plot_dem_piles.py OUT.png FOLDER:LABEL [FOLDER:LABEL ...]
Each FOLDER is a column_collapse folder (its deposit.dump), e.g. a `dem_repose` run's mu_r-<value>/."""
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

CELL = 0.011  # m: the largest grain, the profile's column width
LENGTH = 0.96  # m: the floor


def read_dump(path):
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    columns = lines[start].split()[2:]
    data = np.array([[float(v) for v in line.split()] for line in lines[start + 1:]])
    return {name: data[:, k] for k, name in enumerate(columns)}


def profile(grains):
    n = int(math.ceil(LENGTH / CELL))
    height = np.zeros(n)
    top = grains["z"] + 0.5 * grains["diameter"]
    column = (grains["x"] / CELL).astype(int)
    for c, t in zip(column, top):
        if 0 <= c < n:
            height[c] = max(height[c], t)
    return (np.arange(n) + 0.5) * CELL, height


def flank(x, height):
    peak = int(np.argmax(height))
    top = height[peak]
    keep = [c for c in range(peak, len(height)) if 0.2 * top <= height[c] <= 0.8 * top]
    slope, intercept = np.polyfit(x[keep], height[keep], 1)
    return math.degrees(math.atan(-slope)), slope, intercept, x[keep]


out = sys.argv[1]
fig, ax = plt.subplots(figsize=(8, 3.6))
for spec in sys.argv[2:]:
    folder, label = spec.split(":", 1)
    x, height = profile(read_dump(folder + "/deposit.dump"))
    angle, slope, intercept, fitted = flank(x, height)
    line = ax.step(x * 100, height * 100, where="mid", label=f"{label}: {angle:.1f} deg")[0]
    ax.plot(fitted * 100, (slope * fitted + intercept) * 100, "--", color=line.get_color(), lw=1)
ax.set_xlabel("x (cm)")
ax.set_ylabel("surface height (cm)")
ax.set_xlim(0, 70)
ax.set_ylim(0, 18)
ax.set_aspect("equal")
ax.legend(fontsize=8, loc="upper right")
ax.set_title("DEM column collapse, a = 0.5 (16 x 32 x 6 grains): quasi-static and free", fontsize=9)
fig.tight_layout()
fig.savefig(out, dpi=130)
