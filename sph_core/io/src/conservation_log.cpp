#include "craterkit/sph/io/conservation_log.hpp"

#include <cstdio>

namespace craterkit::sph {

namespace {

constexpr std::size_t step_column = 1;

std::string format_row(const ConservedQuantities& q) {
  char row[512];
  std::snprintf(row, sizeof row, "%.17g,%llu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", q.time,
                static_cast<unsigned long long>(q.step), q.mass, q.momentum_x, q.momentum_y, q.momentum_z,
                q.kinetic_energy, q.internal_energy, q.potential_energy, q.total_energy, q.absolute_momentum);
  return row;
}

}  // namespace

const char* ConservationLog::header() {
  return "time,step,mass,momentum_x,momentum_y,momentum_z,kinetic_energy,internal_energy,potential_energy,"
         "total_energy,absolute_momentum";
}

ConservationLog::ConservationLog(const std::filesystem::path& csv) : log_(csv, header(), step_column) {}

ConservationLog::ConservationLog(const std::filesystem::path& csv, std::uint64_t restart_step,
                                 std::optional<std::uint64_t> expected_rows)
    : log_(csv, header(), step_column, static_cast<std::int64_t>(restart_step), expected_rows) {}

void ConservationLog::append(const ConservedQuantities& q) {
  log_.append(format_row(q));
}

}  // namespace craterkit::sph
