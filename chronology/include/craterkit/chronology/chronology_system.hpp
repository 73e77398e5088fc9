#pragma once
// Published chronology systems in the form crater-counting tools use (craterstats; Neukum et al. 2001;
// Hartmann 2005; Michael 2013): a production function, the shape of the cumulative crater size-frequency
// distribution F(D) = N(>=D) / N(>=1 km), and a chronology function, the density of craters >= 1 km after
// t Gyr,
//   N(1)(t) = c0 (exp(c1 t) - 1) + c2 t^2 + c3 t                (per km^2),
// so that N(>=D, t) = N(1)(t) F(D). The production function comes in one of two forms (ProductionForm):
//
// polynomial (Neukum et al. 2001; Ivanov 2001):
//   log10 N(>=D) = a0 + a1 log10 D + ... + a11 (log10 D)^11   (D in km, N per km^2),
//   valid for D_min <= D <= D_max; F(D) = 10^(P(log10 D) - a0) (a0 only fixes the value at 1 km).
//
// tabular incremental root-2 (Hartmann's isochrons: Hartmann 2005, Icarus 174, 294-320; Hartmann &
// Daubar 2016, Meteoritics & Planetary Science, Martian cratering 11; in the form of craterstats, Michael
// 2013, Icarus 226, 885-890, whose Productionfn is the reference implementation):
//   H_i, i = 0 .. n-1, the density (per km^2) of craters with D_i <= D < sqrt(2) D_i, where
//   D_i = 2^((i - i1)/2) km and i1 = index_1km is the bin that starts at 1 km. The cumulative density at a
//   bin's lower edge is C_i = H_i + H_(i+1) + ... + H_(n-1) (nothing counted above the last bin), and
//   log10 F(D) = interpolation, linear in log10 D, of log10 (C_i / C_i1) between the edges D_i;
//   D < D_0 takes C_0, D > D_(n-1) takes C_(n-1) (the ends held, as numpy's interp and craterstats do).
//   Only the table's shape enters: F(1 km) = 1 whatever density the table was written for. The range of
//   the function is craterstats' one, from the centre of the first bin, 2^(1/4) D_0, to the centre of the
//   last, 2^(1/4) D_(n-1) (above D_(n-1) the held C_(n-1) makes N(>=D) flat).
//
// Shipped in data/chronology/<name>.toml (docs/chronology.md, "Chronology systems").
//
// For the model ages of model_age.hpp a system is written as a present-day production rate and a clock:
//   r(D) = N(1)'(0) F(D)  per km^2 per Gyr (converted to per m^2 per year),
//   clock(t) = N(1)(t) / N(1)'(0)         (years of present-day flux equivalent to t years),
// which gives the same N(>=D, t) and lets the likelihood work with either flux.
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "craterkit/chronology/production.hpp"

namespace craterkit::chronology {

enum class ProductionForm {
  polynomial,                 // `production` holds a0 .. an
  tabular_incremental_root2,  // `incremental_density` and `index_1km` hold Hartmann's table
};
// "polynomial", "tabular_incremental_root2" (the TOML key production.form).
std::string to_string(ProductionForm form);

struct ChronologySystem {
  std::string name;   // file stem, e.g. "moon_neukum2001"
  std::string title;  // e.g. "Moon, Neukum et al. (2001)"
  std::string body;   // e.g. "Moon"
  std::string citation;
  ProductionForm production_form = ProductionForm::polynomial;
  std::vector<double> production;  // polynomial: a0 .. an (empty for the tabular form)
  // Tabular incremental root-2: H_i per km^2 in [D_i, sqrt(2) D_i), D_i = 2^((i - index_1km)/2) km (empty
  // for the polynomial form).
  std::vector<double> incremental_density;
  std::size_t index_1km = 0;
  // m, range of the production function: the polynomial's from its file; for the tabular form the centres
  // of the first and last bins (tabular_root2_range, filled in by the loader).
  double min_diameter = 0.0;
  double max_diameter = 0.0;
  std::array<double, 4> chronology{};  // c0, c1 (1/Gyr), c2, c3 of N(1)(t), t in Gyr, per km^2
};

// The range (m) of a tabular incremental root-2 production function of n bins with index_1km = i1:
// [2^((0 - i1)/2 + 1/4), 2^((n - 1 - i1)/2 + 1/4)] km, the centres of its first and last bins.
std::pair<double, double> tabular_root2_range(std::size_t bins, std::size_t index_1km);

// Throws InputError naming the key unless N(1) increases from 0 (c0, c3 >= 0, c1 >= 0, c2 >= 0, not all
// zero) and the production function is well formed: a polynomial of 2 to 12 finite coefficients with a
// range 0 < D_min < D_max, or a table of at least 2 finite incremental densities > 0 with index_1km inside
// it and the range of tabular_root2_range.
void validate(const ChronologySystem& system);

// N(1)(t) per km^2 after t years.
double n1(const ChronologySystem& system, double age_years);
// N(>=D, t) per km^2, D in m; InputError outside the production function's range.
double cumulative_density(const ChronologySystem& system, double diameter, double age_years);
// The present-day production rate r(D) (per m^2 per year; D in m, InputError outside the range) and the
// clock, for fit_model_age (AgeFitOptions::clock).
ProductionFunction chronology_production(const ChronologySystem& system);
std::function<double(double)> chronology_clock(const ChronologySystem& system);

// Shipped systems: data/chronology/<name>.toml. A file:
//   name, title, body, citation, note (strings; note optional)
//   [production]  form = "polynomial" (the default): coefficients = [a0, ..., an], min_diameter_km,
//                   max_diameter_km
//                 form = "tabular_incremental_root2": incremental_density = [H_0, ..., H_(n-1)] (per km^2),
//                   index_1km = i1 (an integer, the bin that starts at 1 km)
//   [chronology]  coefficients = [c0, c1, c2, c3]
std::vector<std::string> chronology_system_names();
ChronologySystem load_chronology_system(const std::string& name_or_path);
ChronologySystem load_chronology_system_file(const std::filesystem::path& path);

}  // namespace craterkit::chronology
