#include "production_flags.hpp"

#include <cmath>

#include <fmt/format.h>

#include "craterkit/common/input_error.hpp"

namespace craterkit::cli {

namespace ck = craterkit::chronology;

void add_production_flags(CLI::App& command, ProductionFlags& flags) {
  command
      .add_option("--body", flags.body,
                  "Target body: ryugu, bennu or a body .toml file (gives rho, g, U, P_i)")
      ->capture_default_str();
  command.add_option("--region", flags.region, "Collision environment of the body: main_belt or near_earth")
      ->capture_default_str();
  command
      .add_option("--rim-to-apparent", flags.rim_to_apparent,
                  "Rim-to-rim over apparent crater diameter (scaling gives the apparent radius)")
      ->capture_default_str();
  command
      .add_option("--cross-section", flags.cross_section,
                  "Impact cross-section: target+impactor ((R_t+a)^2, Bottke et al. 1994) or target (R_t^2)")
      ->capture_default_str();
  command.add_option(
      "--speed-table", flags.speed_table,
      "CSV of impact speeds (speed_m_s or speed_km_s) and weights to average over, instead of one speed");
}

ck::ProductionSetup resolve_production_flags(const ProductionFlags& flags, const ScalingFlags& scaling,
                                             const ck::Body& body, const ck::ImpactorPopulation& population) {
  const auto region = ck::collision_region_from_string(flags.region);
  if (flags.speed_table && scaling.velocity)
    throw InputError("--velocity and --speed-table cannot both be given");
  if (!(flags.impactor_density > 0.0)) throw InputError("--impactor-density must be > 0 kg/m^3");
  std::optional<ck::SpeedDistribution> speeds;
  if (flags.speed_table) speeds = ck::read_speed_distribution(*flags.speed_table);
  if (scaling.velocity) speeds = ck::single_speed(*scaling.velocity);
  auto setup = ck::production_setup_for_body(body, region, population, speeds ? &*speeds : nullptr);
  setup.diameter.rim_to_apparent = flags.rim_to_apparent;
  ck::validate(setup.diameter, "--rim-to-apparent");
  if (flags.cross_section == "target+impactor") {
    setup.cross_section = ck::CrossSection::target_plus_impactor;
  } else if (flags.cross_section == "target") {
    setup.cross_section = ck::CrossSection::target_only;
  } else {
    throw InputError("--cross-section '" + flags.cross_section +
                     "' is not known; allowed: target+impactor, target");
  }
  return setup;
}

void check_cohesions(const std::vector<double>& cohesions) {
  if (cohesions.empty()) throw InputError("--cohesion needs at least one value (Pa)");
  for (double y : cohesions) {
    if (!(y >= 0.0) || !std::isfinite(y))
      throw InputError(fmt::format("--cohesion {} must be a finite number >= 0 Pa", y));
  }
}

}  // namespace craterkit::cli
