#!/usr/bin/env python3
"""Peak shock pressure against the initial distance from the impact point, for impact runs of craterkit
(docs/validation.md, "Peak pressures in the SCI target"): for each run folder, the target particles that
started below the surface are binned by their initial distance r from the impact point (read from the
run's first snapshot, matched by particle id) and the median, 10th and 90th percentile of `peak_pressure`
in its last snapshot are written per bin, with the kinetic energy at that time (conservation.csv).

    /usr/bin/python3 docs/scripts/peak_pressure_profile.py LABEL=RUN [LABEL=RUN ...] > profile.csv

RUN is a `craterkit simulate` output folder of an impact whose projectile has material id 1.
"""
import csv
import glob
import sys

import h5py
import numpy as np

EDGES = np.array([0.03, 0.05, 0.07, 0.1, 0.14, 0.2, 0.28, 0.4, 0.56, 0.8, 1.1, 1.6, 2.2, 3.2, 4.5, 6.4, 9.0, 12.0])


def profile(label, run, out):
    snapshots = sorted(glob.glob(f"{run}/snap_*.h5"))
    if len(snapshots) < 2:
        sys.exit(f"{run}: needs a first and a later snapshot (found {len(snapshots)})")
    with h5py.File(snapshots[0]) as first, h5py.File(snapshots[-1]) as last:
        if "peak_pressure" not in last:
            sys.exit(f"{snapshots[-1]}: no dataset 'peak_pressure' (written by a craterkit before it existed?)")
        a = float(first.attrs["projectile_radius"])
        ids0 = first["id"][:]
        order = np.argsort(ids0)
        x0, y0, z0 = first["x"][:], first["y"][:], first["z"][:]
        at = order[np.searchsorted(ids0[order], last["id"][:])]
        r = np.sqrt(x0**2 + y0**2 + z0**2)[at]
        target = (last["material"][:] == 0) & (z0[at] < 0.0)
        peak = last["peak_pressure"][:]
        time = float(last.attrs["time"])
    with open(f"{run}/conservation.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    kinetic = float(rows[-1]["kinetic_energy"])
    for lo, hi in zip(EDGES[:-1], EDGES[1:]):
        chosen = target & (r >= lo) & (r < hi)
        if not chosen.any():
            continue
        values = peak[chosen]
        out.writerow([label, f"{time:.6g}", f"{kinetic:.6g}", lo, hi, f"{np.sqrt(lo * hi) / a:.4g}",
                      int(chosen.sum()), f"{np.median(values):.6g}", f"{np.percentile(values, 10):.6g}",
                      f"{np.percentile(values, 90):.6g}"])


def main(arguments):
    if not arguments or any("=" not in a for a in arguments):
        sys.exit(__doc__)
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["run", "time_s", "kinetic_energy_J", "r_low_m", "r_high_m", "r_over_a", "particles",
                  "median_peak_pressure_Pa", "p10_peak_pressure_Pa", "p90_peak_pressure_Pa"])
    for argument in arguments:
        label, run = argument.split("=", 1)
        profile(label, run, out)


if __name__ == "__main__":
    main(sys.argv[1:])
