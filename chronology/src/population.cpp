#include "craterkit/chronology/population.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"
#include "text_table.hpp"

namespace craterkit::chronology {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Integral of c x^q from lo to hi (hi may be infinite when q < -1).
double power_integral(double c, double q, double lo, double hi) {
  if (q == -1.0) return c * std::log(hi / lo);
  if (std::isinf(hi)) return -c * std::pow(lo, q + 1.0) / (q + 1.0);
  return c * (std::pow(hi, q + 1.0) - std::pow(lo, q + 1.0)) / (q + 1.0);
}

// Unnormalised broken power law: coefficients c_i with c_0 = 1 and dN/da continuous.
std::vector<double> broken_coefficients(const BrokenPowerLaw& b) {
  std::vector<double> c(b.slopes.size(), 1.0);
  for (std::size_t i = 1; i < c.size(); ++i) {
    const double x = b.break_radii[i - 1];
    c[i] = c[i - 1] * std::pow(x, b.slopes[i - 1] - b.slopes[i]);
  }
  return c;
}

std::size_t segment_of(const BrokenPowerLaw& b, double a) {
  return static_cast<std::size_t>(std::upper_bound(b.break_radii.begin(), b.break_radii.end(), a) -
                                  b.break_radii.begin());
}

double broken_unnormalised_cumulative(const BrokenPowerLaw& b, const std::vector<double>& c, double a) {
  std::size_t i = segment_of(b, a);
  double total = 0.0;
  double lo = a;
  for (; i < b.slopes.size(); ++i) {
    const double hi = i < b.break_radii.size() ? b.break_radii[i] : kInf;
    total += power_integral(c[i], b.slopes[i], lo, hi);
    lo = hi;
  }
  return total;
}

double broken_scale(const BrokenPowerLaw& b, const std::vector<double>& c) {
  return b.number_larger / broken_unnormalised_cumulative(b, c, b.reference_radius);
}

// Table segment k with radius[k] <= a <= radius[k+1]; throws outside the table.
std::size_t table_segment(const CumulativeTable& t, double a) {
  if (!(a >= t.radius.front() && a <= t.radius.back())) {
    throw InputError("impactor radius " + format_number(a) +
                     " m is outside the tabulated population range [" + format_number(t.radius.front()) +
                     ", " + format_number(t.radius.back()) + "] m; use a population that covers these sizes");
  }
  auto it = std::upper_bound(t.radius.begin(), t.radius.end(), a);
  std::size_t k = static_cast<std::size_t>(it - t.radius.begin());
  if (k == 0) k = 1;
  if (k >= t.radius.size()) k = t.radius.size() - 1;
  return k - 1;
}

double table_log_slope(const CumulativeTable& t, std::size_t k) {
  return std::log(t.cumulative_number[k + 1] / t.cumulative_number[k]) /
         std::log(t.radius[k + 1] / t.radius[k]);
}

}  // namespace

void validate(const ImpactorPopulation& population) {
  const std::string who = "population '" + population.name + "'";
  if (const auto* p = std::get_if<PowerLaw>(&population.shape)) {
    if (!(p->slope < -1.0))
      throw InputError(who + ": slope = " + format_number(p->slope) + " must be < -1 (finite N(>a))");
    if (!(p->reference_radius > 0.0)) throw InputError(who + ": reference size must be > 0");
    if (!(p->number_larger > 0.0)) throw InputError(who + ": number_larger must be > 0");
  } else if (const auto* b = std::get_if<BrokenPowerLaw>(&population.shape)) {
    if (b->slopes.size() != b->break_radii.size() + 1) {
      throw InputError(who + ": slopes must have one more entry than break diameters (got " +
                       std::to_string(b->slopes.size()) + " slopes, " +
                       std::to_string(b->break_radii.size()) + " breaks)");
    }
    for (std::size_t i = 0; i < b->break_radii.size(); ++i) {
      if (!(b->break_radii[i] > 0.0) || (i > 0 && !(b->break_radii[i] > b->break_radii[i - 1]))) {
        throw InputError(who + ": break diameters must be positive and increasing (entry " +
                         std::to_string(i + 1) + " = " + format_number(2.0 * b->break_radii[i] / 1000.0) +
                         " km)");
      }
    }
    if (!(b->slopes.back() < -1.0)) {
      throw InputError(who + ": the last slope = " + format_number(b->slopes.back()) +
                       " must be < -1 (finite N(>a))");
    }
    if (!(b->reference_radius > 0.0) || !(b->number_larger > 0.0)) {
      throw InputError(who + ": reference size and number_larger must be > 0");
    }
  } else {
    const auto& t = std::get<CumulativeTable>(population.shape);
    if (t.radius.size() < 2 || t.radius.size() != t.cumulative_number.size()) {
      throw InputError(who + ": a table needs at least two rows of (diameter, cumulative number)");
    }
    for (std::size_t i = 0; i < t.radius.size(); ++i) {
      if (!(t.radius[i] > 0.0) || !(t.cumulative_number[i] > 0.0)) {
        throw InputError(who + ": table row " + std::to_string(i + 1) + ": diameter and number must be > 0");
      }
      if (i > 0 &&
          (!(t.radius[i] > t.radius[i - 1]) || !(t.cumulative_number[i] < t.cumulative_number[i - 1]))) {
        throw InputError(who + ": table row " + std::to_string(i + 1) +
                         ": diameters must increase and cumulative numbers strictly decrease");
      }
    }
  }
}

double cumulative_number(const ImpactorPopulation& population, double a) {
  if (!(a > 0.0)) throw InputError("impactor radius " + format_number(a) + " m must be > 0");
  if (const auto* p = std::get_if<PowerLaw>(&population.shape)) {
    return p->number_larger * std::pow(a / p->reference_radius, p->slope + 1.0);
  }
  if (const auto* b = std::get_if<BrokenPowerLaw>(&population.shape)) {
    const auto c = broken_coefficients(*b);
    return broken_scale(*b, c) * broken_unnormalised_cumulative(*b, c, a);
  }
  const auto& t = std::get<CumulativeTable>(population.shape);
  const std::size_t k = table_segment(t, a);
  return t.cumulative_number[k] * std::pow(a / t.radius[k], table_log_slope(t, k));
}

double differential_number(const ImpactorPopulation& population, double a) {
  if (!(a > 0.0)) throw InputError("impactor radius " + format_number(a) + " m must be > 0");
  if (const auto* p = std::get_if<PowerLaw>(&population.shape)) {
    // -d/da [n_ref (a/a_ref)^(q+1)]
    return -(p->slope + 1.0) * p->number_larger * std::pow(a / p->reference_radius, p->slope + 1.0) / a;
  }
  if (const auto* b = std::get_if<BrokenPowerLaw>(&population.shape)) {
    const auto c = broken_coefficients(*b);
    const std::size_t i = segment_of(*b, a);
    return broken_scale(*b, c) * c[i] * std::pow(a, b->slopes[i]);
  }
  const auto& t = std::get<CumulativeTable>(population.shape);
  const std::size_t k = table_segment(t, a);
  const double s = table_log_slope(t, k);
  return -s * t.cumulative_number[k] * std::pow(a / t.radius[k], s) / a;
}

double minimum_radius(const ImpactorPopulation& population) {
  if (const auto* t = std::get_if<CumulativeTable>(&population.shape)) return t->radius.front();
  return 0.0;
}

double maximum_radius(const ImpactorPopulation& population) {
  if (const auto* t = std::get_if<CumulativeTable>(&population.shape)) return t->radius.back();
  return kInf;
}

ImpactorPopulation normalised(const ImpactorPopulation& population, double a0, double n0) {
  if (!(n0 > 0.0)) throw InputError("normalisation N(>a0) = " + format_number(n0) + " must be > 0");
  const double factor = n0 / cumulative_number(population, a0);
  ImpactorPopulation out = population;
  if (auto* p = std::get_if<PowerLaw>(&out.shape)) {
    p->number_larger *= factor;
  } else if (auto* b = std::get_if<BrokenPowerLaw>(&out.shape)) {
    b->number_larger *= factor;
  } else {
    for (auto& n : std::get<CumulativeTable>(out.shape).cumulative_number) n *= factor;
  }
  return out;
}

ImpactorPopulation power_law_population(double q, double reference_radius, double number_larger) {
  ImpactorPopulation p;
  p.name = "power law q = " + format_number(q);
  p.citation = "single power law";
  p.shape = PowerLaw{q, reference_radius, number_larger};
  validate(p);
  return p;
}

// ---------------------------------------------------------------- files

namespace {

CumulativeTable read_cumulative_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  const auto lines = detail::read_lines(file);
  CumulativeTable t;
  int d_col = -1, n_col = -1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = detail::trim(lines[i]);
    if (line.empty() || line[0] == '#') continue;
    const auto fields = detail::split_fields(line);
    if (d_col < 0) {
      for (std::size_t c = 0; c < fields.size(); ++c) {
        if (fields[c] == "diameter_km") d_col = static_cast<int>(c);
        if (fields[c] == "cumulative_number") n_col = static_cast<int>(c);
      }
      if (d_col < 0 || n_col < 0) {
        throw InputError(detail::where(file, i) +
                         ": header must name columns 'diameter_km' and 'cumulative_number'");
      }
      continue;
    }
    if (static_cast<int>(fields.size()) <= std::max(d_col, n_col)) {
      throw InputError(detail::where(file, i) + ": expected at least " +
                       std::to_string(std::max(d_col, n_col) + 1) + " columns, found " +
                       std::to_string(fields.size()));
    }
    const double d_km = detail::parse_number(fields[static_cast<std::size_t>(d_col)], file, i, "diameter_km");
    const double n =
        detail::parse_number(fields[static_cast<std::size_t>(n_col)], file, i, "cumulative_number");
    if (!(d_km > 0.0) || !(n > 0.0)) {
      throw InputError(detail::where(file, i) + ": diameter_km and cumulative_number must be > 0");
    }
    if (!t.radius.empty() && !(d_km * 500.0 > t.radius.back())) {
      throw InputError(detail::where(file, i) + ": diameter_km = " + fields[static_cast<std::size_t>(d_col)] +
                       " must be larger than the previous row's (rows sorted by increasing diameter)");
    }
    if (!t.cumulative_number.empty() && !(n < t.cumulative_number.back())) {
      throw InputError(detail::where(file, i) +
                       ": cumulative_number = " + fields[static_cast<std::size_t>(n_col)] +
                       " must be smaller than the previous row's (N(>D) decreases with D)");
    }
    t.radius.push_back(d_km * 500.0);  // km diameter -> m radius
    t.cumulative_number.push_back(n);
  }
  if (t.radius.size() < 2) throw InputError(file + ": a population table needs at least two data rows");
  return t;
}

// kind = "power_law": slope (< -1, for a finite N(>a)), reference_diameter_km, number_larger.
PowerLaw read_power_law(TomlTable& t) {
  PowerLaw law;
  law.slope = t.required_number("slope", -kInf, -1.0, false, true);
  law.reference_radius = t.required_number("reference_diameter_km", 0.0, kInf, true) * 500.0;  // km D -> m a
  law.number_larger = t.required_number("number_larger", 0.0, kInf, true);
  return law;
}

// kind = "broken_power_law": slopes, break_diameters_km (validate() checks how they fit together),
// reference_diameter_km, number_larger.
BrokenPowerLaw read_broken_power_law(TomlTable& t) {
  BrokenPowerLaw law;
  law.slopes = t.required_numbers("slopes");
  for (double d : t.required_numbers("break_diameters_km")) law.break_radii.push_back(d * 500.0);
  law.reference_radius = t.required_number("reference_diameter_km", 0.0, kInf, true) * 500.0;
  law.number_larger = t.required_number("number_larger", 0.0, kInf, true);
  return law;
}

}  // namespace

std::vector<std::string> population_names() {
  return data_set_names("populations");
}

ImpactorPopulation load_population(const std::string& name_or_path) {
  return load_population_file(resolve_data_set(name_or_path, "populations", "population"));
}

ImpactorPopulation load_population_file(const std::filesystem::path& path) {
  TomlTable t = TomlTable::parse_file(path);
  // Every key of any kind first, so that a misspelt key is named as such; finish() below then rejects
  // the keys of the other kinds.
  t.reject_unknown({"name", "citation", "notes", "approximate", "kind", "slope", "slopes",
                    "break_diameters_km", "reference_diameter_km", "number_larger", "table"});
  ImpactorPopulation p;
  p.name = t.text("name", path.stem().string());
  p.citation = t.text("citation", "");
  p.notes = t.text("notes", "");
  p.approximate = t.boolean("approximate", false);
  const std::string kind =
      t.required_text("kind", "the shape of the population", {"power_law", "broken_power_law", "table"});
  if (kind == "power_law") {
    p.shape = read_power_law(t);
  } else if (kind == "broken_power_law") {
    p.shape = read_broken_power_law(t);
  } else {
    p.shape = read_cumulative_csv(path.parent_path() / t.required_text("table", "a CSV file name"));
  }
  t.finish();
  try {
    validate(p);
  } catch (const InputError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
  return p;
}

}  // namespace craterkit::chronology
