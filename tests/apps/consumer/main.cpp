// A downstream project: finds the installed craterkit with find_package and links its libraries.
#include <cmath>
#include <craterkit/scaling/point_source.hpp>
#include <craterkit/sph/particles/particles.hpp>
#include <cstdio>

int main() {
  using namespace craterkit::scaling;
  const ScalingLaw law{Form::hh2011, 0.6, 0.25, 0.44, 0.4};
  const double radius = crater_radius(law, {0.0561, 2700, 2000}, {1300, 1.4e-4, 0.05});
  craterkit::sph::Particles particles;
  particles.resize(3);
  std::printf("R = %.3f m, %zu particles\n", radius, particles.size());
  return (std::isfinite(radius) && radius > 0.0 && particles.size() == 3) ? 0 : 1;
}
