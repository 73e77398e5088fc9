#pragma once
// P-alpha porosity model (Herrmann 1969; Carroll & Holt 1972) with the two-slope crush curve and the
// consistent distention rate of Jutzi, Benz & Michel (2008, eqs. 8-13), as stated in docs/physics.md
// section 2. Distention alpha = rho_matrix / rho >= 1; bulk pressure P = P_m(rho_matrix, E) / alpha.
#include <algorithm>
#include <cmath>

namespace craterkit::sph {

struct PAlphaParameters {
  double initial_distention = 2.0;      // alpha0
  double transition_distention = 1.25;  // alpha_t
  double elastic_pressure = 1.0e6;      // P_e, Pa
  double transition_pressure = 68.0e6;  // P_t, Pa
  double solid_pressure = 213.0e6;      // P_s, Pa
  double exponent_1 = 12.0;             // n1
  double exponent_2 = 3.0;              // n2
};

// alpha_c(P): the crush curve of docs/physics.md section 2.
inline double crush_curve_distention(const PAlphaParameters& p, double pressure) noexcept {
  if (pressure <= p.elastic_pressure) return p.initial_distention;
  if (pressure >= p.solid_pressure) return 1.0;
  const double second =
      (p.transition_distention - 1.0) *
      std::pow((p.solid_pressure - pressure) / (p.solid_pressure - p.elastic_pressure), p.exponent_2);
  if (pressure >= p.transition_pressure) return second + 1.0;
  const double first =
      (p.initial_distention - p.transition_distention) *
      std::pow((p.transition_pressure - pressure) / (p.transition_pressure - p.elastic_pressure),
               p.exponent_1);
  return first + second + 1.0;
}

// dalpha_c/dP (<= 0), zero outside (P_e, P_s).
inline double crush_curve_slope(const PAlphaParameters& p, double pressure) noexcept {
  if (pressure <= p.elastic_pressure || pressure >= p.solid_pressure) return 0.0;
  const double ds = p.solid_pressure - p.elastic_pressure;
  double slope = -(p.transition_distention - 1.0) * p.exponent_2 *
                 std::pow((p.solid_pressure - pressure) / ds, p.exponent_2 - 1.0) / ds;
  if (pressure < p.transition_pressure) {
    const double dt = p.transition_pressure - p.elastic_pressure;
    slope -= (p.initial_distention - p.transition_distention) * p.exponent_1 *
             std::pow((p.transition_pressure - pressure) / dt, p.exponent_1 - 1.0) / dt;
  }
  return slope;
}

// What the distention rate needs of the matrix equation of state at the current state.
struct MatrixResponse {
  double dpressure_ddensity;  // dP_m / drho_m at constant E
  double dpressure_denergy;   // dP_m / dE at constant rho_m
};

// dalpha/dt during plastic compaction (Jutzi et al. 2008, eq. 13 as written in docs/physics.md):
//   dalpha/dt = (dalpha_c/dP) [dE/dt dP_m/dE + alpha drho/dt dP_m/drho_m]
//               / [alpha + (dalpha_c/dP) (P - rho dP_m/drho_m)],
// applied only while loading (the bracket, proportional to the matrix pressure rate, is positive) and on
// the crush curve (alpha >= alpha_c(P)); zero otherwise, and never positive: compaction is irreversible.
// P and rho are the bulk pressure and density.
inline double distention_rate(const PAlphaParameters& p, double distention, double bulk_pressure,
                              double bulk_density, double density_rate, double energy_rate,
                              const MatrixResponse& matrix) noexcept {
  const double slope = crush_curve_slope(p, bulk_pressure);
  if (slope >= 0.0) return 0.0;  // elastic (P <= P_e) or fully compacted (P >= P_s)
  const double loading =
      energy_rate * matrix.dpressure_denergy + distention * density_rate * matrix.dpressure_ddensity;
  if (loading <= 0.0) return 0.0;
  if (distention < crush_curve_distention(p, bulk_pressure)) return 0.0;  // inside the curve: elastic
  const double denominator = distention + slope * (bulk_pressure - bulk_density * matrix.dpressure_ddensity);
  if (denominator <= 0.0) return 0.0;
  return std::min(0.0, slope * loading / denominator);
}

}  // namespace craterkit::sph
