#pragma once
// Impactor populations: the size-frequency distribution of the bodies that hit a target
// (docs/physics.md sec. 7). Sizes are impactor RADII a in metres inside the library (data files may state
// diameters in km and are converted when read). Numbers are absolute counts of bodies in the
// population (e.g. the whole main belt), so that with an intrinsic collision probability they give
// impact rates.
//   N(>a)    cumulative number of impactors with radius larger than a
//   n(a)     differential number dN/da = -d N(>a) / da (positive)
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace craterkit::chronology {

// Single power law dN/da ∝ a^q (q < -1), normalised by N(>a_ref) = n_ref: N(>a) = n_ref (a/a_ref)^(q+1).
struct PowerLaw {
  double slope = -4.0;            // differential slope q
  double reference_radius = 1.0;  // a_ref, m
  double number_larger = 1.0;     // N(>a_ref)
};

// Broken power law: differential slope slopes[i] between break_radii[i-1] and break_radii[i]
// (slopes.size() == break_radii.size() + 1; the first segment extends to a -> 0, the last to infinity
// and needs slope < -1). dN/da is continuous at the breaks. Normalised by N(>a_ref) = n_ref.
struct BrokenPowerLaw {
  std::vector<double> break_radii;  // m, increasing
  std::vector<double> slopes;       // differential slopes q_i
  double reference_radius = 1.0;    // a_ref, m
  double number_larger = 1.0;       // N(>a_ref)
};

// Table of N(>a), interpolated linearly in log a - log N (a piecewise power law). Radii increasing,
// numbers strictly decreasing and positive; outside the table's radius range it is an error, never a
// silent extrapolation.
struct CumulativeTable {
  std::vector<double> radius;             // m
  std::vector<double> cumulative_number;  // N(>a)
};

struct ImpactorPopulation {
  std::string name;
  std::string citation;
  std::string notes;  // what was digitised or approximated
  // True when the shape is an approximation rather than published values: absolute rates and ages
  // computed with it are indicative only (ratios between cohesions depend only on the local slope).
  bool approximate = false;
  std::variant<PowerLaw, BrokenPowerLaw, CumulativeTable> shape;
};

// Throws InputError naming the offending field if the shape is invalid.
void validate(const ImpactorPopulation& population);

double cumulative_number(const ImpactorPopulation& population, double radius);    // N(>a)
double differential_number(const ImpactorPopulation& population, double radius);  // dN/da > 0

// Radius range over which the population is defined ([0, inf) for power laws).
double minimum_radius(const ImpactorPopulation& population);
double maximum_radius(const ImpactorPopulation& population);

// The same shape rescaled so that N(>a0) = n0.
ImpactorPopulation normalised(const ImpactorPopulation& population, double a0, double n0);

// A single power law of differential slope q normalised to N(>1 m) = 1 (enough for relative rates).
ImpactorPopulation power_law_population(double q, double reference_radius = 1.0, double number_larger = 1.0);

// Shipped populations: data/populations/<name>.toml. A population TOML file:
//   name, citation, notes (strings)
//   kind = "power_law" | "broken_power_law" | "table"
//   power_law:        slope, reference_diameter_km, number_larger
//   broken_power_law: slopes = [...], break_diameters_km = [...], reference_diameter_km, number_larger
//   table:            table = "file.csv" (relative to the TOML) with columns diameter_km, cumulative_number
// (diameters are impactor diameters; they become radii a = D/2 in metres).
std::vector<std::string> population_names();
ImpactorPopulation load_population(const std::string& name_or_path);
ImpactorPopulation load_population_file(const std::filesystem::path& path);

}  // namespace craterkit::chronology
