#include "craterkit/dem/grain_sizes.hpp"

#include <fmt/format.h>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::dem {

double GrainSizes::mean_cubed_diameter() const {
  // (1/(b - a)) integral of d^3 from a to b.
  const double a = min_diameter;
  const double b = max_diameter;
  if (b == a) return a * a * a;
  return (b * b * b * b - a * a * a * a) / (4.0 * (b - a));
}

double GrainSizes::draw(std::mt19937_64& random) const {
  if (max_diameter == min_diameter) return min_diameter;
  return std::uniform_real_distribution<double>(min_diameter, max_diameter)(random);
}

void check_grain_sizes(const GrainSizes& sizes, std::string_view table) {
  require_positive(sizes.min_diameter, fmt::format("{}.min_diameter", table));
  require_positive(sizes.max_diameter, fmt::format("{}.max_diameter", table));
  if (sizes.max_diameter < sizes.min_diameter)
    throw InputError(
        fmt::format("{}.max_diameter: value {:g} is below min_diameter {:g}: allowed >= min_diameter", table,
                    sizes.max_diameter, sizes.min_diameter));
}

}  // namespace craterkit::dem
