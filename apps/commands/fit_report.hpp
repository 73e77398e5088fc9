#pragma once
// Text report of a scaling fit, shared by `craterkit fit` and `craterkit run` (defined in fit.cpp).
#include <cstddef>
#include <string>

#include "craterkit/scaling/fit.hpp"

namespace craterkit::cli {

void print_fit_report(const scaling::FitResult& fit, const std::string& source, std::size_t rows);

}  // namespace craterkit::cli
