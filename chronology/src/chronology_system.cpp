// Chronology systems of crater-counting tools (chronology_system.hpp).
#include "craterkit/chronology/chronology_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"

namespace craterkit::chronology {
namespace {

constexpr double kYearsPerGyr = 1e9;
constexpr double kSquareMetresPerKm2 = 1e6;
constexpr const char* kTabularForm = "tabular_incremental_root2";

void check_in_range(const ChronologySystem& s, double diameter) {
  if (!(diameter >= s.min_diameter * (1.0 - 1e-12) && diameter <= s.max_diameter * (1.0 + 1e-12))) {
    throw InputError("chronology system " + s.name + ": diameter " + format_number(diameter) +
                     " m is outside its production function's range [" + format_number(s.min_diameter) +
                     ", " + format_number(s.max_diameter) + "] m; choose a fit range inside it");
  }
}

// Polynomial form: P(log10 D) - a0 for D in m.
double polynomial_exponent(const ChronologySystem& s, double diameter) {
  const double x = std::log10(diameter / 1000.0);
  double sum = 0.0;
  for (std::size_t n = s.production.size(); n-- > 1;) sum = (sum + s.production[n]) * x;
  return sum;
}

// Tabular incremental root-2 form, the table's cumulative shape: log10 D_i (D_i = 2^((i - i1)/2) km, the
// bins' lower edges) and log10 (C_i / C_i1), C_i = H_i + ... + H_(n-1), summed from the largest bin down as
// craterstats does (Productionfn, 'tabular incremental root-2').
struct TabularShape {
  std::vector<double> log_edge;        // log10 D_i, D in km
  std::vector<double> log_cumulative;  // log10 (C_i / C_i1)
};

TabularShape tabular_shape(const ChronologySystem& s) {
  const auto& h = s.incremental_density;
  const std::size_t n = h.size();
  TabularShape shape;
  shape.log_edge.resize(n);
  shape.log_cumulative.resize(n);
  double cumulative = 0.0;
  for (std::size_t i = n; i-- > 0;) {
    cumulative += h[i];
    shape.log_cumulative[i] = std::log10(cumulative);
  }
  const double at_1km = shape.log_cumulative[s.index_1km];
  for (std::size_t i = 0; i < n; ++i) {
    shape.log_cumulative[i] -= at_1km;
    const double k = (static_cast<double>(i) - static_cast<double>(s.index_1km)) / 2.0;
    shape.log_edge[i] = std::log10(std::pow(2.0, k));
  }
  return shape;
}

// log10 F(D) for D in m: the piecewise-linear interpolation of log10 C against log10 D between the bin
// edges, the end values held outside them (numpy.interp's rule, which craterstats applies).
double tabular_exponent(const TabularShape& shape, double diameter) {
  const double x = std::log10(diameter / 1000.0);
  const auto& xp = shape.log_edge;
  const auto& fp = shape.log_cumulative;
  if (!(x > xp.front())) return fp.front();
  if (!(x < xp.back())) return fp.back();
  // xp[j] <= x < xp[j + 1]
  const std::size_t j = static_cast<std::size_t>(std::upper_bound(xp.begin(), xp.end(), x) - xp.begin()) - 1;
  const double slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j]);
  return slope * (x - xp[j]) + fp[j];
}

// log10 F(D) = log10 (N(>=D) / N(>=1 km)) for D in m, InputError outside the range.
double shape_exponent(const ChronologySystem& s, double diameter) {
  check_in_range(s, diameter);
  if (s.production_form == ProductionForm::polynomial) return polynomial_exponent(s, diameter);
  return tabular_exponent(tabular_shape(s), diameter);
}

// The same as a function of D alone, with the table's shape computed once.
std::function<double(double)> shape_exponent_function(const ChronologySystem& s) {
  if (s.production_form == ProductionForm::polynomial) {
    return [s](double diameter) {
      check_in_range(s, diameter);
      return polynomial_exponent(s, diameter);
    };
  }
  return [s, shape = tabular_shape(s)](double diameter) {
    check_in_range(s, diameter);
    return tabular_exponent(shape, diameter);
  };
}

// dN(1)/dt at t = 0, per km^2 per Gyr.
double present_rate(const ChronologySystem& s) {
  return s.chronology[0] * s.chronology[1] + s.chronology[3];
}

void validate_polynomial(const ChronologySystem& s, const std::string& where) {
  if (s.production.size() < 2 || s.production.size() > 12) {
    throw InputError(where + "production.coefficients has " + std::to_string(s.production.size()) +
                     " values; allowed: 2 to 12 (a0 ... a11)");
  }
  for (double a : s.production) {
    if (!std::isfinite(a)) throw InputError(where + "production.coefficients must be finite numbers");
  }
  if (!(s.min_diameter > 0.0 && s.max_diameter > s.min_diameter)) {
    throw InputError(where + "the production range [" + format_number(s.min_diameter / 1000.0) + ", " +
                     format_number(s.max_diameter / 1000.0) +
                     "] km must have 0 < min_diameter_km < max_diameter_km");
  }
}

void validate_tabular(const ChronologySystem& s, const std::string& where) {
  const auto& h = s.incremental_density;
  if (h.size() < 2) {
    throw InputError(where + "production.incremental_density has " + std::to_string(h.size()) +
                     " values; allowed: at least 2 (one density per root-2 diameter bin)");
  }
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (!(h[i] > 0.0) || !std::isfinite(h[i])) {
      throw InputError(where + "production.incremental_density[" + std::to_string(i) + "] = " +
                       format_number(h[i]) + "; allowed: finite numbers > 0 (craters per km^2 in the bin)");
    }
  }
  if (s.index_1km >= h.size()) {
    throw InputError(where + "production.index_1km = " + std::to_string(s.index_1km) +
                     " is outside the table; allowed: 0 to " + std::to_string(h.size() - 1) +
                     " (the index of the bin of incremental_density that starts at 1 km)");
  }
  if (!s.production.empty()) {
    throw InputError(where + "a tabular_incremental_root2 production function takes no coefficients");
  }
  const auto [lo, hi] = tabular_root2_range(h.size(), s.index_1km);
  if (!(std::abs(s.min_diameter / lo - 1.0) <= 1e-12 && std::abs(s.max_diameter / hi - 1.0) <= 1e-12)) {
    throw InputError(where + "the production range [" + format_number(s.min_diameter) + ", " +
                     format_number(s.max_diameter) + "] m must be the table's, [" + format_number(lo) + ", " +
                     format_number(hi) + "] m (tabular_root2_range)");
  }
}

}  // namespace

std::string to_string(ProductionForm form) {
  return form == ProductionForm::polynomial ? "polynomial" : kTabularForm;
}

std::pair<double, double> tabular_root2_range(std::size_t bins, std::size_t index_1km) {
  const double i1 = static_cast<double>(index_1km);
  const double last = static_cast<double>(bins) - 1.0;
  return {1000.0 * std::pow(2.0, (0.0 - i1) / 2.0 + 0.25), 1000.0 * std::pow(2.0, (last - i1) / 2.0 + 0.25)};
}

void validate(const ChronologySystem& s) {
  const std::string where = "chronology system " + s.name + ": ";
  if (s.production_form == ProductionForm::polynomial) {
    validate_polynomial(s, where);
  } else {
    validate_tabular(s, where);
  }
  for (double c : s.chronology) {
    if (!(c >= 0.0) || !std::isfinite(c))
      throw InputError(where + "chronology.coefficients must be finite numbers >= 0 (N(1) increases from 0)");
  }
  if (!(present_rate(s) > 0.0)) {
    throw InputError(where + "chronology.coefficients give no cratering today (c0 c1 + c3 = 0)");
  }
}

double n1(const ChronologySystem& s, double age_years) {
  const double t = age_years / kYearsPerGyr;
  const auto& c = s.chronology;
  return c[0] * std::expm1(c[1] * t) + c[2] * t * t + c[3] * t;
}

double cumulative_density(const ChronologySystem& s, double diameter, double age_years) {
  return n1(s, age_years) * std::pow(10.0, shape_exponent(s, diameter));
}

ProductionFunction chronology_production(const ChronologySystem& s) {
  validate(s);
  const double rate = present_rate(s) / kYearsPerGyr / kSquareMetresPerKm2;  // per m^2 per year at 1 km
  return [exponent = shape_exponent_function(s), rate](double diameter) {
    return rate * std::pow(10.0, exponent(diameter));
  };
}

std::function<double(double)> chronology_clock(const ChronologySystem& s) {
  validate(s);
  const double rate = present_rate(s);
  return [s, rate](double age_years) { return n1(s, age_years) / rate * kYearsPerGyr; };
}

std::vector<std::string> chronology_system_names() {
  return data_set_names("chronology");
}

ChronologySystem load_chronology_system(const std::string& name_or_path) {
  return load_chronology_system_file(resolve_data_set(name_or_path, "chronology", "chronology system"));
}

ChronologySystem load_chronology_system_file(const std::filesystem::path& path) {
  TomlTable t = TomlTable::parse_file(path);
  t.reject_unknown({"name", "title", "body", "citation", "production", "chronology", "note"});
  ChronologySystem s;
  s.name = t.text("name", path.stem().string());
  s.title = t.text("title", s.name);
  s.body = t.required_text("body", "the body the system is for (e.g. Moon)");
  s.citation = t.required_text("citation", "the publication of the coefficients");
  t.text("note", "");
  TomlTable production = t.required_table("production");
  const std::string form = production.text("form", "polynomial", {"polynomial", kTabularForm});
  if (form == "polynomial") {
    production.reject_unknown({"form", "coefficients", "min_diameter_km", "max_diameter_km"});
    s.production = production.required_numbers("coefficients");
    s.min_diameter = production.required_number("min_diameter_km", 0.0, 1e6, true) * 1000.0;
    s.max_diameter = production.required_number("max_diameter_km", 0.0, 1e6, true) * 1000.0;
  } else {
    s.production_form = ProductionForm::tabular_incremental_root2;
    production.reject_unknown({"form", "incremental_density", "index_1km"});
    s.incremental_density = production.required_numbers("incremental_density");
    for (std::size_t i = 0; i < s.incremental_density.size(); ++i) {
      if (!(s.incremental_density[i] > 0.0)) {
        production.out_of_range("incremental_density", s.incremental_density[i],
                                "> 0 (element " + std::to_string(i) + "; craters per km^2 in the bin)");
      }
    }
    if (!production.contains("index_1km")) {
      production.fail("index_1km", "missing: the bin (from 0) of incremental_density that starts at 1 km");
    }
    const auto bins = static_cast<std::int64_t>(s.incremental_density.size());
    s.index_1km =
        static_cast<std::size_t>(production.integer("index_1km", 0, 0, std::max<std::int64_t>(bins - 1, 0)));
    std::tie(s.min_diameter, s.max_diameter) = tabular_root2_range(s.incremental_density.size(), s.index_1km);
  }
  production.finish();
  TomlTable chronology = t.required_table("chronology");
  chronology.reject_unknown({"coefficients"});
  const auto c = chronology.required_numbers("coefficients", 4);
  for (std::size_t k = 0; k < 4; ++k) s.chronology[k] = c[k];
  chronology.finish();
  t.finish();
  try {
    validate(s);
  } catch (const InputError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
  return s;
}

}  // namespace craterkit::chronology
