#pragma once
// The report's scaling constants (report.hpp): the Ceres fit of each group of a radii table as
// `craterkit fit` does it, and what the report draws of them, the engine's craters as pi_R against pi_2
// with the fitted law and the published sand and perlite laws.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::cli {

// A cohesion in Pa in short form for tables and labels ("0.05", "2").
std::string cohesion_text(double cohesion);

// "friction=0.55, porosity=0.5": a group's values with numbers in short form (a sweep writes them with 17
// digits, 0.55000000000000004); "all rows" for an empty key.
std::string key_label(const scaling::GroupKey& key);

// The fit options of the report: the Housen & Holsapple (2011) form with nu = 0.4 held fixed (a sweep's
// runs share one projectile and one target material, so pi_4 does not vary and nu cannot be fitted,
// docs/physics.md section 6), unweighted (see the .cpp), 12 starts as `craterkit fit`.
scaling::FitOptions report_fit_options();

// The fits of one table.
struct TableFits {
  const scaling::RadiiTable* table = nullptr;
  std::optional<scaling::GroupedFitResult> result;  // empty when a fit over every row failed
  std::string not_fitted;                           // why, then
  std::string fit_file;                             // the file its fit JSON goes to ("" without a fit)
  nlohmann::json fit_json;                          // what `craterkit fit --out` writes for the same fit
};

// Fits every group of `table` (`group_by` as `craterkit fit --group-by`: empty for every grouping column,
// an empty list for one fit over every row). Progress on stderr when `progress`.
TableFits fit_table(const scaling::RadiiTable& table, const std::optional<std::vector<std::string>>& group_by,
                    bool progress);

// The rows of a group with distinct pi_2 (impactor size, speed or gravity): a law fitted at one pi_2 does
// not say how craters scale to the impactors of other sizes that rates and ages need.
int distinct_pi2(const scaling::RadiiTable& table, const scaling::GroupFit& group);

// The Markdown section of the fits (one table of constants per radii table) and its JSON (per group: the
// key, the rows, the fit's constants and statistics, or why it was not fitted).
std::string fits_markdown(const std::vector<TableFits>& fits);
nlohmann::json group_fit_json(const TableFits& fits, const scaling::GroupFit& group);

// The published laws the report compares with, as JSON: set, citation, form, constants, not_given.
nlohmann::json published_laws_json();

// The curves of the figure of scaled crater radius against pi_2 for one group: its rows as points, the
// fitted law at each cohesion of the group (along pi_2, at that cohesion's first row's pi_3 and pi_4), and
// the published sand law (gravity regime, Y = 0) and perlite law (strength regime, one level per cohesion
// > 0), which give only those regimes.
nlohmann::json scaled_radius_curves(const scaling::RadiiTable& table, const scaling::GroupFit& group);

}  // namespace craterkit::cli
