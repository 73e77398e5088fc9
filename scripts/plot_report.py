#!/usr/bin/python3
"""Figures of `craterkit report` (and of the main job, `craterkit run`; docs/report.md), drawn from the numbers
of its report.json; nothing is computed here but what a plot needs.
  scaled_radius.png  the engine's craters as pi_R against pi_2 per cohesion, with the fitted law and the
                     published sand (gravity regime) and perlite-sand (strength regime) laws, a panel per group
  sci_cohesion.png   the engine's SCI crater against cohesion per table and target, with the observed band
  friction.png       the engine's cohesionless SCI crater against friction, with the observed band
  rates.png          crater-formation rates relative to the reference cohesion against crater diameter
  ages.png           probability densities of the model ages of the Ryugu counts, per cohesion
Usage: plot_report.py REPORT.json OUTDIR FIGURE.png...  (the figures to draw, by those names). Each PNG is
written to a temporary name and renamed. Exit status 3 without matplotlib."""
import json
import math
import os
import sys
import textwrap


def cohesion_colours(plt, cohesions):
    """One colour per cohesion, the same in every figure."""
    values = sorted(set(cohesions))
    n = max(1, len(values) - 1)
    return {y: plt.cm.viridis(0.9 * i / n) for i, y in enumerate(values)}


def save(fig, path):
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def panel_grid(plt, count, width=5.2, height=4.2, columns=3):
    columns = min(columns, count)
    rows = math.ceil(count / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(width * columns, height * rows), squeeze=False)
    flat = [ax for row in axes for ax in row]
    for ax in flat[count:]:
        ax.set_visible(False)
    return fig, flat[:count]


def group_title(group, first_line=None):
    """The group's table (by file name) and its grouping values, wrapped to fit a panel."""
    lines = [first_line] if first_line else []
    lines.append(os.path.basename(group["table"]))
    lines += textwrap.wrap(group["key_label"], 60)
    return "\n".join(lines)


def series_label(report, series):
    several = len(report["tables"]) > 1
    name = os.path.basename(series["table"])
    return f"{name}: {series['label']}" if several else series["label"]


def scaled_radius(plt, report, path):
    groups = [g for g in report["groups"] if g["fitted"] and "pi2_grid" in g["curves"]]
    colours = cohesion_colours(plt, [p["cohesion"] for g in groups for p in g["curves"]["points"]])
    fig, axes = panel_grid(plt, len(groups))
    for ax, group in zip(axes, groups):
        curves = group["curves"]
        for y in sorted({p["cohesion"] for p in curves["points"]}):
            mine = [p for p in curves["points"] if p["cohesion"] == y]
            ax.loglog([p["pi2"] for p in mine], [p["pi_r"] for p in mine], "o", color=colours[y], label=f"Y = {y:g} Pa")
        for line in curves["fitted"]:
            ax.loglog(curves["pi2_grid"], line["pi_r"], "-", color=colours[line["cohesion"]])
        ax.loglog(curves["pi2_grid"], curves["sand"]["pi_r"], "k--", lw=1, label=f"{curves['sand']['set']} (Y = 0)")
        for level in curves["perlite"]["levels"]:
            ax.axhline(level["pi_r"], color=colours[level["cohesion"]], ls=":", lw=1)
        if curves["perlite"]["levels"]:
            ax.plot([], [], "k:", lw=1, label=f"{curves['perlite']['set']} (strength regime)")
        ax.set_xlabel(r"$\pi_2 = g a / U^2$")
        ax.set_ylabel(r"$\pi_R = R (\rho/m)^{1/3}$")
        ax.set_title(group_title(group), fontsize=8)
        ax.legend(fontsize=7)
    fig.suptitle(report["producer"] + ": scaled crater radius", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    save(fig, path)


def observed_band(ax, section):
    r0, s0 = section["observed_crater_radius"], section["observed_crater_radius_sigma"]
    ax.axhspan(r0 - s0, r0 + s0, color="0.88", label="observed SCI crater (Arakawa et al. 2020)")
    ax.axhline(r0, color="0.55", lw=1)


def legend_below(ax):
    # Below the axes: a study has many series, and a legend inside would cover some of their points.
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1, frameon=False)


def sci_cohesion(plt, report, path):
    section = report["sci_engine"]
    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    observed_band(ax, section)
    for series in section["series"]:
        points = series["points"]
        sigma = [p["crater_radius_sigma"] or 0.0 for p in points]
        line = ax.errorbar([p["cohesion"] for p in points], [p["crater_radius"] for p in points], yerr=sigma,
                           fmt="o-", capsize=3, label=series_label(report, series))
        if series["cohesion_for_observed_radius"] is not None:
            ax.plot([series["cohesion_for_observed_radius"]], [section["observed_crater_radius"]], "x", ms=9,
                    color=line[0].get_color())
    ax.set_xscale("symlog", linthresh=0.01)
    ax.set_xlabel("cohesion (Pa; linear below 0.01 Pa)")
    ax.set_ylabel("SCI crater radius (m)")
    ax.set_title("the engine's SCI crater (x: the cohesion of the observed radius)", fontsize=9)
    legend_below(ax)
    fig.tight_layout()
    save(fig, path)


def friction(plt, report, path):
    section = report["friction"]
    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    observed_band(ax, section)
    for series in section["series"]:
        points = series["points"]
        sigma = [p["crater_radius_sigma"] or 0.0 for p in points]
        ax.errorbar([p["friction"] for p in points], [p["crater_radius"] for p in points], yerr=sigma, fmt="o-",
                    capsize=3, label=series_label(report, series))
    ax.set_xlabel("friction coefficient")
    ax.set_ylabel("SCI crater radius without cohesion (m)")
    ax.set_title("the engine's cohesionless SCI crater", fontsize=9)
    legend_below(ax)
    fig.tight_layout()
    save(fig, path)


def rates(plt, report, path):
    groups = [g for g in report["groups"] if "rates" in g]
    colours = cohesion_colours(plt, report["cohesions"])
    fig, axes = panel_grid(plt, len(groups))
    for ax, group in zip(axes, groups):
        rows = group["rates"]["rows"]
        for y in report["cohesions"]:
            mine = [r for r in rows if r["cohesion"] == y]
            ax.loglog([r["crater_diameter"] for r in mine], [r["relative_rate"] for r in mine], "o-", ms=3,
                      color=colours[y], label=f"Y = {y:g} Pa")
        ax.set_xlabel("crater diameter D, rim to rim (m)")
        ax.set_ylabel(f"rate of craters > D / rate at {group['rates']['reference_cohesion']:g} Pa")
        ax.set_title(group_title(group), fontsize=8)
        ax.legend(fontsize=7)
    fig.suptitle("relative crater-formation rates on Ryugu", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    save(fig, path)


def ages(plt, report, path):
    groups = [g for g in report["groups"] if "ages" in g]
    colours = cohesion_colours(plt, report["cohesions"])
    units = len(groups[0]["ages"]["units"])
    fig, axes = plt.subplots(len(groups), units, figsize=(5 * units, 4 * len(groups)), squeeze=False)
    for row, group in zip(axes, groups):
        for ax, unit in zip(row, group["ages"]["units"]):
            for age in unit["rows"]:
                # Density per unit of ln t (t p(t)), so that the curves keep their areas on the log axis.
                t = age["age_yr"]
                ax.semilogx(t, [x * p for x, p in zip(t, age["density_per_yr"])], color=colours[age["cohesion"]],
                            label=f"Y = {age['cohesion']:g} Pa")
            ax.set_xlabel("model age (yr)")
            ax.set_ylabel("t p(t)")
            ax.set_title(group_title(group, f"{unit['label']} ({unit['craters']:g} craters)"), fontsize=8)
            ax.legend(fontsize=7)
    fig.suptitle(f"model ages of the Ryugu counts (population {groups[0]['ages']['population']}: indicative only)",
                 fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    save(fig, path)


FIGURES = {"scaled_radius.png": scaled_radius, "sci_cohesion.png": sci_cohesion, "friction.png": friction,
           "rates.png": rates, "ages.png": ages}


def main(argv):
    if len(argv) < 3 or any(name not in FIGURES for name in argv[3:]):
        sys.stderr.write("usage: plot_report.py REPORT.json OUTDIR [" + " ".join(FIGURES) + "]...\n")
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        sys.stderr.write(f"plot_report.py: matplotlib is not available ({error}); no figure written\n")
        return 3
    with open(argv[1]) as f:
        report = json.load(f)
    status = 0
    for name in argv[3:]:
        try:
            FIGURES[name](plt, report, os.path.join(argv[2], name))
        except Exception as error:  # one figure's failure leaves the others
            sys.stderr.write(f"plot_report.py: {name} not drawn: {type(error).__name__}: {error}\n")
            status = 1
        plt.close("all")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
