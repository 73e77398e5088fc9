"""Free elastic plate: end displacement against time, SPH and thin-plate theory.
Usage: /usr/bin/python3 docs/scripts/plot_elastic_plate.py DIR docs/figures/elastic_plate.png [AMPLITUDE]
DIR holds plate_*.csv written by: CRATERKIT_VALIDATION_OUTPUT=DIR build/tests/sph_core/test_engine_elastic_plate;
AMPLITUDE is the end amplitude over L of those runs (the test's CRATERKIT_PLATE_AMPLITUDE, default 1e-3)."""
import glob
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

directory, png = sys.argv[1], sys.argv[2]
relative_amplitude = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-3
# Thin-plate theory (Gray, Monaghan & Swift 2001 parameters), free-free first mode kL = 4.7300.
rho, E, nu, H = 1000.0, 2e6, 0.3975, 0.02
L = 15 * H
k = 4.73004074 / L
omega = math.sqrt(E * H**2 * k**4 / (12 * rho * (1 - nu**2)))
amplitude = relative_amplitude * L

fig, ax = plt.subplots(figsize=(8, 4.5))
t = np.linspace(0, 1.5 * 2 * math.pi / omega, 400)
ax.plot(t, amplitude * np.sin(omega * t) * 1e3, "k--", label=f"thin-plate theory, T = {2 * math.pi / omega:.4f} s")
for path in sorted(glob.glob(os.path.join(directory, "plate_*.csv")), key=lambda p: int(p.split("_")[-1][:-4])):
    with open(path) as f:
        comment = f.readline().strip("# \n")
    data = np.loadtxt(path, delimiter=",", comments="#")
    across = os.path.basename(path).split("_")[1].split(".")[0]
    measured = comment.split("measured")[-1].strip()
    ax.plot(data[:, 0], data[:, 1] * 1e3, "-", label=f"SPH, {across} particles across: T = {measured}")
ax.axhline(0, color="k", lw=0.5)
ax.set_xlabel("t (s)")
ax.set_ylabel("end displacement (mm)")
ax.set_title(f"Free plate, L = 15 H, E = 2 MPa, nu = 0.3975; end amplitude {100 * relative_amplitude:g} % of L", fontsize=10)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(png, dpi=110)
