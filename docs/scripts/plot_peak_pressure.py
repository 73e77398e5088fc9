#!/usr/bin/env python3
"""Peak shock pressure against the initial distance from the impact point in the SCI target (docs/validation.md,
"Peak pressures in the SCI target"), from data/validation/sci_peak_pressure.csv
(docs/scripts/peak_pressure_profile.py).

    /usr/bin/python3 docs/scripts/plot_peak_pressure.py data/validation/sci_peak_pressure.csv docs/figures/sci_peak_pressure.png
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "dx0_0.028": "dx0 = 0.028 m = a/2 (sci.toml)",
    "dx0_0.020": "dx0 = 0.020 m",
    "dx0_0.014": "dx0 = 0.014 m",
    "dx0_0.028_dxmax_1.0": "dx0 = 0.028 m, dx_max = 1.0 m",
    "dx0_0.010": "dx0 = 0.010 m",
    "dx0_0.028_constant_viscosity": "constant viscosity, dx0 = 0.028 m",
    "dx0_0.020_constant_viscosity": "constant viscosity, dx0 = 0.020 m",
    "dx0_0.014_constant_viscosity": "constant viscosity, dx0 = 0.014 m",
    "dx0_0.010_constant_viscosity": "constant viscosity, dx0 = 0.010 m",
    "dx0_0.028_switch_no_balsara": "switch without Balsara, dx0 = 0.028 m",
    "dx0_0.028_constant_viscosity_balsara": "constant viscosity with Balsara, dx0 = 0.028 m",
}
ELASTIC_PRESSURE = 1.0e6  # P_e of basalt_matrix_ryugu, Pa
SOLID_PRESSURE = 213.0e6  # P_s, Pa


def main(source, figure):
    runs = defaultdict(lambda: defaultdict(list))
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            run = runs[row["run"]]
            run["r"].append(float(row["r_over_a"]))
            for key in ("median", "p10", "p90"):
                run[key].append(float(row[f"{key}_peak_pressure_Pa"]) * 1e-6)
    fig, ax = plt.subplots(figsize=(10.5, 5))
    for name, run in runs.items():
        style = "s--" if "constant_viscosity" in name else ("^:" if "balsara" in name else "o-")
        line, = ax.loglog(run["r"], run["median"], style, ms=3, lw=1, label=LABELS.get(name, name))
        if name == "dx0_0.028":
            ax.fill_between(run["r"], run["p10"], run["p90"], color=line.get_color(), alpha=0.15,
                            label="10-90 % of the particles, sci.toml")
    r = [4.0, 200.0]
    ax.loglog(r, [8.0 * (x / 4.0) ** -2 for x in r], "k:", label="r^-2")
    ax.axhline(ELASTIC_PRESSURE * 1e-6, color="grey", lw=0.8, ls="--")
    ax.axhline(SOLID_PRESSURE * 1e-6, color="grey", lw=0.8, ls="--")
    ax.text(150, ELASTIC_PRESSURE * 1.2e-6, "P_e", color="grey")
    ax.text(150, SOLID_PRESSURE * 1.2e-6, "P_s", color="grey")
    ax.set_xlabel("initial distance from the impact point / projectile radius a")
    ax.set_ylabel("peak pressure (MPa), median per shell")
    ax.set_title("SCI target, peak pressure 10 ms after contact")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(figure, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
