#!/usr/bin/python3
"""Growth per step of an elastic oscillation under craterkit's time integration (docs/validation.md,
"Boulders": why the boulder run gains energy).

The model is one elastic mode of frequency w: dv/dt = -w s, ds/dt = w v, where s stands for a stress (or
density) that the solver integrates from its rate, not from the positions. Three schemes, each written as
the linear map of one step (state: the variables and the rates kept between steps):

  predictor-corrector (integrator.hpp): the force of step n+1 uses the predicted s* = s^n + dt s'^n, the rate
      s'^{n+1} the predicted v* = v^n + dt a^n; both are then corrected with the trapezoidal rule;
  Heun (classical second-order Runge-Kutta) on (v, s);
  leapfrog with s updated like a position: s^{n+1} = s^n + dt w v^{n+1/2}, which needs the velocity
      gradient at the half step, a second pass over the pairs.

Prints max |eigenvalue| - 1 of each map (the relative growth of the amplitude per step) against w dt and,
with --plot FILE, draws it.
Usage: /usr/bin/python3 docs/scripts/integrator_stability.py [--plot docs/figures/integrator_stability.png]
"""
import argparse

import numpy as np


def predictor_corrector(wdt):
    def step(state):
        v, s, a, s_rate = state
        v_predicted = v + wdt * a
        s_predicted = s + wdt * s_rate
        a_new, s_rate_new = -s_predicted, v_predicted
        return np.array([v + 0.5 * wdt * (a + a_new), s + 0.5 * wdt * (s_rate + s_rate_new), a_new, s_rate_new])

    return step, 4


def heun(wdt):
    def step(state):
        v, s = state
        v1, s1 = v - wdt * s, s + wdt * v
        return np.array([v + 0.5 * wdt * (-s - s1), s + 0.5 * wdt * (v + v1)])

    return step, 2


def leapfrog(wdt):
    def step(state):
        v, s, a = state
        v_half = v + 0.5 * wdt * a
        s_new = s + wdt * v_half
        a_new = -s_new
        return np.array([v_half + 0.5 * wdt * a_new, s_new, a_new])

    return step, 3


def growth_per_step(scheme, wdt):
    step, size = scheme(wdt)
    matrix = np.array([step(unit) for unit in np.eye(size)]).T
    return max(abs(np.linalg.eigvals(matrix))) - 1.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--plot", help="write the figure to this file")
    args = parser.parse_args()
    schemes = {"predictor-corrector (craterkit)": predictor_corrector, "Heun (RK2)": heun,
               "leapfrog, s from v^{n+1/2}": leapfrog}
    table = [0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0]
    print("w dt      " + "  ".join(f"{x:9.1f}" for x in table))
    for name, scheme in schemes.items():
        print(f"{name}\n          " + "  ".join(f"{growth_per_step(scheme, x):9.2e}" for x in table))
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        wdt = np.linspace(0.02, 1.2, 200)
        fig, ax = plt.subplots(figsize=(6, 4))
        for name, scheme in schemes.items():
            growth = np.array([growth_per_step(scheme, x) for x in wdt])
            ax.loglog(wdt, np.maximum(growth, 1e-16), label=name)
        ax.set_xlabel("w dt of the mode")
        ax.set_ylabel("growth of its amplitude per step")
        ax.set_ylim(1e-8, 2)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title("elastic mode dv/dt = -w s, ds/dt = w v")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)


if __name__ == "__main__":
    main()
