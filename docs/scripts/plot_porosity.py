"""P-alpha compaction in the solver: the quasi-static compression path against the crush curve, and the
porous plate-impact profiles against the porous Hugoniot.
Usage: /usr/bin/python3 docs/scripts/plot_porosity.py DIR docs/figures/compaction.png docs/figures/porous_shock.png
DIR from: CRATERKIT_VALIDATION_OUT=DIR build/tests/sph_core/test_engine_porous (writes compaction.csv,
porous_shock_400.csv, porous_shock_1000.csv; the Hugoniot states are in the shock files' first line)."""
import csv
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

directory, compaction_png, shock_png = sys.argv[1], sys.argv[2], sys.argv[3]

# Nominal crush curve of docs/physics.md section 2 (data/materials/basalt_matrix_ryugu.toml).
alpha0, alpha_t, p_e, p_t, p_s, n1, n2 = 2.0, 1.25, 1.0e6, 68.0e6, 213.0e6, 12.0, 3.0


def crush_curve(p):
    p = np.asarray(p, dtype=float)
    out = np.where(p <= p_e, alpha0, 1.0)
    mid = (p > p_e) & (p < p_s)
    second = (alpha_t - 1.0) * ((p_s - p[mid]) / (p_s - p_e)) ** n2
    first = np.where(p[mid] < p_t, (alpha0 - alpha_t) * (np.clip(p_t - p[mid], 0, None) / (p_t - p_e)) ** n1, 0.0)
    out[mid] = first + second + 1.0
    return out


rows = list(csv.DictReader(open(f"{directory}/compaction.csv")))
fig, ax = plt.subplots(figsize=(7, 4.5))
p_line = np.linspace(0.0, 220e6, 2000)
ax.plot(p_line * 1e-6, crush_curve(p_line), "k-", lw=1, label="crush curve alpha_c(P) (docs/physics.md)")
for phase, style in (("loading", "o"), ("unloading", "v"), ("reloading", "^")):
    sel = [r for r in rows if r["phase"] == phase]
    p = np.array([float(r["pressure_Pa"]) for r in sel])
    implied = np.array([float(r["implied_distention"]) for r in sel])
    ax.plot(p * 1e-6, implied, style, ms=3, mfc="none", label=f"SPH {phase}: alpha from geometric density and P")
ax.set_xlabel("mean pressure in the middle of the column (MPa)")
ax.set_ylabel("distention alpha")
ax.set_xscale("symlog", linthresh=1.0)
ax.set_xlim(0, 220)
ax.legend(fontsize=8)
ax.set_title("Quasi-static uniaxial compression, basalt_matrix_ryugu", fontsize=10)
fig.tight_layout()
fig.savefig(compaction_png, dpi=120)

fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex="col")
for column, speed in enumerate((400, 1000)):
    path = f"{directory}/porous_shock_{speed}.csv"
    header = open(path).readline().split()
    ref = {header[k]: float(header[k + 1]) for k in range(2, len(header) - 1, 2)}
    data = np.genfromtxt(path, delimiter=",", skip_header=2)
    x, p, alpha = data[:, 1] * 1e3, data[:, 2] * 1e-6, data[:, 3]
    order = np.argsort(x)
    t = ref["time"]
    contact, front, margin = ref["particle_velocity"] * t * 1e3, ref["shock_velocity"] * t * 1e3, ref["margin"] * 1e3
    axes[0, column].plot(x[order], p[order], ".-", ms=3, lw=0.5, label="SPH (one lattice column)")
    axes[0, column].axhline(ref["pressure_Pa"] * 1e-6, color="k", ls="--", lw=0.8,
                            label=f"porous Hugoniot {ref['pressure_Pa'] * 1e-6:.0f} MPa")
    axes[1, column].plot(x[order], alpha[order], ".-", ms=3, lw=0.5, label="SPH")
    axes[1, column].axhline(ref["distention"], color="k", ls="--", lw=0.8,
                            label=f"alpha_c(P) = {ref['distention']:.3f}")
    for ax in axes[:, column]:
        ax.axvspan(contact + margin, front - margin, color="0.9", label="averaged (target)")
        ax.legend(fontsize=7)
    axes[0, column].set_title(f"porous on porous at {speed} m/s (u_p = {ref['particle_velocity']:.0f} m/s), "
                              f"t = {t * 1e6:.0f} us", fontsize=9)
    axes[1, column].set_xlabel("x (mm)")
axes[0, 0].set_ylabel("pressure (MPa)")
axes[1, 0].set_ylabel("distention alpha")
fig.tight_layout()
fig.savefig(shock_png, dpi=120)
