#pragma once
// Small solid-mechanics problems built directly in test code: an elastic
// material with a linear equation of state, a cohesive-frictional (Lundborg) granular material with the
// linear low-sound-speed law, and a helper that fills a box of lattice sites. Nothing here is engine
// code: the engine sees ordinary ProblemSetup values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/run/standard_problems.hpp"

namespace solid_test {

using namespace craterkit::sph;

// Linear elastic solid: P = K (rho/rho0 - 1) (the linear law of low_sound_speed.hpp with A = K) and
// shear modulus G from Young's modulus E and Poisson's ratio nu; von Mises with a yield strength far
// above any stress of the test, so that the radial return never acts.
inline Material elastic_material(double density, double young_modulus, double poisson_ratio) {
  Material m;
  m.name = "linear_elastic";
  m.eos = LowSoundSpeed{density, young_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio))};
  m.shear_modulus = young_modulus / (2.0 * (1.0 + poisson_ratio));
  m.strength = VonMisesStrength{1e6 * young_modulus};
  return m;
}

// Granular material: Lundborg yield with cohesion Y0 and friction f (limiting strength far above the
// pressures of the test, so Y = Y0 + f P), with the linear low-sound-speed law (bulk modulus A) and a
// shear modulus giving Poisson's ratio nu, as the late-stage medium of docs/physics.md section 3.
inline Material granular_material(double density, double bulk_modulus, double poisson_ratio, double friction,
                                  double cohesion) {
  Material m;
  m.name = "granular";
  m.eos = LowSoundSpeed{density, bulk_modulus};
  m.shear_modulus = 3.0 * bulk_modulus * (1.0 - 2.0 * poisson_ratio) / (2.0 * (1.0 + poisson_ratio));
  m.strength = LundborgStrength{cohesion, friction, 1e6 * bulk_modulus};
  return m;
}

// Appends a particle at rest on a cubic lattice site (spacing dx) with density rho and material 0.
inline std::size_t add_particle(Particles& p, double x, double y, double z, double dx, double rho, double eta,
                                double alpha, bool fixed) {
  const std::size_t k = p.size();
  p.resize(k + 1);
  p.id[k] = k;
  p.x[k] = x;
  p.y[k] = y;
  p.z[k] = z;
  p.mass[k] = rho * dx * dx * dx;
  p.density[k] = rho;
  p.smoothing_length[k] = eta * dx;
  p.viscosity_alpha[k] = alpha;
  if (fixed) p.flags[k] |= particle_fixed;
  return k;
}

}  // namespace solid_test
