#pragma once
// The stages of the main job (`craterkit run`, docs/main_job.md): from a table of engine craters to the
// scaling constants, the SCI cohesion, relative crater-formation rates and model ages per cohesion. Each
// stage returns its results as JSON (written to summary.json) and appends its part of the report (Markdown,
// printed and written to report.md). The simulations themselves are a `craterkit sweep` (study/sweep.hpp).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::cli {

// The cohesions (Pa) at which the fitted law is evaluated: from cohesionless to the strongest of the study.
inline const std::vector<double> kMainJobCohesions{0.0, 0.05, 0.2, 0.5, 1.0, 2.0};

// Each live run against the row of the same run in `shipped` (same configuration, same engine: the radii
// agree exactly when the checkpoints fall on the same steps, and to the late stage's chaotic scatter
// otherwise).
nlohmann::json compare_with_shipped(const scaling::RadiiTable& live, const scaling::RadiiTable& shipped,
                                    std::string& report);

// The Ceres fit of the point-source law (Housen & Holsapple 2011 form, nu = 0.4 fixed: the engine's runs all
// have one density ratio, docs/physics.md section 6; unweighted, see the .cpp) to every row of `table`,
// against the published Ryugu constants (data/scaling/jutzi2022_ryugu.toml).
scaling::FitResult fit_engine_radii(const scaling::RadiiTable& table, nlohmann::json& out,
                                    std::string& report);

// The SCI impact under `law`: crater radius per cohesion, and the cohesion whose crater is the observed
// 7.25 +- 0.8 m (Arakawa et al. 2020).
nlohmann::json sci_cohesion(const scaling::ScalingLaw& law, double target_density, std::string& report);

// Crater-formation rates on Ryugu (main-belt population) per cohesion for 20, 30 and 40 m craters, relative
// to 1 Pa.
nlohmann::json relative_rates(const scaling::ScalingLaw& law, std::string& report);

// Model ages of the shipped real count (Ryugu, N(>=20 m), Hirata et al. 2020) per cohesion.
nlohmann::json model_ages(const scaling::ScalingLaw& law, std::string& report);

}  // namespace craterkit::cli
