// Tensile porosity of the late stage (late_stage.hpp, PAlphaPorosity::opens_in_tension; applied by
// update_material_state in stress_rates.hpp): a porous matrix stretched below its reference density opens its
// pores, alpha = rho_m0 / rho, so that its matrix pressure is zero and any compression loads it; without it
// the same particle carries no pressure (and a cohesionless one no strength) until it is compressed back to
// alpha rho = rho_m0.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/particles/particle_selection.hpp"
#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/late_stage.hpp"
#include "craterkit/sph/rates/stress_rates.hpp"

using namespace craterkit::sph;

namespace {

constexpr double kALow = 2.7e4;            // Pa, the SCI example's
constexpr double kMatrixDensity = 2600.0;  // rho_m0 of basalt_matrix_ryugu, kg/m^3
constexpr double kFriction = 0.55;         // its f

Material ryugu_late_stage(bool tensile_porosity, double A_low = kALow) {
  return late_stage_material(load_material("basalt_matrix_ryugu"), A_low, tensile_porosity);
}

// One particle of material 0 at the given bulk density and distention, with a shear stress S_xy.
Particles one_particle(double density, double distention, double stress_xy = 0.0) {
  Particles p;
  p.resize(1);
  p.mass[0] = 1.0;
  p.density[0] = density;
  p.distention[0] = distention;
  p.smoothing_length[0] = 1.0;
  p.stress_xy[0] = stress_xy;
  return p;
}

void update(Particles& p, const std::vector<Material>& materials) {
  RateWorkspace workspace;
  std::vector<double> shear_modulus;
  update_material_state(p, materials, workspace, shear_modulus, ParticleSelection::all(p.size()));
}

}  // namespace

// Loosened to 1000 kg/m^3 at distention 1.6 (alpha rho = 1600 < 2600): with the tensile porosity the particle
// opens to alpha = 2.6 at zero pressure and a compression of 1e-4 gives it P = A_low 1e-4 / alpha and the
// strength f P at once; without it the particle stays at alpha = 1.6 with no pressure and no strength for the
// same compression.
TEST(TensilePorosity, StretchedMatrixOpensItsPoresAndIsLoadedByAnyCompression) {
  const std::vector<Material> opening{ryugu_late_stage(true)};
  Particles p = one_particle(1000.0, 1.6, 1.0);
  update(p, opening);
  EXPECT_EQ(p.distention[0], kMatrixDensity / 1000.0);
  EXPECT_GE(p.pressure[0], 0.0);
  EXPECT_LE(p.pressure[0], 1e-12 * kALow);

  EXPECT_EQ(p.stress_xy[0], 0.0);  // no strength yet
  p.density[0] = 1000.0 * (1.0 + 1e-4);
  p.stress_xy[0] = 1.0;
  update(p, opening);
  EXPECT_EQ(p.distention[0], kMatrixDensity / 1000.0);  // compressed: nothing to open
  const double expected = kALow * 1e-4 / 2.6;
  EXPECT_NEAR(p.pressure[0], expected, 1e-9 * expected);
  const DeviatoricStress s{p.stress_xx[0], p.stress_xy[0], p.stress_xz[0], p.stress_yy[0], p.stress_yz[0]};
  EXPECT_NEAR(std::sqrt(second_invariant(s)), kFriction * p.pressure[0], 1e-9 * expected);

  const std::vector<Material> holding{ryugu_late_stage(false)};
  for (double density : {1000.0, 1000.0 * (1.0 + 1e-4)}) {
    Particles q = one_particle(density, 1.6, 1.0);
    update(q, holding);
    EXPECT_EQ(q.distention[0], 1.6);
    EXPECT_EQ(q.pressure[0], 0.0);
    EXPECT_EQ(q.stress_xy[0], 0.0);  // no strength at P = 0
  }
}

// An opened particle evaluated again at the same density stays as it is, bit for bit: the phase runs again on
// a resumed run's first evaluation, which must continue the uninterrupted run exactly.
TEST(TensilePorosity, OpeningAgainChangesNothing) {
  const std::vector<Material> opening{ryugu_late_stage(true)};
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> density(150.0, 1700.0), distention(1.0, 2.0);
  Particles p;
  p.resize(500);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.mass[i] = 1.0;
    p.smoothing_length[i] = 1.0;
    p.density[i] = density(random);
    p.distention[i] = distention(random);
  }
  update(p, opening);
  std::size_t opened = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    opened += p.distention[i] * p.density[i] >= kMatrixDensity * (1 - 1e-15);
  EXPECT_GT(opened, 100u);
  const Particles first = p;
  update(p, opening);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.distention[i], first.distention[i]) << i;
    EXPECT_EQ(p.pressure[i], first.pressure[i]) << i;
  }
}

// Only the late stage's porous materials with the key open, and only moving particles.
TEST(TensilePorosity, FixedParticlesTheShockStageAndSolidMaterialsAreUntouched) {
  Particles fixed = one_particle(1000.0, 1.6);
  fixed.flags[0] = particle_fixed;
  update(fixed, {ryugu_late_stage(true)});
  EXPECT_EQ(fixed.distention[0], 1.6);

  Particles shock_stage = one_particle(1000.0, 1.6);
  update(shock_stage, {load_material("basalt_matrix_ryugu")});
  EXPECT_EQ(shock_stage.distention[0], 1.6);

  EXPECT_TRUE(ryugu_late_stage(true).porosity->opens_in_tension);
  EXPECT_FALSE(ryugu_late_stage(false).porosity->opens_in_tension);
  EXPECT_NE(ryugu_late_stage(true).description.find("tensile porosity"), std::string::npos);
  const Material projectile = late_stage_material(load_material("aluminium_projectile"), kALow, true);
  EXPECT_FALSE(projectile.porosity.has_value());
  EXPECT_EQ(projectile.description.find("tensile porosity"), std::string::npos);
}

// Above the elastic pressure P_e the crush curve binds as before: an opened particle (alpha = 2.6 > alpha0 =
// 2) loaded to about 2 MPa (a stiff linear law, A_low = 2.7 GPa) is put back on the curve. The curve is flat
// at alpha0 below P_e, so the return (at the same bulk density) ends at alpha0, where this matrix is in
// tension.
TEST(TensilePorosity, TheCrushCurveStillBindsAboveTheElasticPressure) {
  const Material stiff = ryugu_late_stage(true, 2.7e9);
  const double loaded = evaluate_material(stiff, 1002.0, 0.0, 2.6, 0.0).pressure;
  ASSERT_GT(loaded, stiff.porosity->crush_curve.elastic_pressure);
  Particles p = one_particle(1002.0, 2.6);
  update(p, {stiff});
  EXPECT_LT(p.distention[0], 2.6);
  EXPECT_NEAR(p.distention[0], crush_curve_distention(stiff.porosity->crush_curve, p.pressure[0]), 1e-9);
}
