#!/usr/bin/env python3
"""Strong and weak scaling of the MPI decomposition projected from the measured halo sizes and phase costs
(docs/parallel.md, "Scaling model"; bench/RESULTS.md). Standard library only:

    python3 bench/domain_model/scaling_model.py [--particles 1e7] [--latency 2e-6] [--bandwidth 5e9]

Per process and step, with n = N/R owned particles and H = f(n) n halo particles:

    T = n (c_search + c_density + c_state) (1 + f)     the per-particle phases run on the halos too
      + n c_rates                                      the rate pass: owned particles only
      + n c_handling                                   today's halo handling (find, insert, remove: O(n))
      + 3 m latency + H b / bandwidth                  three exchanges of m messages, b bytes per halo particle
      + 2 log2(R) latency                              the time step and the conserved sums (allreduce)

f(n) = a n^(-1/3), a surface-to-volume law: fitted on the measured halos (Sedov over 2 processes at 27,000 to
1e6 particles; the SCI example over 2-16 processes), and for the projection taken as the value of a compact
interior domain, a = 6 w with w = 2.4 spacings (the reach h_i + h_j = 2 x 1.2 dx on each of six faces), which
the largest measured rank count approaches. Costs per particle and core from the Sedov run at 1e6 particles
over 2 processes x 1 thread (bound to cores): the search, density and state per owned or halo particle, the
rates and the handling per owned particle.
Assumptions: one process per core, a perfect split (no imbalance), the network's latency and bandwidth per
process as given (defaults: an InfiniBand-class interconnect shared by the cores of a node), and a Sedov-like
problem (gas: 184 bytes a particle; an impact's solids carry 347 and cost more per particle).
"""
import argparse
import math

# Measured (bench/RESULTS.md, "Sedov over MPI processes" and "Halos of the MPI domain decomposition").
HALOS = [  # (owned particles per process, halo / owned)
    (13_500, 0.27), (48_668, 0.17), (500_000, 0.08),  # Sedov, 2 processes
    (8_987, 0.293), (4_494, 0.356), (2_247, 0.648), (1_123, 1.004),  # SCI t = 0.01 s, 2-16 ranks
    (8_987, 0.255), (4_494, 0.494), (2_247, 0.757), (1_123, 1.199),  # SCI t = 1.0 s
]
# The Sedov blast at 1e6 particles over 2 processes x 1 thread bound to cores (22:30 UTC): 2.632 s per step,
# 500,000 owned and 8 % halo particles per process; the faster process's phase shares (one core each).
WALL_2x1, OWNED_2x1, HALOS_2x1 = 2.632, 500_000, 0.08
SHARES_2x1 = {"search": 0.404, "density": 0.098, "state": 0.013, "rates": 0.208, "handling": 0.239}
MEASURED_2x1 = ((97_336, 0.205), (1e6, 2.632))  # s per step (97,336: median of three)
BYTES_PER_HALO = 184 + 8  # every field of a gas particle and its key
W_SUPPORT = 2.4  # halo width in spacings: h_i + h_j = 2 x 1.2 dx
MESSAGES_INTERIOR = 26  # neighbours of a compact interior domain (faces, edges, corners)


def fitted_surface_coefficient():
    """Least squares of log f = log a - log(n)/3 over the measured points: a and the largest misfit."""
    logs = [math.log(f) + math.log(n) / 3.0 for n, f in HALOS]
    a = math.exp(sum(logs) / len(logs))
    worst = max(abs(f / (a * n ** (-1.0 / 3.0)) - 1.0) for n, f in HALOS)
    return a, worst


def step_time(n, ranks, costs, a, latency, bandwidth, handling):
    f = a * n ** (-1.0 / 3.0) if ranks > 1 else 0.0
    halos = f * n
    messages = min(ranks - 1, MESSAGES_INTERIOR)
    compute = n * (costs["search"] + costs["density"] + costs["state"]) * (1.0 + f) + n * costs["rates"]
    halo_work = n * handling if ranks > 1 else 0.0
    network = (3 * messages * latency + halos * BYTES_PER_HALO / bandwidth + 2 * math.log2(ranks) * latency
               if ranks > 1 else 0.0)
    return compute, halo_work, network, f


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--particles", type=float, default=1e7)
    parser.add_argument("--latency", type=float, default=2e-6, help="s per message")
    parser.add_argument("--bandwidth", type=float, default=5e9, help="bytes/s per process")
    parser.add_argument("--weak", type=float, default=1e5, help="particles per process for weak scaling")
    args = parser.parse_args()
    held = OWNED_2x1 * (1.0 + HALOS_2x1)
    per = {"search": held, "density": held, "state": held, "rates": OWNED_2x1, "handling": OWNED_2x1}
    costs = {k: WALL_2x1 * SHARES_2x1[k] / per[k] for k in ("search", "density", "state", "rates")}
    handling = WALL_2x1 * SHARES_2x1["handling"] / per["handling"]
    a_fit, worst = fitted_surface_coefficient()
    a_interior = 6.0 * W_SUPPORT
    print(f"halo / owned = a n^(-1/3): fitted a = {a_fit:.2f} (largest misfit {100 * worst:.0f} %), "
          f"projection a = {a_interior:.1f} (compact interior domain)")
    print(f"costs per particle and core (us): " + ", ".join(f"{k} {1e6 * v:.2f}" for k, v in costs.items())
          + f"; halo handling today {1e6 * handling:.2f} per owned particle")
    # The model against the two measured two-process steps (a from the 2-process Sedov halos alone).
    a_two = math.exp(sum(math.log(f) + math.log(n) / 3.0 for n, f in HALOS[:3]) / 3.0)
    for particles, measured in MEASURED_2x1:
        compute, halo_work, network, _ = step_time(particles / 2, 2, costs, a_two, args.latency, args.bandwidth,
                                                   handling)
        print(f"check, 2 x 1 at {particles:.3g} particles: model {compute + halo_work + network:.3g} s/step, "
              f"measured {measured}")
    for title, total in (("strong", lambda r: args.particles), ("weak", lambda r: args.weak * r)):
        print(f"\n{title} scaling ({'N = %.3g' % args.particles if title == 'strong' else 'n = %.3g per process' % args.weak})")
        print("| processes | particles per process | halo / owned | s/step today | efficiency today |"
              " s/step, halos kept | efficiency, halos kept | network share |")
        print("|---|---|---|---|---|---|---|---|")
        for ranks in (1, 16, 32, 64, 128, 256):
            n = total(ranks) / ranks
            reference = total(ranks) * sum(costs.values()) / ranks  # serial time divided by the processes
            rows = []
            for handling_cost in (handling, 0.0):
                compute, halo_work, network, f = step_time(n, ranks, costs, a_interior, args.latency,
                                                           args.bandwidth, handling_cost)
                rows.append((compute + halo_work + network, network))
            (today, net), (kept, _) = rows
            print(f"| {ranks} | {n:.3g} | {f:.2f} | {today:.3g} | {100 * reference / today:.0f} % | "
                  f"{kept:.3g} | {100 * reference / kept:.0f} % | {100 * net / today:.1f} % |")


if __name__ == "__main__":
    main()
