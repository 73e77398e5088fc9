#!/usr/bin/python3
"""Cohesionless craters against pi_2: fit the gravity-regime exponent and compare with a published law.

Usage:
  /usr/bin/python3 docs/scripts/pi2_study.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...]
                   [--law hh2011_sand] [--radii-csv OUT.csv]

Each RUN_DIR is a run of `docs/scripts/impact_study.py` (it holds config.toml, summary.json and, when the
target material was changed, target.toml). From the configuration: the projectile mass m, density delta
and speed U ([impact]), the gravity g ([run] gravity), the target's bulk density rho (its material's
[eos] reference_density / [porosity] initial_distention; data/materials/ or $CRATERKIT_DATA_DIR/materials)
and its cohesion; from summary.json the crater radius R and its uncertainty. Then (docs/physics.md section 6)

  a = (3 m / (4 pi delta))^(1/3),  pi_2 = g a / U^2,  pi_R = R (rho/m)^(1/3),  pi_4 = rho/delta,

and the least-squares line log pi_R = log C - beta log pi_2 over the runs, weighted by (R/sigma_R)^2, gives the
gravity-regime exponent beta = mu/(2 + mu), so mu = 2 beta/(1 - beta). The published law (a constant set of
data/scaling/, Housen & Holsapple 2011 form, default hh2011_sand: mu = 0.41) is drawn over the runs'
pi_2, and the table printed (Markdown) lists each run's pi_2, pi_R, the law's pi_R and the difference.
--radii-csv writes the runs as a table for `craterkit fit` (columns impactor_radius, impactor_density,
velocity, target_density, gravity, strength, crater_radius, crater_radius_sigma).

Runs with a cohesion are refused (the study is of the gravity regime); so are runs whose crater growth did
not end (their radius is a lower bound). A run that went on past the end of growth (`[crater]
stop_when_grown = false`; its summary's crater_growth_end_time is set) counts with its radius at the end of
growth (crater_growth_end_radius), the radius the default rule reports, not that of its final state.
"""
import csv
import json
import math
import os
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def fail(message):
    sys.exit(f"pi2_study.py: {message}")


def data_dir():
    return os.environ.get("CRATERKIT_DATA_DIR", os.path.join(REPO, "data"))


def load_toml(path):
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        fail(f"{path}: no such file")
    except tomllib.TOMLDecodeError as e:
        fail(f"{path}: not valid TOML ({e})")


def require(table, key, where):
    if key not in table:
        fail(f"{where}: key '{key}' missing")
    return table[key]


def run_parameters(label, run_dir):
    config = load_toml(os.path.join(run_dir, "config.toml"))
    impact = require(config, "impact", f"{run_dir}/config.toml")
    where = f"{run_dir}/config.toml [impact]"
    mass = float(require(impact, "projectile_mass", where))
    delta = float(require(impact, "projectile_density", where))
    speed = float(require(impact, "impact_speed", where))
    angle = float(impact.get("impact_angle", 0.0))
    if angle != 0.0:
        fail(f"{where}: impact_angle = {angle}; the study needs vertical impacts (0)")
    gravity = require(config.get("run", {}), "gravity", f"{run_dir}/config.toml [run]")
    g = math.sqrt(sum(float(c) ** 2 for c in gravity))
    material_name = require(impact, "target_material", where)
    material_path = material_name if material_name.endswith(".toml") else os.path.join(
        data_dir(), "materials", f"{material_name}.toml")
    if not os.path.isabs(material_path):
        material_path = os.path.join(run_dir, material_path)
    material = load_toml(material_path)
    rho_matrix = float(require(require(material, "eos", material_path), "reference_density", material_path))
    distention = float(material.get("porosity", {}).get("initial_distention", 1.0))
    cohesion = float(material.get("strength", {}).get("cohesion", 0.0))
    if cohesion != 0.0:
        fail(f"{label}: the target has a cohesion of {cohesion} Pa ({material_path}); the study is of "
             "cohesionless craters")
    summary_path = os.path.join(run_dir, "summary.json")
    if not os.path.exists(summary_path):
        fail(f"{label}: {summary_path} missing (run not finished?)")
    with open(summary_path) as f:
        summary = json.load(f)
    # A run that stopped at the end of growth, or went on past it (stop_when_grown = false: the summary's
    # crater_growth_end_time says when the rule first held, crater_growth_end_radius the radius then, which
    # is the radius a run with the default rule reports).
    if summary.get("crater_growth_ended", False):
        radius = summary.get("crater_radius")
    elif summary.get("crater_growth_end_time") is not None:
        radius = summary.get("crater_growth_end_radius")
    else:
        fail(f"{label}: crater growth had not ended at t = {summary.get('time')} s ({summary_path}); its "
             "radius is only a lower bound")
    if radius is None:
        fail(f"{label}: no crater radius in {summary_path}")
    return {
        "label": label,
        "mass": mass,
        "impactor_density": delta,
        "velocity": speed,
        "gravity": g,
        "target_density": rho_matrix / distention,
        "crater_radius": float(radius),
        "crater_radius_sigma": float(summary.get("crater_radius_uncertainty", 0.0)),
    }


def law_pi_r(law, pi2, pi4):
    c = law["constants"]
    mu, nu = c["mu"], c["nu"]
    return c["H1"] * pi2 ** (-mu / (2 + mu)) * pi4 ** ((2 + mu - 6 * nu) / (3 * (2 + mu)))


def weighted_line(xs, ys, ws):
    """Least squares y = p + q x with weights ws; returns p, q and the standard error of q."""
    sw = sum(ws)
    mx = sum(w * x for w, x in zip(ws, xs)) / sw
    my = sum(w * y for w, y in zip(ws, ys)) / sw
    sxx = sum(w * (x - mx) ** 2 for w, x in zip(ws, xs))
    sxy = sum(w * (x - mx) * (y - my) for w, x, y in zip(ws, xs, ys))
    q = sxy / sxx
    p = my - q * mx
    n = len(xs)
    if n > 2:
        residual = sum(w * (y - p - q * x) ** 2 for w, x, y in zip(ws, xs, ys)) / (n - 2)
        return p, q, math.sqrt(residual / sxx)
    return p, q, math.nan


def main(argv):
    args = argv[1:]
    law_name, radii_csv = "hh2011_sand", None
    entries = []
    i = 0
    while i < len(args):
        if args[i] in ("--law", "--radii-csv"):
            if i + 1 >= len(args):
                fail(f"{args[i]} needs a value")
            if args[i] == "--law":
                law_name = args[i + 1]
            else:
                radii_csv = args[i + 1]
            i += 2
            continue
        entries.append(args[i])
        i += 1
    if len(entries) < 2 or "=" in entries[0]:
        fail("usage: pi2_study.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...] [--law NAME] [--radii-csv OUT.csv]")
    png = entries[0]
    runs = []
    for entry in entries[1:]:
        if "=" not in entry:
            fail(f"'{entry}': expected LABEL=RUN_DIR")
        label, run_dir = entry.split("=", 1)
        runs.append(run_parameters(label, run_dir))
    law = load_toml(os.path.join(data_dir(), "scaling", f"{law_name}.toml"))
    if law.get("form") != "hh2011" or "H1" not in law.get("constants", {}):
        fail(f"--law {law_name}: needs a Housen & Holsapple (2011) set with H1 (gravity regime)")

    for r in runs:
        r["impactor_radius"] = (3 * r["mass"] / (4 * math.pi * r["impactor_density"])) ** (1 / 3)
        r["pi2"] = r["gravity"] * r["impactor_radius"] / r["velocity"] ** 2
        r["piR"] = r["crater_radius"] * (r["target_density"] / r["mass"]) ** (1 / 3)
        r["pi4"] = r["target_density"] / r["impactor_density"]
        r["law_piR"] = law_pi_r(law, r["pi2"], r["pi4"])

    print(f"| run | a (m) | g (m/s^2) | pi_2 | R (m) | pi_R | {law_name} pi_R | difference |")
    print("|---|---|---|---|---|---|---|---|")
    for r in sorted(runs, key=lambda r: r["pi2"]):
        print(f"| {r['label']} | {r['impactor_radius']:.4g} | {r['gravity']:.3g} | {r['pi2']:.3e} | "
              f"{r['crater_radius']:.2f} +- {r['crater_radius_sigma']:.2f} | {r['piR']:.3f} | "
              f"{r['law_piR']:.3f} | {100 * (r['piR'] / r['law_piR'] - 1):+.1f} % |")
    decades = math.log10(max(r["pi2"] for r in runs) / min(r["pi2"] for r in runs))
    print(f"\npi_2 spans {decades:.2f} decades")
    fit = None
    if len(runs) >= 2 and decades > 0.1:
        xs = [math.log(r["pi2"]) for r in runs]
        ys = [math.log(r["piR"]) for r in runs]
        ws = [(r["crater_radius"] / r["crater_radius_sigma"]) ** 2 if r["crater_radius_sigma"] > 0 else 1.0
              for r in runs]
        p, q, q_error = weighted_line(xs, ys, ws)
        beta = -q
        mu = 2 * beta / (1 - beta)
        mu_error = 2 * q_error / (1 - beta) ** 2 if math.isfinite(q_error) else math.nan
        fit = (p, q, mu)
        law_mu = law["constants"]["mu"]
        print(f"fit: pi_R = {math.exp(p):.3f} pi_2^(-{beta:.4f}) -> mu = {mu:.3f} +- {mu_error:.3f} "
              f"({law_name}: mu = {law_mu}, beta = {law_mu / (2 + law_mu):.4f})")
    else:
        print("fit: needs at least two runs over a range of pi_2")

    if radii_csv:
        tmp = radii_csv + ".tmp"
        with open(tmp, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["impactor_radius", "impactor_density", "velocity", "target_density", "gravity",
                             "strength", "crater_radius", "crater_radius_sigma"])
            for r in runs:
                writer.writerow([r["impactor_radius"], r["impactor_density"], r["velocity"], r["target_density"],
                                 r["gravity"], 0.0, r["crater_radius"], r["crater_radius_sigma"]])
        os.replace(tmp, radii_csv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.8))
    pis = [r["pi2"] for r in runs]
    lo, hi = min(pis) / 2, max(pis) * 2
    grid = [lo * (hi / lo) ** (k / 60) for k in range(61)]
    pi4 = runs[0]["pi4"]
    ax.loglog(grid, [law_pi_r(law, x, pi4) for x in grid], "k-",
              label=f"{law_name} (mu = {law['constants']['mu']}), pi_4 = {pi4:.2f}")
    for r in runs:
        sigma = r["crater_radius_sigma"] / r["crater_radius"] * r["piR"]
        ax.errorbar(r["pi2"], r["piR"], yerr=sigma, fmt="o", ms=6, capsize=3, label=r["label"])
    if fit is not None:
        p, q, mu = fit
        ax.loglog(grid, [math.exp(p) * x ** q for x in grid], "C3--", label=f"fit: mu = {mu:.3f}")
    ax.set_xlabel("pi_2 = g a / U^2")
    ax.set_ylabel("pi_R = R (rho / m)^(1/3)")
    ax.set_title("Cohesionless craters against pi_2")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main(sys.argv)
