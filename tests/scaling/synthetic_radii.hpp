#pragma once
// Synthetic crater-radius tables for the fit tests: impacts on a grid of projectile masses, densities, target
// strengths and speeds, with radii from a known law times log-normal noise.
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "craterkit/scaling/point_source.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace scaling_test {

constexpr double kNoise = 0.05;  // standard deviation of ln R

// Truth: the Jutzi et al. (2022) Ryugu constants, in the Housen & Holsapple (2011) form.
inline craterkit::scaling::ScalingLaw truth_hh() {
  return {craterkit::scaling::Form::hh2011, 0.60, 0.25, 0.44, 0.4};
}

struct Grid {
  std::vector<double> masses{0.05, 2.0, 100.0, 2000.0};  // kg
  std::vector<double> densities{2700.0, 7800.0};         // kg/m^3
  std::vector<double> strengths{0.05, 0.5, 5.0, 50.0};   // Pa
  std::vector<double> velocities{1000.0, 4000.0};        // m/s
  double gravity = 1.4e-4;
};

// Impacts on the grid with radii from `law` times exp(kNoise N(0,1)); sigma column = kNoise R.
inline craterkit::scaling::RadiiTable synthetic(const craterkit::scaling::ScalingLaw& law, const Grid& grid,
                                                unsigned seed, bool with_sigma = true) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  craterkit::scaling::RadiiTable table;
  table.source = "synthetic";
  int line = 1;
  for (double delta : grid.densities) {
    for (double mass : grid.masses) {
      for (double y : grid.strengths) {
        for (double u : grid.velocities) {
          craterkit::scaling::ImpactRecord row;
          row.impactor = {std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * delta)), delta, u};
          row.target = {1300.0, grid.gravity, y};
          row.crater_radius = craterkit::scaling::crater_radius(law, row.impactor, row.target) *
                              std::exp(kNoise * normal(random));
          if (with_sigma) row.crater_radius_sigma = kNoise * row.crater_radius;
          row.line = ++line;
          table.rows.push_back(row);
        }
      }
    }
  }
  return table;
}

inline double truth_value(const craterkit::scaling::ScalingLaw& law, const std::string& name) {
  if (name == "mu") return law.mu;
  if (name == "nu") return law.nu;
  return name.back() == '1' ? law.coefficient_1 : law.coefficient_2;
}

}  // namespace scaling_test
