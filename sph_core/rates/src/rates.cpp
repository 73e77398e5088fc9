#include "craterkit/sph/rates/rates.hpp"

#include "craterkit/sph/rates/artificial_stress.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/rates/stress_rates.hpp"
#include "pair_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace craterkit::sph {

void VelocityGradients::resize(std::size_t n) {
  for (auto& component : corrected) component.resize(n);
}

std::string_view viscosity_switch_name(ViscositySwitch s) noexcept {
  return s == ViscositySwitch::morris_monaghan ? "morris_monaghan" : "none";
}

namespace {

using detail::KernelGradient;
using detail::PairCentre;
using detail::PairFrame;
using detail::PairGeometry;

// The pass is an OpenMP loop over the particles i (rates_impl: i's state in, its rates out) around a
// j-loop over i's neighbour list. Per entry the j-loop runs the prologue of pair_geometry.hpp, then
// fluid_pair (pressure force, artificial viscosity, continuity, energy; for solids too, whose pressure is
// in the stress force) and, for solids, solid_pair (the corrected stress force, the artificial stress,
// the velocity-gradient and kernel-moment sums). The template switches (kernel, solid, mirror planes,
// artificial stress) are resolved once per call in compute_rates, and the pair bodies are forced inline:
// each instantiation's j-loop is one loop over the arrays, as written out in one piece.

// Particle fields the fluid pair body reads of j (and the driver of i): structure of arrays over every
// particle, as Particles and RateWorkspace hold them.
struct FluidFields {
  const double* vx;
  const double* vy;
  const double* vz;
  const double* mass;
  const double* rho;
  const double* c;        // sound speed
  const double* alpha;    // viscosity alpha (Morris-Monaghan switch)
  const double* balsara;  // Balsara factors of the last evaluation
  const double* pressure;
  const double* inv_rho;  // 1/rho
  const double* volume;   // m/rho
};

// ArtificialViscosity as the pair body uses it.
struct Viscosity {
  double alpha, beta;      // constant coefficients, or the maxima with the switch
  double beta_over_alpha;  // with the switch, beta_ij = beta alpha_ij / alpha
  double eps;              // eta^2 of mu_ij
  bool use_switch, use_balsara;
};

// Particle i as the fluid pair body reads it.
struct FluidParticle {
  double vx, vy, vz;
  double c, rho;
  double pr2;      // P_i/rho_i^2, rounded as for j
  double alpha;    // alpha_i (alpha without the switch)
  double balsara;  // f_i of the last evaluation
};

[[gnu::always_inline]] inline FluidParticle fluid_particle(const FluidFields& f, const Viscosity& av,
                                                           std::size_t i) {
  const double c = f.c[i], rho = f.rho[i], inv_rho = f.inv_rho[i];
  const double alpha = av.use_switch ? f.alpha[i] : av.alpha;
  return {f.vx[i], f.vy[i], f.vz[i], c, rho, f.pressure[i] * (inv_rho * inv_rho), alpha, f.balsara[i]};
}

// Sums of the fluid pair body over the neighbours of i.
struct FluidSums {
  double ax = 0.0, ay = 0.0, az = 0.0;  // dv_i/dt without gravity; solid_pair adds the stress force
  double vv_grad = 0.0;                 // sum_j (m_j/rho_j) v_ij . grad_i W_ij  (= -div v_i)
  double mv_grad = 0.0;                 // sum_j m_j v_ij . grad_i W_ij
  double viscous = 0.0;                 // sum_j m_j Pi_ij v_ij . grad_i W_ij
  double max_mu = 0.0;                  // max_j |mu_ij| over approaching pairs
  double curl_x = 0.0, curl_y = 0.0, curl_z = 0.0;  // sum_j V_j (v_j - v_i) x grad_i W_ij (Balsara, fluids)
};

// v_ij = v_i - v_j, j's image.
struct RelativeVelocity {
  double x, y, z;
};

[[gnu::always_inline]] inline RelativeVelocity relative_velocity(const FluidParticle& i, const FluidFields& f,
                                                                 const MirrorImage& image) {
  const std::size_t j = image.index;
  return {i.vx - image.vector(0, f.vx[j]), i.vy - image.vector(1, f.vy[j]), i.vz - image.vector(2, f.vz[j])};
}

// Pressure force, artificial viscosity, continuity and energy of one pair (rates.hpp; docs/physics.md section
// 1).
template <bool solid>
[[gnu::always_inline]] inline void fluid_pair(const FluidParticle& i, const FluidFields& f,
                                              const Viscosity& av, const PairGeometry& pair,
                                              const KernelGradient& grad, const RelativeVelocity& dv,
                                              FluidSums& sum) {
  const std::size_t j = pair.j();
  const double gx = grad.x, gy = grad.y, gz = grad.z;
  const double v_dot_g = dv.x * gx + dv.y * gy + dv.z * gz;
  const double v_dot_x = dv.x * pair.dx + dv.y * pair.dy + dv.z * pair.dz;
  const double mj = f.mass[j];

  // Monaghan & Gingold (1983) viscosity, only for approaching pairs.
  double pi_ij = 0.0;
  if (v_dot_x < 0.0) {
    const double hbar = grad.hbar;
    const double mu = hbar * v_dot_x / (pair.r2 + av.eps * hbar * hbar);
    const double cbar = 0.5 * (i.c + f.c[j]);
    const double rhobar = 0.5 * (i.rho + f.rho[j]);
    const double alpha_ij = av.use_switch ? 0.5 * (i.alpha + f.alpha[j]) : av.alpha;
    const double beta_ij = av.use_switch ? av.beta_over_alpha * alpha_ij : av.beta;
    pi_ij = (-alpha_ij * cbar * mu + beta_ij * mu * mu) / rhobar;
    if (av.use_balsara) pi_ij *= 0.5 * (i.balsara + f.balsara[j]);
    sum.max_mu = std::max(sum.max_mu, -mu);
  }

  const double inv_rho2j = f.inv_rho[j] * f.inv_rho[j];
  double force = pi_ij;  // the pressure of solids is in their stress force (solid_pair)
  if constexpr (!solid) force += i.pr2 + f.pressure[j] * inv_rho2j;  // symmetric in i, j
  sum.ax -= mj * force * gx;
  sum.ay -= mj * force * gy;
  sum.az -= mj * force * gz;
  sum.vv_grad += f.volume[j] * v_dot_g;
  if constexpr (!solid) sum.mv_grad += mj * v_dot_g;
  sum.viscous += mj * pi_ij * v_dot_g;
  if constexpr (!solid) {
    if (av.use_balsara) {  // (v_j - v_i) x grad W = grad W x dv (solids take it from G)
      sum.curl_x += f.volume[j] * (gy * dv.z - gz * dv.y);
      sum.curl_y += f.volume[j] * (gz * dv.x - gx * dv.z);
      sum.curl_z += f.volume[j] * (gx * dv.y - gy * dv.x);
    }
  }
}

// Solids: B = sigma L / rho^2 (sigma = S - P I, L the stored correction matrix of gradient_correction.hpp;
// xx, xy, xz, yx, yy, yz, zx, zy, zz) and, with the artificial stress, R (artificial_stress.hpp; xx, xy,
// xz, yy, yz, zz) of every particle, computed before the pair loop (stress_force_pass).
struct SolidFields {
  const double *bxx, *bxy, *bxz, *byx, *byy, *byz, *bzx, *bzy, *bzz;
  const double *rxx, *rxy, *rxz, *ryy, *ryz, *rzz;  // null without the artificial stress
  // 1 / W(dp, 1) (artificial stress): f_ij = W(r_ij, h_ij) / W(dp, h_ij) with dp = h_ij spacing_over_h; W
  // scales as h^-3, so the ratio is that of the kernel at unit h.
  double inverse_kernel_at_spacing;
};

// Particle i as the solid pair body reads it: B_i and R_i (zero without the artificial stress).
struct SolidParticle {
  double bxx, bxy, bxz, byx, byy, byz, bzx, bzy, bzz;
  double rxx = 0.0, rxy = 0.0, rxz = 0.0, ryy = 0.0, ryz = 0.0, rzz = 0.0;
};

template <bool artificial_stress>
[[gnu::always_inline]] inline SolidParticle solid_particle(const SolidFields& s, std::size_t i) {
  SolidParticle particle{s.bxx[i], s.bxy[i], s.bxz[i], s.byx[i], s.byy[i],
                         s.byz[i], s.bzx[i], s.bzy[i], s.bzz[i]};
  if constexpr (artificial_stress) {
    particle.rxx = s.rxx[i], particle.rxy = s.rxy[i], particle.rxz = s.rxz[i];
    particle.ryy = s.ryy[i], particle.ryz = s.ryz[i], particle.rzz = s.rzz[i];
  }
  return particle;
}

// Sums of the solid pair body over the neighbours of i.
struct SolidSums {
  double G[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  // sum V_j (v_j - v_i) (x) grad W, G[3a + b] = dv_a/dx_b
  std::array<double, 6> M{0, 0, 0, 0, 0, 0};  // sum V_j (x_j - x_i) (x) grad W: xx, xy, xz, yy, yz, zz
  double work = 0.0;  // -sum_j m_j v_ij . (B_i grad W): pressure and deviatoric work, matched to the force
};

// Corrected stress force + m_j (B_i + B_j) grad_i W_ij (with the artificial stress + m_j f_ij^4 (R_i + R_j)
// grad_i W_ij), its work, and the sums G and M of one pair (rates.hpp). The image's B and R have their
// off-diagonals reflected like S.
template <class Kernel, bool artificial_stress>
[[gnu::always_inline]] inline void solid_pair(const SolidParticle& i, const SolidFields& s,
                                              const FluidFields& f, const PairGeometry& pair,
                                              const KernelGradient& grad, const RelativeVelocity& dv,
                                              FluidSums& sum, SolidSums& solid) {
  const MirrorImage& image = pair.image;
  const std::size_t j = pair.j();
  const double gx = grad.x, gy = grad.y, gz = grad.z;
  const double dvx = dv.x, dvy = dv.y, dvz = dv.z;
  const double mj = f.mass[j];
  double tix = i.bxx * gx + i.bxy * gy + i.bxz * gz;
  double tiy = i.byx * gx + i.byy * gy + i.byz * gz;
  double tiz = i.bzx * gx + i.bzy * gy + i.bzz * gz;
  double tjx = s.bxx[j] * gx + image.shear(0, 1, s.bxy[j]) * gy + image.shear(0, 2, s.bxz[j]) * gz;
  double tjy = image.shear(0, 1, s.byx[j]) * gx + s.byy[j] * gy + image.shear(1, 2, s.byz[j]) * gz;
  double tjz = image.shear(0, 2, s.bzx[j]) * gx + image.shear(1, 2, s.bzy[j]) * gy + s.bzz[j] * gz;
  if constexpr (artificial_stress) {
    // Added to the stress force of each side, and so to its work.
    const double ratio = Kernel::value(grad.r / grad.hbar, 1.0) * s.inverse_kernel_at_spacing;
    const double f2 = ratio * ratio;
    const double f4 = f2 * f2;
    static_assert(artificial_stress_exponent == 4);
    const double rxy_j = image.shear(0, 1, s.rxy[j]), rxz_j = image.shear(0, 2, s.rxz[j]),
                 ryz_j = image.shear(1, 2, s.ryz[j]);
    tix += f4 * (i.rxx * gx + i.rxy * gy + i.rxz * gz);
    tiy += f4 * (i.rxy * gx + i.ryy * gy + i.ryz * gz);
    tiz += f4 * (i.rxz * gx + i.ryz * gy + i.rzz * gz);
    tjx += f4 * (s.rxx[j] * gx + rxy_j * gy + rxz_j * gz);
    tjy += f4 * (rxy_j * gx + s.ryy[j] * gy + ryz_j * gz);
    tjz += f4 * (rxz_j * gx + ryz_j * gy + s.rzz[j] * gz);
  }
  sum.ax += mj * (tix + tjx);
  sum.ay += mj * (tiy + tjy);
  sum.az += mj * (tiz + tjz);
  solid.work -= mj * (dvx * tix + dvy * tiy + dvz * tiz);
  // (v_j - v_i) = -dv, grad W = g.
  const double vgx = f.volume[j] * gx, vgy = f.volume[j] * gy, vgz = f.volume[j] * gz;
  double* G = solid.G;
  G[0] -= dvx * vgx;
  G[1] -= dvx * vgy;
  G[2] -= dvx * vgz;
  G[3] -= dvy * vgx;
  G[4] -= dvy * vgy;
  G[5] -= dvy * vgz;
  G[6] -= dvz * vgx;
  G[7] -= dvz * vgy;
  G[8] -= dvz * vgz;
  std::array<double, 6>& M = solid.M;
  M[0] -= pair.dx * vgx;
  M[1] -= pair.dx * vgy;
  M[2] -= pair.dx * vgz;
  M[3] -= pair.dy * vgy;
  M[4] -= pair.dy * vgz;
  M[5] -= pair.dz * vgz;
}

// Solids, before the pair loop: B = sigma L / rho^2 of every particle, the half of the corrected stress
// force and of the work term that belongs to one particle of a pair. Once per particle instead of once
// per pair (a pair then reads 9 values of B_j instead of S_j, P_j and L_j and computing sigma_j L_j);
// for the particles whose B the pass reads: the selected ones and their neighbours. With the artificial
// stress also R.
template <class Kernel, bool artificial_stress>
SolidFields stress_force_pass(const Particles& p, const RateOptions& options, RateWorkspace& workspace,
                              const ParticleSelection& neighbourhood) {
  std::array<double*, 6> artificial{};
  if constexpr (artificial_stress) {
    for (int k = 0; k < 6; ++k) {
      workspace.artificial_stress[k].resize(p.size());
      artificial[k] = workspace.artificial_stress[k].data();
    }
  }
  const double* sxx = p.stress_xx.data();
  const double* sxy = p.stress_xy.data();
  const double* sxz = p.stress_xz.data();
  const double* syy = p.stress_yy.data();
  const double* syz = p.stress_yz.data();
  const double* lxx = p.correction_xx.data();
  const double* lxy = p.correction_xy.data();
  const double* lxz = p.correction_xz.data();
  const double* lyy = p.correction_yy.data();
  const double* lyz = p.correction_yz.data();
  const double* lzz = p.correction_zz.data();
  const double* pressure_all = p.pressure.data();
  const double* inv_rho_all = workspace.inverse_density.data();
  std::array<double*, 9> B{};
  for (int k = 0; k < 9; ++k) {
    workspace.stress_force[k].resize(p.size());
    B[k] = workspace.stress_force[k].data();
  }
  const auto count = static_cast<std::int64_t>(neighbourhood.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t kk = 0; kk < count; ++kk) {
    const std::size_t i = neighbourhood.at(static_cast<std::size_t>(kk));
    const double inv_rho2 = inv_rho_all[i] * inv_rho_all[i];
    const double P = pressure_all[i];
    const double s_xx = sxx[i] - P, s_xy = sxy[i], s_xz = sxz[i], s_yy = syy[i] - P, s_yz = syz[i];
    const double s_zz = -(sxx[i] + syy[i]) - P;
    const double l_xx = lxx[i], l_xy = lxy[i], l_xz = lxz[i], l_yy = lyy[i], l_yz = lyz[i], l_zz = lzz[i];
    B[0][i] = (s_xx * l_xx + s_xy * l_xy + s_xz * l_xz) * inv_rho2;
    B[1][i] = (s_xx * l_xy + s_xy * l_yy + s_xz * l_yz) * inv_rho2;
    B[2][i] = (s_xx * l_xz + s_xy * l_yz + s_xz * l_zz) * inv_rho2;
    B[3][i] = (s_xy * l_xx + s_yy * l_xy + s_yz * l_xz) * inv_rho2;
    B[4][i] = (s_xy * l_xy + s_yy * l_yy + s_yz * l_yz) * inv_rho2;
    B[5][i] = (s_xy * l_xz + s_yy * l_yz + s_yz * l_zz) * inv_rho2;
    B[6][i] = (s_xz * l_xx + s_yz * l_xy + s_zz * l_xz) * inv_rho2;
    B[7][i] = (s_xz * l_xy + s_yz * l_yy + s_zz * l_yz) * inv_rho2;
    B[8][i] = (s_xz * l_xz + s_yz * l_yz + s_zz * l_zz) * inv_rho2;
    if constexpr (artificial_stress) {
      const std::array<double, 6> R = artificial_stress_tensor({s_xx, s_xy, s_xz, s_yy, s_yz, s_zz}, inv_rho2,
                                                               options.artificial_stress.epsilon);
      for (int k = 0; k < 6; ++k) artificial[k][i] = R[k];
    }
  }
  const double inverse_kernel_at_spacing =
      artificial_stress ? 1.0 / Kernel::value(options.artificial_stress.spacing_over_h, 1.0) : 0.0;
  return {B[0],          B[1],          B[2],          B[3],
          B[4],          B[5],          B[6],          B[7],
          B[8],          artificial[0], artificial[1], artificial[2],
          artificial[3], artificial[4], artificial[5], inverse_kernel_at_spacing};
}

// Solids, after the j-loop: this evaluation's L_i from M, written over the stored one (the pair loop
// reads the stored L only through B, so no particle sees a neighbour's new L), and the corrected velocity
// gradient G . L_i (Randles & Libersky 1996) for the stress rate, stored in `gradients` or, with
// `stress_inputs`, turned into the stress rates of i at once (store_stress_rate); L_i is the force's in the
// next evaluation (gradient_correction.hpp).
[[gnu::always_inline]] inline void store_correction(Particles& p, std::size_t i, const SolidSums& solid,
                                                    const std::array<double*, 6>& correction,
                                                    VelocityGradients* gradients,
                                                    const StressRateInputs* stress_inputs) {
  const std::array<double, 6> L = correction_matrix(solid.M);
  for (int k = 0; k < 6; ++k) correction[k][i] = L[k];
  if (gradients != nullptr || stress_inputs != nullptr) {
    const double* G = solid.G;
    const double Lm[9] = {L[0], L[1], L[2], L[1], L[3], L[4], L[2], L[4], L[5]};
    Tensor3 corrected{};
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        corrected[a][b] = G[3 * a] * Lm[b] + G[3 * a + 1] * Lm[3 + b] + G[3 * a + 2] * Lm[6 + b];
      }
    }
    if (stress_inputs != nullptr) {
      store_stress_rate(p, i, corrected, stress_inputs->shear_modulus[i],
                        stress_inputs->materials[p.material[i]]);
    } else {
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) gradients->corrected[3 * a + b][i] = corrected[a][b];
      }
    }
  }
}

// artificial_stress: solids with RateOptions::artificial_stress on (a separate instantiation, so that the
// pair loop without it is the one it was: +4.6 % instructions in the solid pass behind a run-time flag).
template <class Kernel, bool solid, bool mirrored, bool artificial_stress = false>
RateSummary rates_impl(Particles& p, const PairList& pairs, const RateOptions& options,
                       RateWorkspace& workspace, VelocityGradients* gradients,
                       const ParticleSelection& selection, const ParticleSelection& neighbourhood,
                       const StressRateInputs* stress_inputs) {
  static_assert(solid || !artificial_stress);
  const auto n = static_cast<std::int64_t>(selection.size());
  const PairFrame frame = detail::pair_frame(p, options.period, options.mirror);
  // The Balsara factors of the last evaluation are read (for i and j); the new ones go to the workspace
  // and replace them after the pass, so that no particle reads a neighbour's value of this pass (the
  // result would depend on the thread schedule).
  p.balsara.resize(p.size(), 1.0);
  if (options.viscosity.balsara) workspace.balsara_next.resize(p.size());
  double* balsara_next = workspace.balsara_next.data();
  const FluidFields fluid{p.vx.data(),
                          p.vy.data(),
                          p.vz.data(),
                          p.mass.data(),
                          p.density.data(),
                          p.sound_speed.data(),
                          p.viscosity_alpha.data(),
                          p.balsara.data(),
                          p.pressure.data(),
                          workspace.inverse_density.data(),
                          workspace.volume.data()};
  workspace.neighbour_count.resize(p.size());
  std::uint32_t* neighbour_count = workspace.neighbour_count.data();
  workspace.signal_time.resize(p.size());
  double* signal_time = workspace.signal_time.data();
  // Solids: B (and R) of every particle; this evaluation's correction matrices are then written over the
  // stored ones as the pass goes (store_correction).
  SolidFields stress{};
  std::array<double*, 6> correction{};
  if constexpr (solid) {
    stress = stress_force_pass<Kernel, artificial_stress>(p, options, workspace, neighbourhood);
    correction = {p.correction_xx.data(), p.correction_xy.data(), p.correction_xz.data(),
                  p.correction_yy.data(), p.correction_yz.data(), p.correction_zz.data()};
  }
  const std::uint8_t* flags = p.flags.data();
  const std::uint64_t* offsets = pairs.offsets.data();
  const std::uint64_t* ends = pairs.ends_of();
  const std::uint32_t* neighbours = pairs.neighbours.data();

  double* ax_out = p.acceleration_x.data();
  double* ay_out = p.acceleration_y.data();
  double* az_out = p.acceleration_z.data();
  double* drho_out = p.density_rate.data();
  double* du_out = p.energy_rate.data();
  double* dalpha_out = p.viscosity_alpha_rate.data();

  const auto& options_av = options.viscosity;
  const Viscosity av{options_av.alpha,
                     options_av.beta,
                     options_av.alpha > 0.0 ? options_av.beta / options_av.alpha : 0.0,
                     options_av.epsilon,
                     options_av.viscosity_switch != ViscositySwitch::none,
                     options_av.balsara};
  const double inf = std::numeric_limits<double>::infinity();
  const double gx_body = options.gravity[0], gy_body = options.gravity[1], gz_body = options.gravity[2];

  double min_signal_time = inf;
  std::uint64_t interacting = 0;

  // firstprivate: each thread reads the frame, the fields and the viscosity parameters from its own copy
  // rather than through the pointer to the shared ones (the j-loops then take 1-2 % fewer instructions).
#pragma omp parallel for schedule(dynamic, 128) reduction(min : min_signal_time) reduction(+ : interacting) \
    firstprivate(frame, fluid, av)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    if ((flags[i] & (particle_fixed | particle_ejected)) != 0) {
      ax_out[i] = ay_out[i] = az_out[i] = 0.0;
      drho_out[i] = du_out[i] = dalpha_out[i] = 0.0;
      neighbour_count[i] = 0;
      signal_time[i] = inf;
      if constexpr (solid) {
        if (stress_inputs != nullptr)  // compute_stress_rates' zeros
          store_stress_rate(p, i, Tensor3{}, 0.0, stress_inputs->materials[p.material[i]]);
      }
      continue;
    }
    const PairCentre centre = detail::pair_centre(frame, i);
    const FluidParticle fluid_i = fluid_particle(fluid, av, i);
    SolidParticle solid_i{};  // (dead code, removed by the compiler, for fluids)
    if constexpr (solid) solid_i = solid_particle<artificial_stress>(stress, i);
    const double hi = centre.h, ci = fluid_i.c, alphai = fluid_i.alpha;

    FluidSums sum;
    SolidSums solid_sum;
    std::uint64_t count = 0;
    for (std::uint64_t k = offsets[i]; k < ends[i]; ++k) {
      const PairGeometry pair = detail::pair_geometry<mirrored>(frame, centre, neighbours[k]);
      if (pair.beyond_support() || pair.coincident()) continue;
      ++count;
      const KernelGradient grad = detail::kernel_gradient<Kernel>(pair);
      const RelativeVelocity dv = relative_velocity(fluid_i, fluid, pair.image);
      fluid_pair<solid>(fluid_i, fluid, av, pair, grad, dv, sum);
      if constexpr (solid) {
        solid_pair<Kernel, artificial_stress>(solid_i, stress, fluid, pair, grad, dv, sum, solid_sum);
      }
    }

    ax_out[i] = sum.ax + gx_body;
    ay_out[i] = sum.ay + gy_body;
    az_out[i] = sum.az + gz_body;
    drho_out[i] = fluid_i.rho * sum.vv_grad;
    if constexpr (solid) {
      du_out[i] = solid_sum.work + 0.5 * sum.viscous;
      store_correction(p, i, solid_sum, correction, gradients, stress_inputs);
    } else {
      du_out[i] = fluid_i.pr2 * sum.mv_grad + 0.5 * sum.viscous;
    }

    if (av.use_balsara) {
      // Balsara (1995) factor |div v| / (|div v| + |curl v| + 1e-4 c/h) for the next evaluation, from the
      // uncorrected (kernel-sum) gradient: G[3a + b] = dv_a/dx_b for solids.
      double curl_x = sum.curl_x, curl_y = sum.curl_y, curl_z = sum.curl_z;
      if constexpr (solid) {
        const double* G = solid_sum.G;
        curl_x = G[7] - G[5];
        curl_y = G[2] - G[6];
        curl_z = G[3] - G[1];
      }
      const double div_v = std::abs(sum.vv_grad);
      const double curl_v = std::sqrt(curl_x * curl_x + curl_y * curl_y + curl_z * curl_z);
      const double denominator = div_v + curl_v + 1e-4 * ci / hi;
      balsara_next[i] = denominator > 0.0 ? div_v / denominator : 1.0;
    }
    if (av.use_switch) {
      // Morris & Monaghan (1997): decay towards alpha_min on tau = h / (l c), growth in compression.
      const double div_v = -sum.vv_grad;
      const double source = std::max(-div_v, 0.0) * (av.alpha - alphai);
      dalpha_out[i] = -(alphai - options_av.alpha_min) * options_av.decay_factor * ci / hi + source;
    } else {
      dalpha_out[i] = 0.0;
    }

    const double beta_i = av.use_switch ? av.beta_over_alpha * alphai : av.beta;
    const double signal = ci + 1.2 * (alphai * ci + beta_i * sum.max_mu);
    signal_time[i] = signal > 0.0 ? hi / signal : inf;
    min_signal_time = std::min(min_signal_time, signal_time[i]);
    interacting += count;
    neighbour_count[i] = static_cast<std::uint32_t>(count);
  }
  if (av.use_balsara) {
    double* factor = p.balsara.data();
#pragma omp parallel for schedule(static)
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = selection.at(static_cast<std::size_t>(ii));
      if ((flags[i] & (particle_fixed | particle_ejected)) == 0) factor[i] = balsara_next[i];
    }
  }
  return RateSummary{min_signal_time, interacting};
}

}  // namespace

RateSummary compute_rates(Particles& particles, const PairList& pairs, const RateOptions& options,
                          RateWorkspace& workspace, VelocityGradients* gradients) {
  return compute_rates(particles, pairs, options, workspace, ParticleSelection::all(particles.size()),
                       gradients);
}

namespace {

RateSummary dispatch_rates(Particles& particles, const PairList& pairs, const RateOptions& options,
                           RateWorkspace& workspace, const ParticleSelection& selection,
                           const ParticleSelection& neighbourhood, VelocityGradients* gradients,
                           const StressRateInputs* stress_inputs) {
  return with_kernel(options.kernel, [&](auto kernel) {
    using K = decltype(kernel);
    const bool artificial = options.solid && options.artificial_stress.on();
    if (options.mirror.any()) {
      if (artificial) {
        return rates_impl<K, true, true, true>(particles, pairs, options, workspace, gradients, selection,
                                               neighbourhood, stress_inputs);
      }
      return options.solid ? rates_impl<K, true, true>(particles, pairs, options, workspace, gradients,
                                                       selection, neighbourhood, stress_inputs)
                           : rates_impl<K, false, true>(particles, pairs, options, workspace, gradients,
                                                        selection, neighbourhood, stress_inputs);
    }
    if (artificial) {
      return rates_impl<K, true, false, true>(particles, pairs, options, workspace, gradients, selection,
                                              neighbourhood, stress_inputs);
    }
    return options.solid ? rates_impl<K, true, false>(particles, pairs, options, workspace, gradients,
                                                      selection, neighbourhood, stress_inputs)
                         : rates_impl<K, false, false>(particles, pairs, options, workspace, gradients,
                                                       selection, neighbourhood, stress_inputs);
  });
}

}  // namespace

RateSummary compute_rates(Particles& particles, const PairList& pairs, const RateOptions& options,
                          RateWorkspace& workspace, const ParticleSelection& selection,
                          VelocityGradients* gradients) {
  if (gradients != nullptr) gradients->resize(particles.size());
  return dispatch_rates(particles, pairs, options, workspace, selection,
                        ParticleSelection::all(particles.size()), gradients, nullptr);
}

RateSummary compute_rates_and_stress_rates(Particles& particles, const PairList& pairs,
                                           const RateOptions& options, RateWorkspace& workspace,
                                           const ParticleSelection& selection,
                                           std::span<const double> shear_modulus,
                                           std::span<const Material> materials,
                                           const ParticleSelection* neighbourhood) {
  if (options.solid && shear_modulus.size() != particles.size()) {
    throw std::invalid_argument("compute_rates_and_stress_rates: " + std::to_string(shear_modulus.size()) +
                                " shear moduli for " + std::to_string(particles.size()) + " particles");
  }
  const StressRateInputs stress{shear_modulus.data(), materials.data()};
  return dispatch_rates(particles, pairs, options, workspace, selection,
                        neighbourhood != nullptr ? *neighbourhood : ParticleSelection::all(particles.size()),
                        nullptr, options.solid ? &stress : nullptr);
}

}  // namespace craterkit::sph
