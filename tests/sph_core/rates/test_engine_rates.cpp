// Rates: exact pairwise conservation of momentum and energy on a random particle cloud (with and
// without deviatoric stress), first-order consistency of the corrected velocity gradient, the
// continuity equation on a linear velocity field, a uniform state at rest staying at rest, and
// independence of the thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>
#include <string_view>
#include <type_traits>
#include <vector>

#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/rates/rates.hpp"
#include "craterkit/sph/rates/stress_rates.hpp"
#include "craterkit/sph/rates/summation_density.hpp"

using namespace craterkit::sph;

namespace {

struct Cloud {
  Particles p;
  NeighbourLists lists;
  RateWorkspace workspace;
  Box box;
};

// A jittered lattice of n^3 particles with random states, spacing 1.
Cloud random_cloud(int n, unsigned seed, double jitter, bool random_state) {
  Cloud c;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  c.p.resize(static_cast<std::size_t>(n) * n * n);
  std::size_t i = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int d = 0; d < n; ++d, ++i) {
        c.p.id[i] = i;
        c.p.x[i] = a + jitter * u(rng);
        c.p.y[i] = b + jitter * u(rng);
        c.p.z[i] = d + jitter * u(rng);
        c.p.mass[i] = random_state ? 1.0 + 0.3 * u(rng) : 1.0;
        c.p.density[i] = random_state ? 1.0 + 0.2 * u(rng) : 1.0;
        c.p.smoothing_length[i] = random_state ? 1.2 + 0.2 * u(rng) : 1.2;
        c.p.vx[i] = random_state ? u(rng) : 0.0;
        c.p.vy[i] = random_state ? u(rng) : 0.0;
        c.p.vz[i] = random_state ? u(rng) : 0.0;
        c.p.pressure[i] = random_state ? 1.0 + 0.5 * u(rng) : 1.0;
        c.p.sound_speed[i] = random_state ? 1.0 + 0.5 * u(rng) : 1.0;
        c.p.specific_energy[i] = 1.0;
        c.p.viscosity_alpha[i] = random_state ? 0.5 + 0.4 * u(rng) : 1.0;
        c.p.stress_xx[i] = random_state ? 0.3 * u(rng) : 0.0;
        c.p.stress_xy[i] = random_state ? 0.3 * u(rng) : 0.0;
        c.p.stress_xz[i] = random_state ? 0.3 * u(rng) : 0.0;
        c.p.stress_yy[i] = random_state ? 0.3 * u(rng) : 0.0;
        c.p.stress_yz[i] = random_state ? 0.3 * u(rng) : 0.0;
      }
    }
  }
  c.workspace.inverse_density.resize(c.p.size());
  c.workspace.volume.resize(c.p.size());
  for (std::size_t k = 0; k < c.p.size(); ++k) {
    c.workspace.inverse_density[k] = 1.0 / c.p.density[k];
    c.workspace.volume[k] = c.p.mass[k] / c.p.density[k];
  }
  NeighbourSearch search;
  search.build(neighbour_input(c.p), c.box, c.lists);
  return c;
}

// The solid pair pass reads the correction matrices of all particles: computed first, as the engine does.
RateSummary rates(Cloud& c, const RateOptions& options, VelocityGradients* g = nullptr) {
  if (options.solid) {
    compute_correction_matrices(c.p, PairList{c.lists.offsets, c.lists.neighbours}, options, c.workspace,
                                ParticleSelection::all(c.p.size()));
  }
  return compute_rates(c.p, PairList{c.lists.offsets, c.lists.neighbours}, options, c.workspace, g);
}

void expect_conservation(Cloud& c, const RateOptions& options) {
  rates(c, options);
  double px = 0, py = 0, pz = 0, scale = 0, power = 0, power_scale = 0;
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    const double m = c.p.mass[i];
    px += m * c.p.acceleration_x[i];
    py += m * c.p.acceleration_y[i];
    pz += m * c.p.acceleration_z[i];
    scale += m * std::sqrt(c.p.acceleration_x[i] * c.p.acceleration_x[i] +
                           c.p.acceleration_y[i] * c.p.acceleration_y[i] +
                           c.p.acceleration_z[i] * c.p.acceleration_z[i]);
    const double kinetic = m * (c.p.vx[i] * c.p.acceleration_x[i] + c.p.vy[i] * c.p.acceleration_y[i] +
                                c.p.vz[i] * c.p.acceleration_z[i]);
    power += kinetic + m * c.p.energy_rate[i];
    power_scale += std::abs(kinetic) + std::abs(m * c.p.energy_rate[i]);
  }
  ASSERT_GT(scale, 0.0);
  // Round-off of ~1e5 pair terms: relative 1e-13 (an inconsistent pair term would give O(1)).
  EXPECT_LT(std::abs(px) / scale, 1e-13);
  EXPECT_LT(std::abs(py) / scale, 1e-13);
  EXPECT_LT(std::abs(pz) / scale, 1e-13);
  // d/dt (kinetic + internal) = sum m (v.a + du/dt) vanishes pairwise (no gravity).
  EXPECT_LT(std::abs(power) / power_scale, 1e-13);
}

}  // namespace

TEST(Rates, PairwiseConservationOfMomentumAndEnergy) {
  Cloud c = random_cloud(10, 1, 0.3, true);
  RateOptions options;
  expect_conservation(c, options);
  options.kernel = KernelType::wendland_c2;
  options.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  expect_conservation(c, options);
}

TEST(Rates, PairwiseConservationWithDeviatoricStress) {
  Cloud c = random_cloud(10, 2, 0.3, true);
  RateOptions options;
  options.solid = true;
  expect_conservation(c, options);
}

// The artificial stress (artificial_stress.hpp) keeps the pair forces antisymmetric and its work in the
// energy equation: the same cloud in tension (P - 1.5 < 0, so that sigma = S - P I has tensile principal
// stresses), with and without it.
TEST(Rates, PairwiseConservationWithArtificialStress) {
  Cloud c = random_cloud(10, 3, 0.3, true);
  for (double& P : c.p.pressure) P -= 1.5;
  RateOptions options;
  options.solid = true;
  rates(c, options);
  const std::vector<double> ax_without = c.p.acceleration_x;
  options.artificial_stress.epsilon = 0.3;
  expect_conservation(c, options);
  double change = 0.0, size = 0.0;
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    change += std::abs(c.p.acceleration_x[i] - ax_without[i]);
    size += std::abs(ax_without[i]);
  }
  EXPECT_GT(change, 1e-3 * size);  // the term is there
}

// The summed density against a brute-force double loop over all pairs written out here: same kernel at
// the mean h, self term W(0, h_i); the lists' pair selection must not lose or add anything.
TEST(SummationDensity, EqualsTheBruteForceKernelSum) {
  const auto check = [](auto kernel) {
    using Kernel = decltype(kernel);
    Cloud c = random_cloud(9, 7, 0.3, true);
    auto expected = c.p.density;
    const std::size_t n = c.p.size();
    for (std::size_t i = 0; i < n; ++i) {
      double sum = c.p.mass[i] * Kernel::value(0.0, c.p.smoothing_length[i]);
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const double dx = c.p.x[i] - c.p.x[j], dy = c.p.y[i] - c.p.y[j], dz = c.p.z[i] - c.p.z[j];
        const double hbar = 0.5 * (c.p.smoothing_length[i] + c.p.smoothing_length[j]);
        sum += c.p.mass[j] * Kernel::value(std::sqrt(dx * dx + dy * dy + dz * dz), hbar);
      }
      expected[i] = sum;
    }
    compute_summation_density(c.p, PairList{c.lists.offsets, c.lists.neighbours}, Kernel::type,
                              {0.0, 0.0, 0.0});
    for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(c.p.density[i], expected[i], 1e-13 * expected[i]) << i;
  };
  check(CubicSpline{});
  check(WendlandC2{});
}

// Interior of a unit lattice with unit masses: the sum is the lattice kernel sum, 1 within the kernel's
// discretisation error (about 1 % for the cubic spline at h = 1.2 spacings), and equal for all.
TEST(SummationDensity, UniformLatticeGivesTheLatticeDensity) {
  Cloud c = random_cloud(12, 8, 0.0, false);
  compute_summation_density(c.p, PairList{c.lists.offsets, c.lists.neighbours}, KernelType::cubic_spline,
                            {0.0, 0.0, 0.0});
  double reference = 0.0;
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    const bool interior =
        c.p.x[i] > 3 && c.p.x[i] < 8 && c.p.y[i] > 3 && c.p.y[i] < 8 && c.p.z[i] > 3 && c.p.z[i] < 8;
    if (!interior) continue;
    if (reference == 0.0) reference = c.p.density[i];
    EXPECT_NEAR(c.p.density[i], reference, 1e-12);
  }
  EXPECT_NEAR(reference, 1.0, 0.02);
}

TEST(Rates, UniformStateAtRestStaysAtRest) {
  // Interior particles of a perfect lattice at uniform pressure: no acceleration, no compression.
  Cloud c = random_cloud(12, 3, 0.0, false);
  rates(c, RateOptions{});
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    const bool interior =
        c.p.x[i] > 3 && c.p.x[i] < 8 && c.p.y[i] > 3 && c.p.y[i] < 8 && c.p.z[i] > 3 && c.p.z[i] < 8;
    if (!interior) continue;
    EXPECT_NEAR(c.p.acceleration_x[i], 0.0, 1e-12);
    EXPECT_NEAR(c.p.acceleration_z[i], 0.0, 1e-12);
    EXPECT_EQ(c.p.density_rate[i], 0.0);
    EXPECT_EQ(c.p.energy_rate[i], 0.0);
  }
}

TEST(Rates, CorrectedVelocityGradientIsExactForLinearFields) {
  // v = K x: the Randles-Libersky gradient reproduces K exactly (first-order consistency) even on a
  // jittered lattice and at the free surface; the continuity equation gives -rho tr K in the interior of a
  // lattice.
  Cloud c = random_cloud(10, 4, 0.25, false);
  const double K[9] = {0.3, -0.2, 0.1, 0.05, -0.4, 0.25, -0.15, 0.2, 0.6};
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    c.p.vx[i] = K[0] * c.p.x[i] + K[1] * c.p.y[i] + K[2] * c.p.z[i];
    c.p.vy[i] = K[3] * c.p.x[i] + K[4] * c.p.y[i] + K[5] * c.p.z[i];
    c.p.vz[i] = K[6] * c.p.x[i] + K[7] * c.p.y[i] + K[8] * c.p.z[i];
  }
  RateOptions options;
  options.solid = true;
  VelocityGradients g;
  rates(c, options, &g);
  // Exact wherever the correction is not lifted (gradient_correction.hpp): every particle but those at the
  // edges and corners of the block (and a few face particles that the jitter left short of neighbours).
  std::size_t exact = 0;
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    Eigen::Matrix3d L;
    L << c.p.correction_xx[i], c.p.correction_xy[i], c.p.correction_xz[i], c.p.correction_xy[i],
        c.p.correction_yy[i], c.p.correction_yz[i], c.p.correction_xz[i], c.p.correction_yz[i],
        c.p.correction_zz[i];
    const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(L).eigenvalues()(2);
    if (largest > (1.0 - 1e-9) / min_correction_eigenvalue) continue;  // lifted
    ++exact;
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(g.corrected[k][i], K[k], 1e-11) << "particle " << i << " component " << k;
  }
  std::printf("exact (not lifted): %zu of %zu particles\n", exact, c.p.size());
  EXPECT_GT(exact, c.p.size() - 12 * 8 - 8 - 50);  // all but the 104 edge and corner particles and a few
  // Continuity on a perfect lattice: drho/dt = -rho tr K in the interior to the (second-order)
  // discretisation error of the uncorrected SPH divergence.
  Cloud lattice = random_cloud(10, 4, 0.0, false);
  for (std::size_t i = 0; i < lattice.p.size(); ++i) {
    lattice.p.vx[i] = K[0] * lattice.p.x[i] + K[1] * lattice.p.y[i] + K[2] * lattice.p.z[i];
    lattice.p.vy[i] = K[3] * lattice.p.x[i] + K[4] * lattice.p.y[i] + K[5] * lattice.p.z[i];
    lattice.p.vz[i] = K[6] * lattice.p.x[i] + K[7] * lattice.p.y[i] + K[8] * lattice.p.z[i];
  }
  rates(lattice, RateOptions{});
  const double trace = K[0] + K[4] + K[8];
  int interior = 0;
  for (std::size_t i = 0; i < lattice.p.size(); ++i) {
    const auto& q = lattice.p;
    if (q.x[i] > 2.5 && q.x[i] < 6.5 && q.y[i] > 2.5 && q.y[i] < 6.5 && q.z[i] > 2.5 && q.z[i] < 6.5) {
      ++interior;
      EXPECT_NEAR(q.density_rate[i], -q.density[i] * trace, 0.02 * std::abs(trace));
    }
  }
  EXPECT_GT(interior, 0);
}

// The corrected stress divergence (rates.hpp) on an affine (sheared and stretched) lattice, where the
// correction matrix is a full, anisotropic L != I, with a linear stress field sigma(x) = sigma0 + x-gradient:
// deep in the interior (4h from the surface) every particle and its neighbours have the same L, and the
// neighbours come in point-symmetric pairs, so
// sum_j m_j (sigma_i L_i/rho_i^2 + sigma_j L_j/rho_j^2) grad W = (1/rho) div sigma exactly. Checks the
// products sigma L of both halves (sigma L != L sigma here) and the image-free pair loop; the uncorrected
// sum is off by the lattice's kernel moments (printed).
TEST(Rates, CorrectedStressDivergenceIsExactForLinearStressOnAnAffineLattice) {
  const int n = 18;
  // x = A xi: spacings 1.41, 0.66 and 1.02 against h = 1.0, so the kernel sums are far from the lattice's
  // moments and L far from the identity.
  const double A[3][3] = {{1.4, 0.3, 0.0}, {0.0, 0.6, 0.2}, {0.2, 0.0, 1.0}};
  const double volume = 1.4 * (0.6 * 1.0 - 0.2 * 0.0) - 0.3 * (0.0 * 1.0 - 0.2 * 0.2);  // det A
  Cloud c;
  c.p.resize(static_cast<std::size_t>(n) * n * n);
  std::size_t i = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int d = 0; d < n; ++d, ++i) {
        c.p.id[i] = i;
        c.p.x[i] = A[0][0] * a + A[0][1] * b + A[0][2] * d;
        c.p.y[i] = A[1][0] * a + A[1][1] * b + A[1][2] * d;
        c.p.z[i] = A[2][0] * a + A[2][1] * b + A[2][2] * d;
        c.p.density[i] = 2.0;
        c.p.mass[i] = 2.0 * volume;
        c.p.smoothing_length[i] = 1.0;
        c.p.sound_speed[i] = 1.0;
        c.p.viscosity_alpha[i] = 1.0;
      }
    }
  }
  // sigma_ab(x) = sigma0_ab + sum_c D_abc x_c (symmetric in ab); P = -tr(sigma)/3, S = sigma + P I.
  const double sigma0[3][3] = {{-1.0, 0.3, -0.2}, {0.3, -2.0, 0.4}, {-0.2, 0.4, -0.5}};
  double D[3][3][3];
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int a = 0; a < 3; ++a) {
    for (int b = a; b < 3; ++b) {
      for (int k = 0; k < 3; ++k) D[a][b][k] = D[b][a][k] = u(rng);
    }
  }
  for (std::size_t k = 0; k < c.p.size(); ++k) {
    const double x[3] = {c.p.x[k], c.p.y[k], c.p.z[k]};
    double sigma[3][3];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b)
        sigma[a][b] = sigma0[a][b] + D[a][b][0] * x[0] + D[a][b][1] * x[1] + D[a][b][2] * x[2];
    }
    const double P = -(sigma[0][0] + sigma[1][1] + sigma[2][2]) / 3.0;
    c.p.pressure[k] = P;
    c.p.stress_xx[k] = sigma[0][0] + P;
    c.p.stress_yy[k] = sigma[1][1] + P;
    c.p.stress_xy[k] = sigma[0][1];
    c.p.stress_xz[k] = sigma[0][2];
    c.p.stress_yz[k] = sigma[1][2];
  }
  c.workspace.inverse_density.assign(c.p.size(), 0.5);
  c.workspace.volume.assign(c.p.size(), volume);
  NeighbourSearch search;
  search.build(neighbour_input(c.p), c.box, c.lists);
  RateOptions options;
  options.solid = true;
  rates(c, options);
  double expected[3];
  for (int a = 0; a < 3; ++a) expected[a] = (D[a][0][0] + D[a][1][1] + D[a][2][2]) / 2.0;  // div sigma / rho
  int interior = 0;
  double anisotropy = 0.0;
  for (std::size_t k = 0; k < c.p.size(); ++k) {
    const int a = static_cast<int>(k) / (n * n), b = (static_cast<int>(k) / n) % n,
              d = static_cast<int>(k) % n;
    // Neighbours too must have the bulk L: 6 layers > 4h from the surface.
    if (a < 6 || a > n - 7 || b < 6 || b > n - 7 || d < 6 || d > n - 7) continue;
    ++interior;
    anisotropy = std::max(
        anisotropy, std::abs(c.p.correction_xy[k]) + std::abs(c.p.correction_xx[k] - c.p.correction_zz[k]));
    EXPECT_NEAR(c.p.acceleration_x[k], expected[0], 1e-10) << "particle " << k;
    EXPECT_NEAR(c.p.acceleration_y[k], expected[1], 1e-10) << "particle " << k;
    EXPECT_NEAR(c.p.acceleration_z[k], expected[2], 1e-10) << "particle " << k;
  }
  EXPECT_GT(interior, 100);
  std::printf("largest |L_xy| + |L_xx - L_zz| in the interior: %.3f\n", anisotropy);
  EXPECT_GT(anisotropy, 0.05);  // a full L, not a multiple of the identity
}

TEST(Rates, ViscositySwitchDecaysAwayFromShocksAndGrowsInCompression) {
  Cloud c = random_cloud(8, 5, 0.0, false);
  RateOptions options;
  options.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  for (std::size_t i = 0; i < c.p.size(); ++i) c.p.viscosity_alpha[i] = 0.5;
  rates(c, options);  // at rest: pure decay, dalpha/dt = -(alpha - alpha_min) l c / h
  EXPECT_NEAR(c.p.viscosity_alpha_rate[100], -(0.5 - 0.1) * 0.2 * 1.0 / 1.2, 1e-12);
  for (std::size_t i = 0; i < c.p.size(); ++i) {  // uniform compression v = -x
    c.p.vx[i] = -c.p.x[i];
    c.p.vy[i] = -c.p.y[i];
    c.p.vz[i] = -c.p.z[i];
  }
  rates(c, options);
  EXPECT_GT(c.p.viscosity_alpha_rate[200], 0.0);
}

// Balsara (1995) limiter: in simple shear (v_x = y: |curl v| = 1, div v = 0) the factor falls to ~0 and
// with it the viscous heating; in uniform compression (v = -x: div v = -3, curl 0) it is ~1 and the
// heating is that of the plain viscosity. Both for the fluid and the solid pair loop.
TEST(Rates, BalsaraFactorRemovesTheViscosityOfShearAndKeepsThatOfCompression) {
  for (const bool solid : {false, true}) {
    Cloud c = random_cloud(10, 8, 0.0, false);
    RateOptions plain, limited;
    plain.solid = limited.solid = solid;
    limited.viscosity.balsara = true;
    VelocityGradients g;
    const auto interior = [&](std::size_t i) {
      const auto& q = c.p;
      return q.x[i] > 3 && q.x[i] < 6 && q.y[i] > 3 && q.y[i] < 6 && q.z[i] > 3 && q.z[i] < 6;
    };
    for (std::size_t i = 0; i < c.p.size(); ++i) c.p.vx[i] = c.p.y[i];  // shear
    rates(c, plain, &g);
    const auto plain_heating = c.p.energy_rate;
    rates(c, limited, &g);  // first evaluation: the factors of the particles start at 1
    rates(c, limited, &g);  // now with the factors of the shear flow
    int n = 0;
    for (std::size_t i = 0; i < c.p.size(); ++i) {
      if (!interior(i)) continue;
      ++n;
      EXPECT_LT(c.p.balsara[i], 1e-3) << "shear, particle " << i;
      ASSERT_GT(plain_heating[i], 0.0);
      EXPECT_LT(c.p.energy_rate[i], 1e-3 * plain_heating[i]) << "shear, particle " << i;
    }
    EXPECT_GT(n, 0);
    for (std::size_t i = 0; i < c.p.size(); ++i) {  // uniform compression
      c.p.vx[i] = -c.p.x[i];
      c.p.vy[i] = -c.p.y[i];
      c.p.vz[i] = -c.p.z[i];
    }
    rates(c, limited, &g);
    for (std::size_t i = 0; i < c.p.size(); ++i) {
      if (interior(i)) {
        EXPECT_GT(c.p.balsara[i], 0.99) << "compression, particle " << i;
      }
    }
  }
}

TEST(Rates, IndependentOfThreadCount) {
  Cloud one = random_cloud(12, 6, 0.3, true);
  Cloud two = one;
  RateOptions options;
  options.solid = true;
  options.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  options.viscosity.balsara = true;
  omp_set_num_threads(1);
  const auto s1 = rates(one, options);
  omp_set_num_threads(2);
  const auto s2 = rates(two, options);
  EXPECT_EQ(s1.min_signal_time, s2.min_signal_time);
  EXPECT_EQ(s1.interacting_pairs, s2.interacting_pairs);
  // Gather form: each particle's sums run in the same order whatever the thread count.
  EXPECT_EQ(one.p.acceleration_x, two.p.acceleration_x);
  EXPECT_EQ(one.p.energy_rate, two.p.energy_rate);
  EXPECT_EQ(one.p.density_rate, two.p.density_rate);
  EXPECT_EQ(one.p.balsara, two.p.balsara);
}

TEST(Rates, PeriodicLatticeIsTranslationInvariant) {
  // A periodic lattice at uniform pressure: every particle, edge ones included, has zero acceleration.
  Cloud c = random_cloud(8, 7, 0.0, false);
  c.box.lower = {-0.5, -0.5, -0.5};
  c.box.upper = {7.5, 7.5, 7.5};
  c.box.periodic = {true, true, true};
  NeighbourSearch search;
  search.build(neighbour_input(c.p), c.box, c.lists);
  RateOptions options;
  options.period = {8.0, 8.0, 8.0};
  rates(c, options);
  for (std::size_t i = 0; i < c.p.size(); ++i) {
    EXPECT_NEAR(c.p.acceleration_x[i], 0.0, 1e-12);
    EXPECT_NEAR(c.p.acceleration_y[i], 0.0, 1e-12);
  }
  EXPECT_NEAR(static_cast<double>(c.lists.total()) / c.p.size(), 4.0 / 3.0 * 3.14159265 * std::pow(2.4, 3),
              8.0);
}

// The solver takes the stress rates from the pair pass (compute_rates_and_stress_rates) and holds no velocity
// gradient: every rate must be the same bits as the pass that stores the gradient followed by
// compute_stress_rates, for all particles and for a selection (block time steps), fixed particles included.
TEST(Rates, StressRatesFromThePairPassEqualThoseFromTheStoredGradient) {
  Cloud stored = random_cloud(9, 11, 0.3, true);
  for (std::size_t i = 0; i < stored.p.size(); i += 17) stored.p.flags[i] = particle_fixed;
  std::vector<double> shear_modulus(stored.p.size());
  for (std::size_t i = 0; i < shear_modulus.size(); ++i)
    shear_modulus[i] = i % 23 == 5 ? 0.0 : 2.0 + 0.001 * double(i);
  // Every other particle counts the plastic strain (store_stress_rate's other branch).
  Material total = load_material("boulder");
  std::get<LundborgStrength>(*total.strength).weakening_strain = WeakeningStrain::total;
  Material plastic = total;
  std::get<LundborgStrength>(*plastic.strength).weakening_strain = WeakeningStrain::plastic;
  const std::vector<Material> materials{total, plastic};
  for (std::size_t i = 0; i < stored.p.size(); ++i) stored.p.material[i] = static_cast<std::uint16_t>(i % 2);
  RateOptions options;
  options.solid = true;
  options.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  options.viscosity.balsara = true;
  std::vector<std::uint32_t> listed;
  for (std::uint32_t i = 0; i < stored.p.size(); i += 3) listed.push_back(i);
  for (const ParticleSelection& selection :
       {ParticleSelection::all(stored.p.size()), ParticleSelection::listed(listed)}) {
    Cloud fused = stored;
    const PairList stored_pairs{stored.lists.offsets, stored.lists.neighbours};
    const PairList fused_pairs{fused.lists.offsets, fused.lists.neighbours};
    VelocityGradients g;
    const RateSummary a = compute_rates(stored.p, stored_pairs, options, stored.workspace, selection, &g);
    compute_stress_rates(stored.p, materials, g, shear_modulus, selection);
    const RateSummary b = compute_rates_and_stress_rates(fused.p, fused_pairs, options, fused.workspace,
                                                         selection, shear_modulus, materials);
    EXPECT_EQ(a.min_signal_time, b.min_signal_time);
    EXPECT_EQ(a.interacting_pairs, b.interacting_pairs);
    std::size_t compared = 0;
    stored.p.for_each_field([&](std::string_view name, const auto& field) {
      fused.p.for_each_field([&](std::string_view other, const auto& other_field) {
        if (name != other) return;
        ASSERT_EQ(field.size(), other_field.size()) << name;
        for (std::size_t i = 0; i < field.size(); ++i) {
          if constexpr (std::is_same_v<std::decay_t<decltype(field)>, std::decay_t<decltype(other_field)>>) {
            ASSERT_EQ(std::memcmp(&field[i], &other_field[i], sizeof(field[i])), 0)
                << name << " of particle " << i;
          }
        }
        ++compared;
      });
    });
    EXPECT_GT(compared, 40u);
    EXPECT_NE(stored.p.stress_rate_xx[1], 0.0);  // the stress rates were written
  }
}
