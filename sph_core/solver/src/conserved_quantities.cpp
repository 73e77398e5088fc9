#include "craterkit/sph/solver/conserved_quantities.hpp"

#include <algorithm>
#include <cmath>

namespace craterkit::sph {
namespace {

// Neumaier's compensated sum: the error of each addition is carried separately, so sums of many
// terms of mixed sign (momenta) keep their round-off near one ulp of the largest partial sum.
struct CompensatedSum {
  double sum = 0;
  double compensation = 0;
  void add(double term) {
    const double t = sum + term;
    compensation += std::abs(sum) >= std::abs(term) ? (sum - t) + term : (term - t) + sum;
    sum = t;
  }
  [[nodiscard]] double value() const { return sum + compensation; }
};

constexpr int n_sums = 8;  // mass, px, py, pz, kinetic, internal, potential, |p|

// Block size of the partial sums: fixed (not derived from the thread count), so that the order of
// every addition, and therefore the result, is the same for any number of threads.
constexpr std::size_t block_size = 4096;

}  // namespace

ConservedQuantities measure_conserved(const Particles& p, std::array<double, 3> gravity) {
  const std::size_t n = p.size();
  const std::size_t n_blocks = (n + block_size - 1) / block_size;
  std::vector<std::array<double, n_sums>> blocks(n_blocks);

#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < n_blocks; ++b) {
    std::array<CompensatedSum, n_sums> s{};
    const std::size_t end = std::min(n, (b + 1) * block_size);
    for (std::size_t i = b * block_size; i < end; ++i) {
      const double m = p.mass[i];
      const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i];
      s[0].add(m);
      s[1].add(m * p.vx[i]);
      s[2].add(m * p.vy[i]);
      s[3].add(m * p.vz[i]);
      s[4].add(0.5 * m * v2);
      s[5].add(m * p.specific_energy[i]);
      // Potential of a uniform field: phi = -g.x, zero at the coordinate origin.
      s[6].add(-m * (gravity[0] * p.x[i] + gravity[1] * p.y[i] + gravity[2] * p.z[i]));
      s[7].add(m * std::sqrt(v2));
    }
    for (int k = 0; k < n_sums; ++k) blocks[b][k] = s[k].value();
  }

  std::array<CompensatedSum, n_sums> total{};
  for (const auto& block : blocks) {
    for (int k = 0; k < n_sums; ++k) total[k].add(block[k]);
  }
  ConservedQuantities q;
  q.mass = total[0].value();
  q.momentum_x = total[1].value();
  q.momentum_y = total[2].value();
  q.momentum_z = total[3].value();
  q.kinetic_energy = total[4].value();
  q.internal_energy = total[5].value();
  q.potential_energy = total[6].value();
  q.absolute_momentum = total[7].value();
  q.total_energy = q.kinetic_energy + q.internal_energy + q.potential_energy;
  return q;
}

double relative_energy_error(const ConservedQuantities& initial, const ConservedQuantities& now) {
  double scale = std::abs(initial.total_energy);
  if (scale == 0) {
    scale = std::abs(initial.kinetic_energy) + std::abs(initial.internal_energy) +
            std::abs(initial.potential_energy);
  }
  const double change = std::abs(now.total_energy - initial.total_energy);
  return scale > 0 ? change / scale : change;
}

double relative_momentum_error(const ConservedQuantities& initial, const ConservedQuantities& now) {
  const double scale = std::max(initial.absolute_momentum, now.absolute_momentum);
  if (scale == 0) return 0;
  const double dx = now.momentum_x - initial.momentum_x;
  const double dy = now.momentum_y - initial.momentum_y;
  const double dz = now.momentum_z - initial.momentum_z;
  return std::sqrt(dx * dx + dy * dy + dz * dz) / scale;
}

}  // namespace craterkit::sph
