#!/usr/bin/python3
"""Plan view of an impact run with boulders: where the boulders were and went, and the crater edge.

Usage: plot_impact_plan.py OUT.png RUN_DIR [--time T] [--extent X] [--crater CRATER.json]

Draws, seen from above, the particles of every boulder (material id >= 2) at t = 0 (light) and in the
snapshot closest to T (default: the last one; dark), the target particles of that snapshot that lie below
the pre-impact surface inside the crater (z < -0.25 m, light grey), and the crater of RUN_DIR/crater.json:
the circle of `crater_radius`, the edge radius measured along +x, -x, +y and -y and, where crater.json has
it, the outline (the edge of every ray). --crater takes the crater from another file (`craterkit measure
SNAPSHOT --out DIR` of the snapshot drawn). Fixed and ejected particles are left out. Prints each
boulder's displacement from crater.json.
"""
import glob
import json
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FIXED, EJECTED = 1, 2
COLOURS = ["tab:red", "tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:brown"]


def snapshot_closest(run_dir, time):
    paths = sorted(glob.glob(os.path.join(run_dir, "snap_*.h5")))
    if not paths:
        raise SystemExit(f"{run_dir}: no snap_*.h5")
    if time is None:
        return paths[-1]
    gaps = []
    for path in paths:
        with h5py.File(path, "r") as f:
            gaps.append(abs(float(f.attrs["time"]) - time))
    return paths[int(np.argmin(gaps))]


def read(path):
    with h5py.File(path, "r") as f:
        return {k: f[k][:] for k in ("x", "y", "z", "material", "flags")}, float(f.attrs["time"])


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    out, run_dir = argv[1], argv[2]
    time, extent = None, 12.0
    crater_path = os.path.join(run_dir, "crater.json")
    args = iter(argv[3:])
    for a in args:
        if a == "--time":
            time = float(next(args))
        elif a == "--extent":
            extent = float(next(args))
        elif a == "--crater":
            crater_path = next(args)
        else:
            raise SystemExit(f"unknown argument {a!r}")
    with open(crater_path) as f:
        crater = json.load(f)
    first, _ = read(os.path.join(run_dir, "snap_000000.h5"))
    last, t = read(snapshot_closest(run_dir, time))

    fig, ax = plt.subplots(figsize=(7.5, 7.5))
    live = (last["flags"] & (FIXED | EJECTED)) == 0
    floor = live & (last["material"] == 0) & (last["z"] < -0.25)
    ax.scatter(last["x"][floor], last["y"][floor], s=2, c="0.8", label="target below z = -0.25 m")
    materials = sorted(m for m in np.unique(first["material"]) if m >= 2)
    for k, m in enumerate(materials):
        colour = COLOURS[k % len(COLOURS)]
        was = first["material"] == m
        now = live & (last["material"] == m)
        ax.scatter(first["x"][was], first["y"][was], s=3, c=colour, alpha=0.15)
        ax.scatter(last["x"][now], last["y"][now], s=3, c=colour, label=f"material {m}")
    r = crater["crater_radius"]
    phi = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(r * np.cos(phi), r * np.sin(phi), "k--", lw=1, label=f"R = {r:.2f} m")
    if "outline" in crater:
        azimuth = np.radians(crater["outline"]["azimuth_deg"])
        edge = np.array([np.nan if e is None else e for e in crater["outline"]["edge_radius"]])
        closed = np.append(np.arange(len(edge)), 0)
        ax.plot(edge[closed] * np.cos(azimuth[closed]), edge[closed] * np.sin(azimuth[closed]), "k-", lw=1.2,
                label="crater edge (every ray)")
    radii = crater["radii"]
    ax.plot([radii["+x"], -radii["-x"], 0.0, 0.0], [0.0, 0.0, radii["+y"], -radii["-y"]], "ko", ms=5,
            label="edge along +-x, +-y")
    ax.set_xlim(-extent, extent)
    ax.set_ylim(-extent, extent)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{os.path.basename(os.path.normpath(run_dir))}: t = {t:.3g} s (light: boulders at t = 0)",
                 fontsize=10)
    ax.legend(loc="upper right", fontsize=8, markerscale=3)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    for b in crater.get("boulders", []):
        d = b["displacement"]
        if b.get("displacement_magnitude") is None:  # none of its particles is left: ejected whole
            print(f"{b['name']}: ejected ({b.get('ejected_mass', 0.0):.4g} kg), no displacement")
            continue
        print(f"{b['name']}: displacement ({d[0]:+.3f}, {d[1]:+.3f}, {d[2]:+.3f}) m, "
              f"|d| = {np.linalg.norm(d):.3f} m")
    print("radii: " + ", ".join(f"{k} {v:.3f}" for k, v in radii.items()) + f"; crater_radius {r:.3f} m")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
