#pragma once
// ejecta.csv: one row per ejected particle (solver/ejecta.hpp), 17 significant digits, written by the run
// loop as a step log (step_csv_log.hpp) so that it resumes with the run.
#include <cstddef>
#include <string>

#include "craterkit/sph/solver/ejecta.hpp"

namespace craterkit::sph {

const char* ejecta_csv_header();
std::string ejecta_csv_row(const EjectaRecord& record);
constexpr std::size_t ejecta_csv_step_column = 4;

}  // namespace craterkit::sph
