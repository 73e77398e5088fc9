#pragma once
// Published chronology systems in the form crater-counting tools use (craterstats; Neukum et al. 2001):
// a production function, the shape of the cumulative crater size-frequency distribution as a polynomial,
//   log10 N(>=D) = a0 + a1 log10 D + ... + a11 (log10 D)^11   (D in km, N per km^2),
// valid for D_min <= D <= D_max, and a chronology function, the density of craters >= 1 km after t Gyr,
//   N(1)(t) = c0 (exp(c1 t) - 1) + c2 t^2 + c3 t                (per km^2),
// so that N(>=D, t) = N(1)(t) 10^(P(log10 D) - a0). a0 only fixes the polynomial's value at 1 km and drops
// out. Shipped in data/chronology/<name>.toml (docs/chronology.md, "Chronology systems").
//
// For the model ages of model_age.hpp a system is written as a present-day production rate and a clock:
//   r(D) = N(1)'(0) 10^(P(log10 D) - a0)  per km^2 per Gyr (converted to per m^2 per year),
//   clock(t) = N(1)(t) / N(1)'(0)         (years of present-day flux equivalent to t years),
// which gives the same N(>=D, t) and lets the likelihood work with either flux.
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "craterkit/chronology/production.hpp"

namespace craterkit::chronology {

struct ChronologySystem {
  std::string name;   // file stem, e.g. "moon_neukum2001"
  std::string title;  // e.g. "Moon, Neukum et al. (2001)"
  std::string body;   // e.g. "Moon"
  std::string citation;
  std::vector<double> production;      // a0 .. an
  double min_diameter = 0.0;           // m, range of the polynomial
  double max_diameter = 0.0;           // m
  std::array<double, 4> chronology{};  // c0, c1 (1/Gyr), c2, c3 of N(1)(t), t in Gyr, per km^2
};

// Throws InputError naming the key unless the polynomial has 2 to 12 coefficients, the range is
// 0 < D_min < D_max and N(1) increases from 0 (c0, c3 >= 0, c1 >= 0, c2 >= 0, not all zero).
void validate(const ChronologySystem& system);

// N(1)(t) per km^2 after t years.
double n1(const ChronologySystem& system, double age_years);
// N(>=D, t) per km^2, D in m; InputError outside the polynomial's range.
double cumulative_density(const ChronologySystem& system, double diameter, double age_years);
// The present-day production rate r(D) (per m^2 per year; D in m, InputError outside the range) and the
// clock, for fit_model_age (AgeFitOptions::clock).
ProductionFunction chronology_production(const ChronologySystem& system);
std::function<double(double)> chronology_clock(const ChronologySystem& system);

// Shipped systems: data/chronology/<name>.toml. A file:
//   name, title, body, citation (strings)
//   [production]  coefficients = [a0, ..., an], min_diameter_km, max_diameter_km
//   [chronology]  coefficients = [c0, c1, c2, c3]
std::vector<std::string> chronology_system_names();
ChronologySystem load_chronology_system(const std::string& name_or_path);
ChronologySystem load_chronology_system_file(const std::filesystem::path& path);

}  // namespace craterkit::chronology
