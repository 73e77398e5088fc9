#include "craterkit/sph/neighbours/mirror_reflection.hpp"

#include <array>
#include <vector>

namespace craterkit::sph {

std::size_t reflect_across_mirror_planes(Particles& p, const Box& box) {
  if (!box.any_mirror()) return 0;
  std::size_t reflected = 0;
  const std::array<std::vector<double>*, 3> position{&p.x, &p.y, &p.z};
  const std::array<std::vector<double>*, 3> velocity{&p.vx, &p.vy, &p.vz};
  const std::array<std::vector<double>*, 3> acceleration{&p.acceleration_x, &p.acceleration_y,
                                                         &p.acceleration_z};
  // The deviatoric stress components (and rates, and the correction matrix) with exactly one index along each
  // axis: xy, xz for x; xy, yz for y; xz, yz for z (S_zz = -(S_xx + S_yy) and the diagonal are even).
  const std::array<std::array<std::vector<double>*, 2>, 3> stress{
      {{&p.stress_xy, &p.stress_xz}, {&p.stress_xy, &p.stress_yz}, {&p.stress_xz, &p.stress_yz}}};
  const std::array<std::array<std::vector<double>*, 2>, 3> correction{{{&p.correction_xy, &p.correction_xz},
                                                                       {&p.correction_xy, &p.correction_yz},
                                                                       {&p.correction_xz, &p.correction_yz}}};
  const std::array<std::array<std::vector<double>*, 2>, 3> stress_rate{
      {{&p.stress_rate_xy, &p.stress_rate_xz},
       {&p.stress_rate_xy, &p.stress_rate_yz},
       {&p.stress_rate_xz, &p.stress_rate_yz}}};
  for (int a = 0; a < 3; ++a) {
    if (!box.mirror[a]) continue;
    const double plane = box.lower[a];
    auto& q = *position[a];
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!(q[i] < plane) || (p.flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
      q[i] = 2.0 * plane - q[i];
      (*velocity[a])[i] = -(*velocity[a])[i];
      (*acceleration[a])[i] = -(*acceleration[a])[i];
      if (p.solid_fields) {
        for (auto* s : stress[a]) (*s)[i] = -(*s)[i];
        for (auto* s : stress_rate[a]) (*s)[i] = -(*s)[i];
        for (auto* s : correction[a]) (*s)[i] = -(*s)[i];
      }
      ++reflected;
    }
  }
  return reflected;
}

}  // namespace craterkit::sph
