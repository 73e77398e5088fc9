#include "craterkit/dem/repose_calibration.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::dem {

ReposeCalibration read_repose_calibration(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the repose calibration", path.string()));
  auto fail = [&](std::size_t line, const std::string& what) {
    return std::runtime_error(fmt::format("{}:{}: {}", path.string(), line, what));
  };
  ReposeCalibration table;
  std::string line;
  std::size_t number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line != "sliding_friction,rolling_friction,angle_degrees")
        throw fail(number,
                   "header '" + line + "', expected 'sliding_friction,rolling_friction,angle_degrees'");
      header = true;
      continue;
    }
    std::istringstream row(line);
    double sliding = 0, rolling = 0, angle = 0;
    char comma1 = 0, comma2 = 0;
    if (!(row >> sliding >> comma1 >> rolling >> comma2 >> angle) || comma1 != ',' || comma2 != ',' ||
        !(row >> std::ws).eof())
      throw fail(number, "row '" + line + "' is not three numbers");
    if (table.rolling_friction.empty()) {
      table.sliding_friction = sliding;
    } else {
      if (sliding != table.sliding_friction)
        throw fail(number, fmt::format("sliding_friction {:g} differs from the first row's {:g}", sliding,
                                       table.sliding_friction));
      if (!(rolling > table.rolling_friction.back()))
        throw fail(number, fmt::format("rolling_friction {:g} does not ascend", rolling));
      if (!(angle > table.angle_degrees.back()))
        throw fail(number,
                   fmt::format("angle_degrees {:g} does not rise above {:g}: the angle has no unique rolling "
                               "friction",
                               angle, table.angle_degrees.back()));
    }
    table.rolling_friction.push_back(rolling);
    table.angle_degrees.push_back(angle);
  }
  if (table.rolling_friction.size() < 2) throw fail(number, "fewer than two rows");
  return table;
}

ReposeCalibration shipped_repose_calibration() {
  return read_repose_calibration(data_file("dem/repose_calibration.csv"));
}

double rolling_friction_for_repose_angle(const ReposeCalibration& table, double angle_degrees) {
  const auto& angles = table.angle_degrees;
  if (!(angle_degrees >= angles.front() && angle_degrees <= angles.back()))
    throw InputError(
        fmt::format("angle of repose {:g} degrees: outside the calibrated piles' [{:g}, {:g}] degrees "
                    "(sliding friction {:g})",
                    angle_degrees, angles.front(), angles.back(), table.sliding_friction));
  std::size_t upper = 1;
  while (angles[upper] < angle_degrees) ++upper;
  const double w = (angle_degrees - angles[upper - 1]) / (angles[upper] - angles[upper - 1]);
  return table.rolling_friction[upper - 1] +
         w * (table.rolling_friction[upper] - table.rolling_friction[upper - 1]);
}

}  // namespace craterkit::dem
