#pragma once
// The slope of a pile's flank from its surface profile, one measurement for the SPH granular tests and the
// DEM piles (docs/validation.md, "Granular flow under gravity" and "DEM piles"): the least-squares line
// z = a + b x through the columns from the highest one outwards whose heights lie between `lower` and `upper`
// times the highest; the angle is atan(-b) in degrees.
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace craterkit {

struct SurfaceProfile {
  std::vector<double> x;       // column centres, m
  std::vector<double> height;  // surface height of the column, m (0: empty)
};

struct FlankFit {
  double angle_degrees = NAN;  // NaN when fewer than 3 columns were fitted
  int columns = 0;             // profile columns in the fit
};

inline FlankFit flank_slope(const SurfaceProfile& profile, double lower, double upper) {
  std::size_t peak = 0;
  for (std::size_t c = 0; c < profile.height.size(); ++c)
    if (profile.height[c] > profile.height[peak]) peak = c;
  const double top = profile.height[peak];
  double sx = 0, sz = 0, sxx = 0, sxz = 0;
  FlankFit fit;
  for (std::size_t c = peak; c < profile.height.size(); ++c) {
    const double z = profile.height[c];
    if (z < lower * top || z > upper * top) continue;
    const double x = profile.x[c];
    sx += x;
    sz += z;
    sxx += x * x;
    sxz += x * z;
    ++fit.columns;
  }
  if (fit.columns < 3) return fit;
  const double n = fit.columns;
  const double b = (n * sxz - sx * sz) / (n * sxx - sx * sx);
  fit.angle_degrees = std::atan(-b) * 180.0 / std::numbers::pi;
  return fit;
}

}  // namespace craterkit
