#include "craterkit/chronology/production.hpp"

#include <cmath>
#include <sstream>

#include "craterkit/common/input_error.hpp"
#include "text_table.hpp"

namespace craterkit::chronology {

SpeedDistribution single_speed(double speed) {
  return SpeedDistribution{{speed}, {1.0}};
}

void validate(const SpeedDistribution& speeds) {
  if (speeds.speed.empty() || speeds.speed.size() != speeds.weight.size()) {
    throw InputError("impact-speed distribution needs at least one (speed, weight) pair");
  }
  double total = 0.0;
  for (std::size_t i = 0; i < speeds.speed.size(); ++i) {
    if (!(speeds.speed[i] > 0.0)) {
      std::ostringstream os;
      os << "impact speed " << speeds.speed[i] << " m/s (entry " << i + 1 << ") must be > 0";
      throw InputError(os.str());
    }
    if (!(speeds.weight[i] >= 0.0))
      throw InputError("impact-speed weight (entry " + std::to_string(i + 1) + ") must be >= 0");
    total += speeds.weight[i];
  }
  if (!(total > 0.0)) throw InputError("impact-speed weights sum to zero");
}

SpeedDistribution read_speed_distribution(const std::string& path) {
  const auto lines = detail::read_lines(path);
  SpeedDistribution out;
  int s_col = -1, w_col = -1;
  double unit = 1.0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = detail::trim(lines[i]);
    if (line.empty() || line[0] == '#') continue;
    const auto fields = detail::split_fields(line);
    if (s_col < 0) {
      for (std::size_t c = 0; c < fields.size(); ++c) {
        if (fields[c] == "speed_m_s") s_col = static_cast<int>(c), unit = 1.0;
        if (fields[c] == "speed_km_s") s_col = static_cast<int>(c), unit = 1000.0;
        if (fields[c] == "weight") w_col = static_cast<int>(c);
      }
      if (s_col < 0 || w_col < 0) {
        throw InputError(detail::where(path, i) +
                         ": header must name columns 'speed_m_s' (or 'speed_km_s') and 'weight'");
      }
      continue;
    }
    if (static_cast<int>(fields.size()) <= std::max(s_col, w_col)) {
      throw InputError(detail::where(path, i) + ": expected " + std::to_string(std::max(s_col, w_col) + 1) +
                       " columns, found " + std::to_string(fields.size()));
    }
    const double s = detail::parse_number(fields[static_cast<std::size_t>(s_col)], path, i, "speed") * unit;
    const double w = detail::parse_number(fields[static_cast<std::size_t>(w_col)], path, i, "weight");
    if (!(s > 0.0)) throw InputError(detail::where(path, i) + ": speed must be > 0");
    if (!(w >= 0.0)) throw InputError(detail::where(path, i) + ": weight must be >= 0");
    out.speed.push_back(s);
    out.weight.push_back(w);
  }
  if (out.speed.empty()) throw InputError(path + ": no (speed, weight) rows found");
  validate(out);
  return out;
}

ProductionSetup production_setup_for_body(const Body& body, CollisionRegion region,
                                          ImpactorPopulation population, const SpeedDistribution* speeds) {
  const auto& env = environment(body, region);
  ProductionSetup s;
  s.population = std::move(population);
  s.intrinsic_probability = per_square_metre(env.intrinsic_probability_km2_yr);
  s.target_radius = body.mean_radius;
  s.surface_area = body.surface_area;
  s.speeds = speeds != nullptr ? *speeds : single_speed(env.impact_speed);
  validate(s.speeds);
  return s;
}

double mean_speed(const SpeedDistribution& speeds) {
  validate(speeds);
  double sum = 0.0, weights = 0.0;
  for (std::size_t i = 0; i < speeds.speed.size(); ++i) {
    sum += speeds.weight[i] * speeds.speed[i];
    weights += speeds.weight[i];
  }
  return sum / weights;
}

double impact_rate(const ProductionSetup& setup, double a) {
  const double r = setup.cross_section == CrossSection::target_plus_impactor ? setup.target_radius + a
                                                                             : setup.target_radius;
  return setup.intrinsic_probability * r * r * cumulative_number(setup.population, a);
}

namespace {
double weight_sum(const SpeedDistribution& s) {
  double total = 0.0;
  for (double w : s.weight) total += w;
  return total;
}
}  // namespace

double crater_production_rate(const ProductionSetup& setup, const ImpactorRadiusFunction& impactor_radius,
                              double rim_diameter) {
  if (!(rim_diameter > 0.0)) {
    std::ostringstream os;
    os << "crater diameter " << rim_diameter << " m must be > 0";
    throw InputError(os.str());
  }
  const double R = apparent_radius_from_rim_diameter(rim_diameter, setup.diameter);
  double total = 0.0;
  for (std::size_t k = 0; k < setup.speeds.speed.size(); ++k) {
    if (setup.speeds.weight[k] == 0.0) continue;
    const double a = impactor_radius(R, setup.speeds.speed[k]);
    total += setup.speeds.weight[k] * impact_rate(setup, a);
  }
  return total / weight_sum(setup.speeds) / setup.surface_area;
}

double differential_production_rate(const ProductionSetup& setup,
                                    const ImpactorRadiusFunction& impactor_radius, double rim_diameter,
                                    double step) {
  const double lo = rim_diameter * (1.0 - step);
  const double hi = rim_diameter * (1.0 + step);
  return (crater_production_rate(setup, impactor_radius, lo) -
          crater_production_rate(setup, impactor_radius, hi)) /
         (hi - lo);
}

ProductionFunction production_function(ProductionSetup setup, ImpactorRadiusFunction impactor_radius) {
  validate(setup.population);
  validate(setup.speeds);
  validate(setup.diameter);
  return [setup = std::move(setup), impactor_radius = std::move(impactor_radius)](double d) {
    return crater_production_rate(setup, impactor_radius, d);
  };
}

}  // namespace craterkit::chronology
