#pragma once
// Text reports of scaling fits (defined in fit_report.cpp): one fit, shared by `craterkit fit` and
// `craterkit run`, and the report of `craterkit fit` on a whole table, one section per group with its
// constants, regime counts and flagged rows.
#include <cstddef>
#include <string>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::cli {

void print_fit_report(const scaling::FitResult& fit, const std::string& source, std::size_t rows);

void print_grouped_fit_report(const scaling::GroupedFitResult& result, const scaling::RadiiTable& table);

}  // namespace craterkit::cli
