#!/usr/bin/env python3
"""The SCI crater's radius after its end of growth, for the runs of docs/validation.md ("Why the crater
walls creep"): data/validation/sci_creep_growth.csv (columns run,time_s,crater_radius_m).

    /usr/bin/python3 docs/scripts/plot_sci_creep.py data/validation/sci_creep_growth.csv docs/figures/sci_creep.png
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "cohesionless": "cohesionless (engine of 5-6 December)",
    "tensile_porosity": "+ tensile porosity from 250 s",
    "friction_0.8": "f = 0.8 from 250 s",
    "cohesion_0.05": "Y0 = 0.05 Pa (not weakened) from 250 s",
    "cohesion_0.5": "Y0 = 0.5 Pa (not weakened) from 250 s",
    "strength_floor_0.09": "Y = f max(P, 0.09 Pa) from t = 0",
    "cohesionless_dx0.5": "dx_max = 0.5 m: cohesionless (sci.toml)",
    "strength_floor_0.045_dx0.5": "dx_max = 0.5 m: Y = f max(P, 0.045 Pa)",
    "cohesionless_engine_2026-12-07": "cohesionless (engine of 7 December)",
    "tensile_porosity_from_switch": "+ tensile porosity from the late-stage switch (7 December)",
    "cohesionless_engine_2026-12-07_dx0.5": "dx_max = 0.5 m: cohesionless (engine of 7 December)",
    "tensile_porosity_from_switch_dx0.5": "dx_max = 0.5 m: + tensile porosity from the switch",
    "f0.8_engine_2026-12-07": "f = 0.8 from t = 0 (engine of 7 December)",
    "f0.8_tensile_porosity_from_switch": "f = 0.8, + tensile porosity from the late-stage switch",
}


def main(source, figure):
    curves = defaultdict(list)
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            if row["run"].startswith("rest_"):  # the runs to rest: plot_sci_rest.py
                continue
            if row["crater_radius_m"] not in ("", "nan"):
                curves[row["run"]].append((float(row["time_s"]), float(row["crater_radius_m"])))
    fig, (ax, ax8) = plt.subplots(1, 2, figsize=(13, 4.8), gridspec_kw={"width_ratios": [2, 1]})
    for run, points in curves.items():
        points.sort()
        target = ax8 if run.startswith("f0.8_") else ax
        target.plot([t for t, _ in points], [r for _, r in points], label=LABELS.get(run, run),
                    lw=2.2 if run.startswith("cohesionless") else 1.4, ls="--" if run.endswith("dx0.5") else "-")
    ax.set_xlim(100, None)
    ax.set_ylim(5.6, 7.45)
    ax.set_title("SCI crater, f = 0.55: the radius after the end of growth (solid 1.0 m, dashed 0.5 m)", fontsize=10)
    ax8.set_xlim(100, None)
    ax8.set_ylim(4.7, 5.6)
    ax8.set_title("the same with f = 0.8 (1.0 m)", fontsize=10)
    for a in (ax, ax8):
        a.set_xlabel("time (s)")
        a.set_ylabel("crater radius (m)")
        a.grid(alpha=0.3)
    ax.legend(fontsize=7.5, loc="lower left")
    ax8.legend(fontsize=7.5, loc="lower right")
    fig.tight_layout()
    fig.savefig(figure, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
