// The rate of the weakening strain in compute_stress_rates (stress_rates.hpp): the total deviatoric strain
// rate for weakening_strain = "total", the plastic rate of a stress on the yield surface (zero below it)
// for a material that counts the plastic strain, whatever the elastic strain the gradient makes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/particles/particle_selection.hpp"
#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/late_stage.hpp"
#include "craterkit/sph/rates/stress_rates.hpp"

using namespace craterkit::sph;

namespace {

Material boulder_counting(WeakeningStrain weakening) {
  Material m = load_material("boulder");
  std::get<LundborgStrength>(*m.strength).weakening_strain = weakening;
  return m;
}

// A shear gradient that loads the stresses below (S : sym(L) > 0).
Tensor3 loading_gradient() {
  Tensor3 L{};
  L[0][1] = 2e-3;
  L[1][0] = 1e-3;
  L[0][0] = 5e-4;
  L[1][1] = -5e-4;
  return L;
}

struct Case {
  std::uint16_t material;
  double stress_xy;  // Pa; the only stress component
};

// Runs update_material_state and compute_stress_rates on one particle per case at the bulk reference
// density and no internal energy (zero pressure), and returns each particle's total_strain_rate.
std::vector<double> weakening_rates(const std::vector<Material>& materials, const std::vector<Case>& cases,
                                    std::vector<DeviatoricStress>* stresses = nullptr) {
  Particles p;
  p.resize(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    p.material[i] = cases[i].material;
    p.mass[i] = 1.0;
    p.density[i] = 1300.0;
    p.smoothing_length[i] = 1.0;
    p.stress_xy[i] = cases[i].stress_xy;
  }
  RateWorkspace workspace;
  std::vector<double> shear_modulus;
  const auto all = ParticleSelection::all(cases.size());
  update_material_state(p, materials, workspace, shear_modulus, all);
  VelocityGradients gradients;
  gradients.resize(cases.size());
  const Tensor3 L = loading_gradient();
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) gradients.corrected[3 * a + b][i] = L[a][b];
  compute_stress_rates(p, materials, gradients, shear_modulus, all);
  if (stresses) {
    stresses->clear();
    for (std::size_t i = 0; i < cases.size(); ++i)
      stresses->push_back({p.stress_xx[i], p.stress_xy[i], p.stress_xz[i], p.stress_yy[i], p.stress_yz[i]});
  }
  return {p.total_strain_rate.begin(), p.total_strain_rate.end()};
}

}  // namespace

// The boulder after the late-stage switch (G = 23 kPa): below yield the total strain grows with every
// elastic strain the flow makes, the plastic one does not; on the yield surface (cohesion 1e8 Pa at zero
// pressure) both grow, the plastic one by the part the radial return removes.
TEST(StressRates, WeakeningStrainCountsTheTotalOrThePlasticStrain) {
  const double a_low = 2.7e4;
  const std::vector<Material> materials{
      late_stage_material(boulder_counting(WeakeningStrain::total), a_low),
      late_stage_material(boulder_counting(WeakeningStrain::plastic_after_switch), a_low)};
  const Tensor3 L = loading_gradient();
  const double total = deviatoric_strain_rate_invariant(L);
  ASSERT_GT(total, 0.0);
  std::vector<DeviatoricStress> stresses;
  const auto rates = weakening_rates(materials, {{0, 40.0}, {1, 40.0}, {0, 3e8}, {1, 3e8}}, &stresses);
  EXPECT_EQ(rates[0], total);  // elastic, total strain
  EXPECT_EQ(rates[1], 0.0);    // elastic, plastic strain
  EXPECT_EQ(rates[2], total);  // returned onto the surface, total strain
  // Returned onto Y = 1e8 Pa: the plastic rate of that stress, positive and below the total.
  EXPECT_NEAR(std::sqrt(second_invariant(stresses[3])), 1e8, 1e-4);
  EXPECT_EQ(rates[3], plastic_strain_rate_at_yield(stresses[3], L));
  EXPECT_GT(rates[3], 0.0);
  EXPECT_LT(rates[3], total);
}

// In the shock stage "plastic_after_switch" is the published total strain.
TEST(StressRates, PlasticAfterSwitchCountsTheTotalStrainBeforeTheSwitch) {
  const std::vector<Material> materials{boulder_counting(WeakeningStrain::plastic_after_switch),
                                        boulder_counting(WeakeningStrain::plastic)};
  const auto rates = weakening_rates(materials, {{0, 40.0}, {1, 40.0}});
  EXPECT_EQ(rates[0], deviatoric_strain_rate_invariant(loading_gradient()));
  EXPECT_EQ(rates[1], 0.0);
}
