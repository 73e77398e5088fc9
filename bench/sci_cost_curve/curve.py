"""The SCI crater's cost model from runs at several outer spacings (bench/sci_cost_curve/run.sh).

Every run costs a fixed part (the graded core, the same in every run) and the outer particles' part, their number
(~dx^-3) times their late-stage steps (~dx^-1): particle updates U(dx) = U0 + k dx^-p. U0 and k by least squares
for each p on a grid, p where the relative residuals are least (through three runs the fit is exact). Prints each
run, the fit, and the projected updates and wall time at finer spacings (the particle counts there: `craterkit
simulate --dry-run`).

Usage: python3 curve.py RUN_FOLDER DX DX DX [DX ...]   (RUN_FOLDER holds run-DX.json of each)
"""
import json
import sys


def load(folder, dx):
    with open(f"{folder}/run-{dx}.json") as f:
        d = json.load(f)
    return {"dx": float(dx), "particles": d["particles"], "wall": d["wall_seconds"],
            "updates": d["wall_seconds"] * d["particle_updates_per_second"],
            "rate": d["particle_updates_per_second"], "radius": d["crater_radius"],
            "uncertainty": d["crater_radius_uncertainty"], "end": d["crater_growth_end_time"]}


def fit_linear(runs, p):
    """U0 and k by least squares for a given p, and the sum of squared relative residuals."""
    xs = [r["dx"] ** -p for r in runs]
    ys = [r["updates"] for r in runs]
    n = len(runs)
    mx, my = sum(xs) / n, sum(ys) / n
    k = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    u0 = my - k * mx
    return u0, k, sum(((u0 + k * x) / y - 1.0) ** 2 for x, y in zip(xs, ys))


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    folder = sys.argv[1]
    runs = sorted((load(folder, dx) for dx in sys.argv[2:]), key=lambda r: -r["dx"])
    for r in runs:
        print(f"dx_max {r['dx']:g} m: {r['particles']} particles, {r['wall']:.0f} s, {r['updates']:.3g} updates "
              f"({r['rate']:.3g}/s), crater {r['radius']:.3f} +- {r['uncertainty']:.2f} m at {r['end']:.0f} s")
    # p on a fine grid: the best least-squares fit (exact through three runs)
    p = min((fit_linear(runs, q / 1000.0)[2], q / 1000.0) for q in range(1000, 8001))[1]
    u0, k, _ = fit_linear(runs, p)
    rate = runs[-1]["rate"]
    print(f"updates = {u0:.3g} + {k:.3g} dx^-{p:.2f}; projections at the finest run's {rate:.3g} updates/s:")
    for dx in (0.25, 0.18, 0.125, 0.09):
        u = u0 + k * dx ** -p
        print(f"  dx_max {dx:g} m: {u:.3g} updates, {u / rate / 3600:.2f} h")


if __name__ == "__main__":
    main()
