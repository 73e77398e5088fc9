#pragma once
// The main job's own stage (`craterkit run`, docs/main_job.md): its live runs against the shipped table. It
// returns its results as JSON (written to report.json) and appends its part of the report (Markdown); the
// rest of the report is `craterkit report`'s (report_builder.hpp), the simulations a `craterkit sweep`.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::cli {

// Each live run against the row of the same run in `shipped` (same configuration, same engine: the radii
// agree exactly when the checkpoints fall on the same steps, and to the late stage's chaotic scatter
// otherwise).
nlohmann::json compare_with_shipped(const scaling::RadiiTable& live, const scaling::RadiiTable& shipped,
                                    std::string& report);

}  // namespace craterkit::cli
