#!/usr/bin/python3
"""Vertical sections through impact snapshots, coloured by each particle's vertical displacement.

Usage: plot_impact_section.py OUT.png LABEL=RUN_DIR@TIME [LABEL=RUN_DIR@TIME ...] [--width W] [--xmax X]
                              [--zmin Z] [--zmax Z]

For each LABEL=RUN_DIR@TIME, the snapshot of RUN_DIR (a `craterkit simulate` output directory) whose time is
closest to TIME is drawn in the plane y = 0: the particles with |y| < W (default 0.4 m), not fixed and not
ejected, at (x, z), coloured by z - z(t = 0) (matched by particle id with the run's first snapshot). A
heave of the target or a loosened floor shows as colour far from the crater. One panel per run, stacked.
"""
import glob
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FIXED, EJECTED = 1, 2


def snapshot_at(run_dir, time):
    best, best_gap = None, None
    for path in sorted(glob.glob(os.path.join(run_dir, "snap_*.h5"))):
        with h5py.File(path, "r") as f:
            gap = abs(float(f.attrs["time"]) - time)
        if best_gap is None or gap < best_gap:
            best, best_gap = path, gap
    if best is None:
        raise SystemExit(f"{run_dir}: no snap_*.h5")
    return best


def main(argv):
    width, xmax, zmin, zmax, runs = 0.4, None, None, 2.0, []
    args = iter(argv[2:])
    for a in args:
        if a == "--width":
            width = float(next(args))
        elif a == "--xmax":
            xmax = float(next(args))
        elif a == "--zmin":
            zmin = float(next(args))
        elif a == "--zmax":
            zmax = float(next(args))
        else:
            label, _, rest = a.partition("=")
            run_dir, _, time = rest.rpartition("@")
            if not run_dir or not time:
                raise SystemExit(f"{a!r}: expected LABEL=RUN_DIR@TIME")
            runs.append((label, run_dir, float(time)))
    if len(argv) < 3 or not runs:
        print(__doc__)
        return 2
    fig, axes = plt.subplots(len(runs), 1, figsize=(8.5, 2.9 * len(runs)), squeeze=False)
    for ax, (label, run_dir, time) in zip(axes[:, 0], runs):
        with h5py.File(os.path.join(run_dir, "snap_000000.h5"), "r") as f:
            ids0, z0 = f["id"][:], f["z"][:]
        order = np.argsort(ids0)
        path = snapshot_at(run_dir, time)
        with h5py.File(path, "r") as f:
            t = float(f.attrs["time"])
            ids, x, y, z, flags = f["id"][:], f["x"][:], f["y"][:], f["z"][:], f["flags"][:]
            R = float(f.attrs.get("domain_radius", np.max(np.abs(x))))
        initial_z = z0[order][np.searchsorted(ids0[order], ids)]
        keep = (np.abs(y) < width) & ((flags & (FIXED | EJECTED)) == 0)
        dz = z - initial_z
        limit = max(np.percentile(np.abs(dz[keep]), 98), 1e-3)
        sc = ax.scatter(x[keep], z[keep], c=dz[keep], s=5, cmap="coolwarm", vmin=-limit, vmax=limit)
        quarter = np.mean(x < 0.0) < 0.01  # a quarter domain (mirror plane x = 0)
        ax.set_xlim(0.0 if quarter else -R, xmax if xmax else R)
        ax.set_ylim(zmin if zmin is not None else -0.5 * R, zmax)
        ax.set_aspect("equal")
        ax.set_title(f"{label}: t = {t:.3g} s ({os.path.basename(path)})", fontsize=10)
        ax.set_ylabel("z (m)")
        fig.colorbar(sc, ax=ax, label="z - z(0) (m)", shrink=0.9)
    axes[-1, 0].set_xlabel("x (m)")
    fig.tight_layout()
    fig.savefig(argv[1], dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
