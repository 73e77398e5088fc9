#!/usr/bin/python3
"""Standard model-age figure of `craterkit age --plot`: the crater size-frequency distribution of the count
with Poisson error bars and the fitted isochrons, the diameter range of the fit shaded (left), and the age
probability densities (right), one colour per cohesion.

Usage: plot_age.py DATA.json OUT.(png|pdf|svg) [cumulative|differential|R], where DATA.json is written by
`craterkit age`. Presentations:
  cumulative    N(>=D) per km^2 at every crater (or bin), error sqrt(N) / A;
  differential  dN/dD per km^2 per km in root-2 bins, error sqrt(n) / (A dD);
  R             relative plot, D^3 dN/dD at each bin's geometric mean diameter (D in km), error R / sqrt(n).
n counts the craters of a bin weighted by their fractions. Ages are shown in yr, kyr, Myr or Gyr as they
fall. The figure is written to a temporary name and renamed, so a failure never leaves a partial file."""
import json
import math
import os
import sys

PRESENTATIONS = ("cumulative", "differential", "R")


def format_age(years):
    """A value in years in the unit that suits it."""
    for unit, scale in (("Gyr", 1e9), ("Myr", 1e6), ("kyr", 1e3)):
        if years >= scale:
            return years / scale, unit
    return years, "yr"


def age_label(age):
    median = age["median_yr"]
    value, unit = format_age(median)
    scale = median / value if value else 1.0
    lo, hi = (x / scale for x in age["sigma1_yr"])
    return f"{value:.3g} (+{hi - value:.3g} / -{value - lo:.3g}) {unit}"


def craters(data):
    """(diameters in m, weights) of an unbinned count, from its cumulative steps; None for binned counts."""
    if data["counts"]["binned"]:
        return None
    area_km2 = data["counts"]["area_km2"]
    previous = 0.0
    out = []
    for d, n in data["observed_cumulative_per_km2"]:  # decreasing diameter, running density
        out.append((d, (n - previous) * area_km2))
        previous = n
    return out


def bins(data):
    """Root-2 bins (lower edge in m, upper edge, weighted count) of the count."""
    area_km2 = data["counts"]["area_km2"]
    observed = data["observed_cumulative_per_km2"]
    if data["counts"]["binned"]:
        rows = sorted(observed)
        out = []
        for k, (d, n) in enumerate(rows):
            upper = rows[k + 1][0] if k + 1 < len(rows) else d * math.sqrt(2.0)
            above = rows[k + 1][1] if k + 1 < len(rows) else 0.0
            out.append((d, upper, (n - above) * area_km2))
        return out
    items = craters(data)
    d_min = min(d for d, _ in items)
    edge = 2.0 ** (math.floor(2.0 * math.log2(d_min)) / 2.0)
    out = []
    while edge <= max(d for d, _ in items):
        upper = edge * math.sqrt(2.0)
        n = sum(w for d, w in items if edge <= d < upper)
        if n > 0:
            out.append((edge, upper, n))
        edge = upper
    return out


def observed_points(data, presentation):
    """x (m), y, y error (1 sigma, Poisson) of the count in the presentation's units."""
    area_km2 = data["counts"]["area_km2"]
    if presentation == "cumulative":
        xs, ys, es = [], [], []
        for d, n in data["observed_cumulative_per_km2"]:
            xs.append(d)
            ys.append(n)
            es.append(math.sqrt(n * area_km2) / area_km2)
        return xs, ys, es
    xs, ys, es = [], [], []
    for lower, upper, n in bins(data):
        width_km = (upper - lower) / 1e3
        density = n / (area_km2 * width_km)  # per km^2 per km
        mean = math.sqrt(lower * upper)
        value = density if presentation == "differential" else density * (mean / 1e3) ** 3
        xs.append(mean)
        ys.append(value)
        es.append(value / math.sqrt(n) if n > 0 else 0.0)
    return xs, ys, es


def isochron_points(isochron, presentation):
    """The isochron (cumulative per km^2 at diameters in m) in the presentation's units."""
    if presentation == "cumulative":
        return [p[0] for p in isochron], [p[1] for p in isochron]
    xs, ys = [], []
    for k in range(1, len(isochron) - 1):
        (d0, n0), (d, _), (d1, n1) = isochron[k - 1], isochron[k], isochron[k + 1]
        density = -(n1 - n0) / ((d1 - d0) / 1e3)  # per km^2 per km
        if density <= 0:
            continue
        xs.append(d)
        ys.append(density if presentation == "differential" else density * (d / 1e3) ** 3)
    return xs, ys


def main(argv):
    if len(argv) not in (3, 4) or (len(argv) == 4 and argv[3] not in PRESENTATIONS):
        sys.stderr.write("usage: plot_age.py DATA.json OUT.(png|pdf|svg) [cumulative|differential|R]\n")
        return 2
    presentation = argv[3] if len(argv) == 4 else "cumulative"
    out = argv[2]
    extension = os.path.splitext(out)[1].lower()
    if extension not in (".png", ".pdf", ".svg"):
        sys.stderr.write(f"plot_age.py: {out}: the figure must be .png, .pdf or .svg\n")
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        sys.stderr.write(f"plot_age.py: matplotlib is not available ({error}); no figure written\n")
        return 3
    with open(argv[1]) as f:
        data = json.load(f)

    fig, (ax_sfd, ax_pdf) = plt.subplots(1, 2, figsize=(11, 4.6))
    xs, ys, es = observed_points(data, presentation)
    lower_errors = [min(e, 0.999 * y) for y, e in zip(ys, es)]  # keep the bars on a log axis
    label = "counts" + (" (binned)" if data["counts"]["binned"] else "") + ", 1-sigma Poisson"
    if presentation == "cumulative" and not data["counts"]["binned"]:
        ax_sfd.step(xs, ys, "k-", where="post", lw=0.8)
    ax_sfd.errorbar(xs, ys, yerr=[lower_errors, es], fmt="ks", ms=2.5, lw=0.6, capsize=1.5, label=label)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    age_unit = format_age(max(a["median_yr"] for a in data["ages"]))[1]
    unit_scale = {"Gyr": 1e9, "Myr": 1e6, "kyr": 1e3, "yr": 1.0}[age_unit]
    for i, age in enumerate(data["ages"]):
        c = colours[i % len(colours)]
        ix, iy = isochron_points(age["isochron"], presentation)
        name = age.get("label") or f"Y = {age['cohesion']:g} Pa"  # a chronology system, or a cohesion
        ax_sfd.plot(ix, iy, "-", color=c, label=f"{name}: {age_label(age)}")
        ax_pdf.plot([t / unit_scale for t in age["age_grid_yr"]], [p * unit_scale for p in age["density_per_yr"]],
                    "-", color=c, label=name)
        ax_pdf.axvline(age["median_yr"] / unit_scale, color=c, ls=":", lw=0.8)
    first = data["ages"][0]
    d_lo = first["fit_min_diameter"]
    d_hi = first["fit_max_diameter"]
    span = f"fit range {d_lo:.4g}-{d_hi:.4g} m" if d_hi else f"fit range from {d_lo:.4g} m"
    ax_sfd.axvspan(d_lo, d_hi or max(xs) * 1.5, color="0.85", zorder=0, label=span)
    ax_sfd.set_xscale("log")
    ax_sfd.set_yscale("log")
    ax_sfd.set_xlabel("crater diameter D (rim to rim), m")
    ax_sfd.set_ylabel({"cumulative": "cumulative number N(>D) per km$^2$",
                       "differential": "differential dN/dD per km$^2$ per km",
                       "R": "relative R = D$^3$ dN/dD (D in km), per km$^2$"}[presentation])
    conv = data["conventions"]
    ax_sfd.set_title(f"{conv['body']}: {os.path.basename(data['counts']['source'])}", fontsize=10)
    ax_sfd.legend(fontsize=7)
    ax_pdf.set_xscale("log")
    ax_pdf.set_xlabel(f"model age, {age_unit}")
    ax_pdf.set_ylabel(f"probability density per {age_unit}")
    title = data.get("title") or f"Poisson likelihood ages ({data['scaling_law']['source']}, {conv['region']})"
    ax_pdf.set_title(title, fontsize=10)
    ax_pdf.legend(fontsize=7)
    fig.tight_layout()

    directory = os.path.dirname(os.path.abspath(out))
    tmp = os.path.join(directory, "." + os.path.basename(out) + f".tmp.{os.getpid()}{extension}")
    try:
        fig.savefig(tmp, dpi=130)
        os.replace(tmp, out)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
