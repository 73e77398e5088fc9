#pragma once
// An impact run: the set-up of impact_setup.hpp with its late-stage plan and ejection rule, run by the
// generic run loop (sph/run/run_simulation.hpp) with two observers of its own: the crater-growth monitor,
// which measures the radius every check interval (crater_growth.csv) and ends the run when growth has
// ended (crater_growth.hpp), and the final crater measurement (crater.json, crater_profile.csv;
// docs/crater_measurement.md).
#include <optional>
#include <string>

#include "craterkit/impact/crater_measurement.hpp"
#include "craterkit/impact/impact_config.hpp"
#include "craterkit/impact/impact_run_record.hpp"
#include "craterkit/impact/impact_setup.hpp"
#include "craterkit/sph/run/run_simulation.hpp"

namespace craterkit::impact {

struct ImpactRun {
  sph::ProblemSetup problem;  // with the late-stage plan and the ejection rule
  ImpactSummary summary;
  ImpactRunRecord record;
};

// The set-up of `config`: the target, projectile and boulders (make_impact), the late-stage switch at
// summary.transition_time with A_low for every material (the density-scaled stand-in's scaled by the same
// k as its other stress-like parameters, docs/impact_setup.md), ejection beyond R_dom or above the escape
// speed, and the run record.
ImpactRun build_impact_run(const ImpactConfig& config);

struct ImpactRunSummary {
  sph::RunSummary run;
  ImpactSummary setup;
  bool crater_growth_ended = false;  // stopped because growth ended (else end_time or max_steps)
  // The first sample of crater_growth.csv at which the end-of-growth rule held (also when the run went on
  // with stop_when_grown = false), and its radius (m, the axis radii of the sample).
  std::optional<double> crater_growth_end_time;    // s
  std::optional<double> crater_growth_end_radius;  // m
  std::optional<CraterMeasurement> crater;         // of the final state
  std::string crater_json;                         // path ("" without an output directory)
};

// Runs the impact (options.log: the set-up summary and the crater on stderr).
ImpactRunSummary run_impact(const ImpactConfig& config, const sph::RunOptions& options);

}  // namespace craterkit::impact
