#!/usr/bin/python3
"""Figure of the main job (`craterkit run`, docs/main_job.md): (a) the engine's craters as scaled radius
pi_R against pi_2, one colour per cohesion, with the fitted law at each cohesion and the published Ryugu law
without cohesion; (b) the SCI crater radius against cohesion under the fitted law with the observed band;
(c) crater-formation rates relative to 1 Pa against cohesion, per crater diameter; (d) model ages of the
Ryugu count against cohesion with their 1-sigma ranges.
Usage: plot_main_job.py SUMMARY.json OUT.png (SUMMARY.json written by `craterkit run`; the radii table it
names is read for the craters). The PNG is written to a temporary name and renamed."""
import csv
import json
import math
import os
import sys


def law_pi_r(constants, pi2, pi3, pi4):
    """Housen & Holsapple (2011) form (docs/physics.md section 6)."""
    h1, h2, mu, nu = (constants[k] for k in ("H1", "H2", "mu", "nu"))
    braces = pi2 + (h1 / h2) ** ((2 + mu) / mu) * pi4 ** nu * pi3 ** ((2 + mu) / 2)
    return h1 * pi4 ** ((2 + mu - 6 * nu) / (3 * (2 + mu))) * braces ** (-mu / (2 + mu))


def read_rows(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = []
    for r in csv.DictReader(lines):
        a, delta, u = float(r["impactor_radius"]), float(r["impactor_density"]), float(r["velocity"])
        rho, g, y, radius = (float(r[k]) for k in ("target_density", "gravity", "strength", "crater_radius"))
        mass = 4 / 3 * math.pi * a ** 3 * delta
        rows.append({"pi2": g * a / u ** 2, "pi3": y / (rho * u ** 2), "pi4": rho / delta,
                     "pi_r": radius * (rho / mass) ** (1 / 3), "cohesion": y})
    return rows


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_main_job.py SUMMARY.json OUT.png\n")
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        sys.stderr.write(f"plot_main_job.py: matplotlib is not available ({error}); no figure written\n")
        return 3
    with open(argv[1]) as f:
        summary = json.load(f)
    out = argv[2]
    fit = summary["fit"]
    fitted = {k: v["value"] for k, v in fit["parameters"].items()}
    published = fit["published"]["constants"]
    rows = read_rows(fit["source"])
    cohesions = sorted({r["cohesion"] for r in rows})
    colours = plt.cm.viridis([i / max(1, len(cohesions) - 1) * 0.85 for i in range(len(cohesions))])

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    ax = axes[0][0]
    pi2_all = [r["pi2"] for r in rows]
    lo, hi = min(pi2_all) / 2, max(pi2_all) * 2
    grid = [lo * (hi / lo) ** (i / 80) for i in range(81)]
    for y, colour in zip(cohesions, colours):
        mine = [r for r in rows if r["cohesion"] == y]
        ax.loglog([r["pi2"] for r in mine], [r["pi_r"] for r in mine], "o", color=colour, label=f"Y = {y:g} Pa")
        # The law at this cohesion along the study's line: fixed speed, density ratio and Y, so pi3 is fixed.
        ax.loglog(grid, [law_pi_r(fitted, p, mine[0]["pi3"], mine[0]["pi4"]) for p in grid], "-", color=colour)
    pi4 = rows[0]["pi4"]
    ax.loglog(grid, [law_pi_r(published, p, 0.0, pi4) for p in grid], "k--", lw=1,
              label=f"{fit['published']['set']}, Y = 0")
    ax.set_xlabel(r"$\pi_2 = g a / U^2$")
    ax.set_ylabel(r"$\pi_R = R (\rho/m)^{1/3}$")
    ax.set_title("(a) engine craters and the fitted law")
    ax.legend(fontsize=8)

    ax = axes[0][1]
    sci = summary["sci"]
    ys = [r["cohesion"] for r in sci["cohesions"]]
    xs = [max(y, 1e-3) for y in ys]
    ax.semilogx(xs, [r["crater_radius"] for r in sci["cohesions"]], "o-", color="C0", label="fitted law")
    r0, s0 = sci["observed_crater_radius"], sci["observed_crater_radius_sigma"]
    ax.axhspan(r0 - s0, r0 + s0, color="0.85", label="observed (Arakawa et al. 2020)")
    ax.axhline(r0, color="0.5", lw=1)
    ax.set_xlabel("cohesion (Pa; 0 drawn at 1e-3)")
    ax.set_ylabel("SCI crater radius (m)")
    ax.set_title("(b) the SCI crater")
    ax.legend(fontsize=8)

    ax = axes[1][0]
    rates = summary["rates"]["rows"]
    for d in sorted({r["crater_diameter"] for r in rates}):
        mine = [r for r in rates if r["crater_diameter"] == d]
        ax.semilogx([max(r["cohesion"], 1e-3) for r in mine], [r["relative_rate"] for r in mine], "o-",
                    label=f"D > {d:g} m")
    ax.axhline(1.0, color="0.6", lw=1)
    ax.set_xlabel("cohesion (Pa; 0 drawn at 1e-3)")
    ax.set_ylabel(f"crater-formation rate / rate at {summary['rates']['reference_cohesion']:g} Pa")
    ax.set_title("(c) relative rates on Ryugu")
    ax.legend(fontsize=8)

    ax = axes[1][1]
    ages = summary["ages"]["rows"]
    x = [max(r["cohesion"], 1e-3) for r in ages]
    med = [r["median_yr"] / 1e6 for r in ages]
    low = [m - r["sigma1_yr"][0] / 1e6 for m, r in zip(med, ages)]
    high = [r["sigma1_yr"][1] / 1e6 - m for m, r in zip(med, ages)]
    ax.errorbar(x, med, yerr=[low, high], fmt="o-", capsize=3)
    ax.set_xscale("log")
    ax.set_xlabel("cohesion (Pa; 0 drawn at 1e-3)")
    ax.set_ylabel("model age (Myr)")
    ax.set_title("(d) " + os.path.basename(summary["ages"]["count"]))

    fig.suptitle(summary.get("producer", "craterkit"), fontsize=9)
    fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
