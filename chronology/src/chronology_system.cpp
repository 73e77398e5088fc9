// Chronology systems of crater-counting tools (chronology_system.hpp).
#include "craterkit/chronology/chronology_system.hpp"

#include <cmath>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"

namespace craterkit::chronology {
namespace {

constexpr double kYearsPerGyr = 1e9;
constexpr double kSquareMetresPerKm2 = 1e6;

// P(log10 D) - a0 for D in m.
double shape_exponent(const ChronologySystem& s, double diameter) {
  if (!(diameter >= s.min_diameter * (1.0 - 1e-12) && diameter <= s.max_diameter * (1.0 + 1e-12))) {
    throw InputError("chronology system " + s.name + ": diameter " + format_number(diameter) +
                     " m is outside its production function's range [" + format_number(s.min_diameter) +
                     ", " + format_number(s.max_diameter) + "] m; choose a fit range inside it");
  }
  const double x = std::log10(diameter / 1000.0);
  double sum = 0.0;
  for (std::size_t n = s.production.size(); n-- > 1;) sum = (sum + s.production[n]) * x;
  return sum;
}

// dN(1)/dt at t = 0, per km^2 per Gyr.
double present_rate(const ChronologySystem& s) {
  return s.chronology[0] * s.chronology[1] + s.chronology[3];
}

}  // namespace

void validate(const ChronologySystem& s) {
  const std::string where = "chronology system " + s.name + ": ";
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
  return [s, rate](double diameter) { return rate * std::pow(10.0, shape_exponent(s, diameter)); };
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
  production.reject_unknown({"coefficients", "min_diameter_km", "max_diameter_km"});
  s.production = production.required_numbers("coefficients");
  s.min_diameter = production.required_number("min_diameter_km", 0.0, 1e6, true) * 1000.0;
  s.max_diameter = production.required_number("max_diameter_km", 0.0, 1e6, true) * 1000.0;
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
