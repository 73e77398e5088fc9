// dem_repose FOLDER SLIDING_FRICTION DRAG SEED ROLLING_FRICTION...
// Collapses the standard column (column_collapse.hpp: 32 x 16 x 6 grains of 9-11 mm, a = 0.5) once per
// rolling friction, in FOLDER/mu_r-<value>/, with a drag time of DRAG sqrt(H/g) (0: a free collapse), and
// prints a CSV row per pile (sliding_friction,rolling_friction,angle_degrees) on stdout, the details on
// stderr.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

#include "craterkit/dem/column_collapse.hpp"

namespace {

bool parse(const char* text, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  double sliding = 0, drag = 0, seed = 0;
  if (argc < 6 || !parse(argv[2], sliding) || !parse(argv[3], drag) || !parse(argv[4], seed)) {
    std::fprintf(stderr, "usage: dem_repose FOLDER SLIDING_FRICTION DRAG SEED ROLLING_FRICTION...\n");
    return 2;
  }
  std::printf("sliding_friction,rolling_friction,angle_degrees\n");
  for (int k = 5; k < argc; ++k) {
    craterkit::dem::ColumnSpec spec;
    spec.contact.sliding_friction = sliding;
    if (!parse(argv[k], spec.contact.rolling_friction)) {
      std::fprintf(stderr, "dem_repose: rolling friction '%s' is not a number\n", argv[k]);
      return 2;
    }
    spec.drag_time = drag * std::sqrt(spec.height / spec.gravity);
    spec.seed = static_cast<std::uint64_t>(seed);
    try {
      const auto start = std::chrono::steady_clock::now();
      const auto deposit = craterkit::dem::collapse_column(
          spec, std::filesystem::path(argv[1]) / ("mu_r-" + std::string(argv[k])));
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("%g,%g,%.2f\n", sliding, spec.contact.rolling_friction, deposit.flank.angle_degrees);
      std::fflush(stdout);
      std::fprintf(
          stderr,
          "mu_s %g mu_r %g: %zu grains, flank %.2f deg over %d columns, at rest after %.3f s, %.0f s wall\n",
          sliding, spec.contact.rolling_friction, deposit.grains.size(), deposit.flank.angle_degrees,
          deposit.flank.columns, deposit.collapse_time, wall);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "dem_repose: %s\n", e.what());
      return 1;
    }
  }
  return 0;
}
