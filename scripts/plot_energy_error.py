#!/usr/bin/python3
"""Energy error against time for one or more runs (craterkit simulate output directories), from their
conservation.csv: how well a run kept its energy, e.g. two time-step settings of the same impact
(docs/validation.md, "Boulders").

The error is (E(t) - E(0)) / E_kin(0): total energy (kinetic + internal + potential, ejecta included) against
the initial kinetic energy (the impact's).

Usage: /usr/bin/python3 plot_energy_error.py OUT.png "LABEL=RUN_DIR" ... [--until T]
(installed in <prefix>/share/craterkit/scripts; in the source tree under scripts/)
"""
import argparse
import csv
import sys
from pathlib import Path


def energy_error(run_dir):
    path = Path(run_dir) / "conservation.csv"
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as error:
        sys.exit(f"plot_energy_error: cannot read {path}: {error.strerror}")
    for column in ("time", "total_energy", "kinetic_energy"):
        if not rows or column not in rows[0]:
            sys.exit(f"plot_energy_error: {path} has no column '{column}' (or no rows)")
    e0 = float(rows[0]["total_energy"])
    k0 = float(rows[0]["kinetic_energy"])
    if not k0 > 0:
        sys.exit(f"plot_energy_error: {path}: initial kinetic energy {k0} is not positive")
    return [float(r["time"]) for r in rows], [(float(r["total_energy"]) - e0) / k0 for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    parser.add_argument("runs", nargs="+", help="LABEL=RUN_DIR (the directory holding conservation.csv)")
    parser.add_argument("--until", type=float, default=None, help="last time to draw, s")
    args = parser.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4))
    for spec in args.runs:
        if "=" not in spec:
            sys.exit(f"plot_energy_error: '{spec}' is not LABEL=RUN_DIR")
        label, run_dir = spec.split("=", 1)
        t, error = energy_error(run_dir)
        if args.until is not None:
            keep = [k for k, x in enumerate(t) if x <= args.until]
            t, error = [t[k] for k in keep], [error[k] for k in keep]
            if not t:
                sys.exit(f"plot_energy_error: {run_dir} has no row at or before --until {args.until} s")
        ax.plot(t, error, label=f"{label} (at {t[-1]:.3g} s: {error[-1]:.2e})")
        print(f"{label}: largest |error| {max(abs(e) for e in error):.3e}, at the end ({t[-1]:.4g} s) {error[-1]:.3e}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("(E - E0) / E_kin,0")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)


if __name__ == "__main__":
    main()
