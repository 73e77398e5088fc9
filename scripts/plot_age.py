#!/usr/bin/python3
"""Standard model-age figure of `craterkit age --plot`: the cumulative crater size-frequency
distribution with the fitted isochrons (left) and the age probability densities (right), one colour per
cohesion. Usage: plot_age.py DATA.json OUT.png, where DATA.json is written by `craterkit age`.
The PNG is written to a temporary name and renamed, so a failure never leaves a partial figure."""
import json
import os
import sys


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_age.py DATA.json OUT.png\n")
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
    out = argv[2]

    fig, (ax_sfd, ax_pdf) = plt.subplots(1, 2, figsize=(11, 4.6))
    observed = data["observed_cumulative_per_km2"]
    d = [p[0] for p in observed]
    n = [p[1] for p in observed]
    if data["counts"]["binned"]:
        ax_sfd.plot(d, n, "ks", label="counts (binned)")
    else:
        ax_sfd.step(d, n, "k-", where="post", lw=1.2, label="counts")
        ax_sfd.plot(d, n, "k.", ms=3)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, age in enumerate(data["ages"]):
        c = colours[i % len(colours)]
        iso = age["isochron"]
        med = age["median_yr"] / 1e6
        lo, hi = (x / 1e6 for x in age["sigma1_yr"])
        label = f"Y = {age['cohesion']:g} Pa: {med:.3g} (+{hi - med:.2g} / -{med - lo:.2g}) Myr"
        ax_sfd.plot([p[0] for p in iso], [p[1] for p in iso], "-", color=c, label=label)
        ax_pdf.plot([t / 1e6 for t in age["age_grid_yr"]], [p * 1e6 for p in age["density_per_yr"]], "-", color=c,
                    label=f"Y = {age['cohesion']:g} Pa")
        ax_pdf.axvline(med, color=c, ls=":", lw=0.8)
    dmin = data["ages"][0]["fit_min_diameter"]
    ax_sfd.axvline(dmin, color="0.6", ls="--", lw=0.8, label=f"fit range from {dmin:.3g} m")
    ax_sfd.set_xscale("log")
    ax_sfd.set_yscale("log")
    ax_sfd.set_xlabel("crater diameter D (rim to rim), m")
    ax_sfd.set_ylabel("cumulative number N(>D) per km$^2$")
    conv = data["conventions"]
    ax_sfd.set_title(f"{conv['body']}: {os.path.basename(data['counts']['source'])}", fontsize=10)
    ax_sfd.legend(fontsize=7)
    ax_pdf.set_xscale("log")
    ax_pdf.set_xlabel("model age, Myr")
    ax_pdf.set_ylabel("probability density per Myr")
    ax_pdf.set_title(f"Poisson likelihood ages ({data['scaling_law']['source']}, {conv['region']})", fontsize=10)
    ax_pdf.legend(fontsize=7)
    fig.tight_layout()

    directory = os.path.dirname(os.path.abspath(out))
    tmp = os.path.join(directory, "." + os.path.basename(out) + f".tmp.{os.getpid()}.png")
    try:
        fig.savefig(tmp, dpi=130)
        os.replace(tmp, out)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
