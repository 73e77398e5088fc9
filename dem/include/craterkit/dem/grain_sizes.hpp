#pragma once
// The grain-size distribution of a bed: diameters uniform between a smallest and a largest. A spread of
// +-10-20 % keeps a bed from crystallising into the ordered packing monodisperse spheres form (docs/dem.md).
#include <random>
#include <string_view>

namespace craterkit::dem {

struct GrainSizes {
  double min_diameter = 0.01;  // m
  double max_diameter = 0.01;  // m

  [[nodiscard]] double mean_diameter() const { return 0.5 * (min_diameter + max_diameter); }
  // The mean of d^3 (a grain's mean volume is pi/6 times it).
  [[nodiscard]] double mean_cubed_diameter() const;
  [[nodiscard]] double draw(std::mt19937_64& random) const;
};

// InputError naming `table`.key for a diameter that is not positive or a min above the max.
void check_grain_sizes(const GrainSizes& sizes, std::string_view table);

}  // namespace craterkit::dem
