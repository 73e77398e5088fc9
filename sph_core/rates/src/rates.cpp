#include "craterkit/sph/rates/rates.hpp"

#include "craterkit/sph/rates/artificial_stress.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/rates/stress_rates.hpp"
#include "pair_geometry.hpp"
#include "pair_keeping.hpp"
#include "pair_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace craterkit::sph {

void VelocityGradients::resize(std::size_t n) {
  for (auto& component : corrected) component.resize(n);
}

std::string_view viscosity_switch_name(ViscositySwitch s) noexcept {
  return s == ViscositySwitch::morris_monaghan ? "morris_monaghan" : "none";
}

namespace {

using detail::PairCentre;
using detail::PairFrame;

// The pass is an OpenMP loop over the particles i (rates_impl: i's state in, its rates out) around a
// j-loop over i's neighbour list (pair_sums). The j-loop first keeps the entries within the support
// (pair_keeping.hpp), so that the sums do not depend on which superset of the pairs the lists hold, then
// takes the kept pairs four at a time (pair_lanes.hpp): the pressure force, artificial viscosity, continuity
// and energy of every pair (for solids too, whose pressure is in the stress force) and, for solids, the
// corrected stress force, the artificial stress and the velocity-gradient and kernel-moment sums. The
// template switches (kernel, solid, mirror planes, artificial stress) are resolved once per call in
// compute_rates. The j-loop is compiled for AVX2 and for the baseline processor (pair_sums_wide,
// pair_sums_baseline: the same operations, so the same results), the first used where the processor has it
// (RateOptions::wide_lanes).

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

// What the j-loop reads.
struct PairInputs {
  PairFrame frame;
  FluidFields fluid;
  SolidFields stress;
  Viscosity av;
  const std::uint64_t* offsets;
  const std::uint64_t* ends;
  const std::uint32_t* neighbours;
};

// The sums of particle i over its neighbours (rates.hpp), and the number of pairs within the support.
// Each expression is written for four pairs; per lane it is the one-pair expression (the order of every
// product and sum as the equations of rates.hpp are written), and a lane that holds no pair (the last
// group's padding) is left out of every sum by a select, not by a factor (its values may be NaN).
template <class Kernel, bool solid, bool mirrored, bool artificial_stress>
[[gnu::always_inline]] inline std::uint64_t pair_sums(const PairInputs& in, std::size_t i,
                                                      const PairCentre& centre, const FluidParticle& fi,
                                                      const SolidParticle& si, detail::PairScratch& scratch,
                                                      FluidSums& sum, SolidSums& solid_sum) {
  using detail::LaneMask;
  using detail::Lanes;
  constexpr int lanes = detail::lane_count;
  // The pairs within the support, in list order (pair_keeping.hpp); r = 0 has no direction and is left out.
  const std::size_t kept = detail::keep_pairs_within_support<mirrored, detail::PairUse::kernel_gradient>(
      in.frame, centre, in.neighbours, in.offsets[i], in.ends[i], scratch);

  const FluidFields& f = in.fluid;
  const SolidFields& s = in.stress;
  const Viscosity& av = in.av;
  const Lanes zero = {0.0, 0.0, 0.0, 0.0};
  Lanes ax = zero, ay = zero, az = zero, vv_grad = zero, mv_grad = zero, viscous = zero, max_mu = zero;
  Lanes curl_x = zero, curl_y = zero, curl_z = zero, work = zero;
  Lanes G[9] = {zero, zero, zero, zero, zero, zero, zero, zero, zero};
  Lanes M[6] = {zero, zero, zero, zero, zero, zero};
  for (std::size_t k = 0; k < kept; k += lanes) {
    Lanes dx, dy, dz, r2, hsum, vxj, vyj, vzj, mj, cj, rhoj, alphaj = zero, balsaraj = zero, pressurej = zero,
                                                             inv_rhoj, volumej;
    LaneMask valid, flip_x = {0, 0, 0, 0}, flip_y = flip_x, flip_z = flip_x;
    for (int l = 0; l < lanes; ++l) {
      const bool holds = k + l < kept;
      const std::size_t at = holds ? k + l : k;
      const MirrorImage image = mirror_image<mirrored>(scratch.entry[at]);
      const std::size_t j = image.index;
      valid[l] = holds ? -1 : 0;
      dx[l] = scratch.dx[at];
      dy[l] = scratch.dy[at];
      dz[l] = scratch.dz[at];
      r2[l] = scratch.r2[at];
      hsum[l] = scratch.hsum[at];
      vxj[l] = f.vx[j];
      vyj[l] = f.vy[j];
      vzj[l] = f.vz[j];
      mj[l] = f.mass[j];
      cj[l] = f.c[j];
      rhoj[l] = f.rho[j];
      if (av.use_switch) alphaj[l] = f.alpha[j];
      if (av.use_balsara) balsaraj[l] = f.balsara[j];
      if constexpr (!solid) pressurej[l] = f.pressure[j];
      inv_rhoj[l] = f.inv_rho[j];
      volumej[l] = f.volume[j];
      if constexpr (mirrored) detail::set_reflections(l, image, flip_x, flip_y, flip_z);
    }
    // A padding lane (past the last kept pair) repeats a kept pair's values with no mass and no volume:
    // every term summed below has m_j or V_j as a factor, so the lane adds zeros without a select per sum.
    mj = valid ? mj : zero;
    volumej = valid ? volumej : zero;
    // The image's velocity: -v_a across the plane of axis a (mirror_image.hpp).
    if constexpr (mirrored) {
      vxj = flip_x ? -vxj : vxj;
      vyj = flip_y ? -vyj : vyj;
      vzj = flip_z ? -vzj : vzj;
    }

    // Kernel gradient at the mean h (pair_geometry.hpp, kernel_gradient).
    Lanes r, dwdr;
    detail::lane_sqrt(r2, r);
    const Lanes hbar = 0.5 * hsum;
    detail::kernel_derivative<Kernel>(r, hbar, dwdr);
    const Lanes dwdr_over_r = dwdr / r;
    const Lanes gx = dx * dwdr_over_r, gy = dy * dwdr_over_r, gz = dz * dwdr_over_r;
    const Lanes dvx = fi.vx - vxj, dvy = fi.vy - vyj, dvz = fi.vz - vzj;

    // Pressure force, Monaghan & Gingold (1983) viscosity of approaching pairs, continuity and energy.
    const Lanes v_dot_g = dvx * gx + dvy * gy + dvz * gz;
    const Lanes v_dot_x = dvx * dx + dvy * dy + dvz * dz;
    const LaneMask approaching = (v_dot_x < 0.0) & valid;
    const Lanes mu = hbar * v_dot_x / (r2 + av.eps * hbar * hbar);
    const Lanes cbar = 0.5 * (fi.c + cj);
    const Lanes rhobar = 0.5 * (fi.rho + rhoj);
    const Lanes alpha_ij = av.use_switch ? 0.5 * (fi.alpha + alphaj) : zero + av.alpha;
    const Lanes beta_ij = av.use_switch ? av.beta_over_alpha * alpha_ij : zero + av.beta;
    Lanes pi_ij = (-alpha_ij * cbar * mu + beta_ij * mu * mu) / rhobar;
    if (av.use_balsara) pi_ij *= 0.5 * (fi.balsara + balsaraj);
    pi_ij = approaching ? pi_ij : zero;
    const Lanes minus_mu = approaching ? -mu : zero;
    max_mu = max_mu < minus_mu ? minus_mu : max_mu;
    Lanes force = pi_ij;  // the pressure of solids is in their stress force
    if constexpr (!solid) force += fi.pr2 + pressurej * (inv_rhoj * inv_rhoj);  // symmetric in i, j
    ax -= mj * force * gx;
    ay -= mj * force * gy;
    az -= mj * force * gz;
    vv_grad += volumej * v_dot_g;
    if constexpr (!solid) mv_grad += mj * v_dot_g;
    viscous += mj * pi_ij * v_dot_g;
    if constexpr (!solid) {
      if (av.use_balsara) {  // (v_j - v_i) x grad W = grad W x dv (solids take it from G)
        curl_x += volumej * (gy * dvz - gz * dvy);
        curl_y += volumej * (gz * dvx - gx * dvz);
        curl_z += volumej * (gx * dvy - gy * dvx);
      }
    }

    if constexpr (solid) {
      // Corrected stress force m_j (B_i + B_j) grad_i W_ij (with the artificial stress + m_j f_ij^4 (R_i +
      // R_j) grad_i W_ij), its work, and the sums G and M. The image's B and R have their off-diagonals
      // reflected like S: the sign changes when exactly one of the two axes is reflected.
      Lanes bxx, bxy, bxz, byx, byy, byz, bzx, bzy, bzz;
      Lanes rxx = zero, rxy = zero, rxz = zero, ryy = zero, ryz = zero, rzz = zero;
      for (int l = 0; l < lanes; ++l) {
        const std::size_t j = neighbour_index(scratch.entry[k + l < kept ? k + l : k]);
        bxx[l] = s.bxx[j], bxy[l] = s.bxy[j], bxz[l] = s.bxz[j];
        byx[l] = s.byx[j], byy[l] = s.byy[j], byz[l] = s.byz[j];
        bzx[l] = s.bzx[j], bzy[l] = s.bzy[j], bzz[l] = s.bzz[j];
        if constexpr (artificial_stress) {
          rxx[l] = s.rxx[j], rxy[l] = s.rxy[j], rxz[l] = s.rxz[j];
          ryy[l] = s.ryy[j], ryz[l] = s.ryz[j], rzz[l] = s.rzz[j];
        }
      }
      if constexpr (mirrored) {
        const LaneMask flip_xy = flip_x ^ flip_y, flip_xz = flip_x ^ flip_z, flip_yz = flip_y ^ flip_z;
        bxy = flip_xy ? -bxy : bxy;
        byx = flip_xy ? -byx : byx;
        bxz = flip_xz ? -bxz : bxz;
        bzx = flip_xz ? -bzx : bzx;
        byz = flip_yz ? -byz : byz;
        bzy = flip_yz ? -bzy : bzy;
        if constexpr (artificial_stress) {
          rxy = flip_xy ? -rxy : rxy;
          rxz = flip_xz ? -rxz : rxz;
          ryz = flip_yz ? -ryz : ryz;
        }
      }
      Lanes tix = si.bxx * gx + si.bxy * gy + si.bxz * gz;
      Lanes tiy = si.byx * gx + si.byy * gy + si.byz * gz;
      Lanes tiz = si.bzx * gx + si.bzy * gy + si.bzz * gz;
      Lanes tjx = bxx * gx + bxy * gy + bxz * gz;
      Lanes tjy = byx * gx + byy * gy + byz * gz;
      Lanes tjz = bzx * gx + bzy * gy + bzz * gz;
      if constexpr (artificial_stress) {
        // Added to the stress force of each side, and so to its work.
        Lanes ratio;
        detail::kernel_value_at_unit_h<Kernel>(r / hbar, ratio);
        ratio *= s.inverse_kernel_at_spacing;
        const Lanes f2 = ratio * ratio;
        const Lanes f4 = f2 * f2;
        static_assert(artificial_stress_exponent == 4);
        tix += f4 * (si.rxx * gx + si.rxy * gy + si.rxz * gz);
        tiy += f4 * (si.rxy * gx + si.ryy * gy + si.ryz * gz);
        tiz += f4 * (si.rxz * gx + si.ryz * gy + si.rzz * gz);
        tjx += f4 * (rxx * gx + rxy * gy + rxz * gz);
        tjy += f4 * (rxy * gx + ryy * gy + ryz * gz);
        tjz += f4 * (rxz * gx + ryz * gy + rzz * gz);
      }
      ax += mj * (tix + tjx);
      ay += mj * (tiy + tjy);
      az += mj * (tiz + tjz);
      work -= mj * (dvx * tix + dvy * tiy + dvz * tiz);
      // (v_j - v_i) = -dv, grad W = g.
      const Lanes vgx = volumej * gx, vgy = volumej * gy, vgz = volumej * gz;
      G[0] -= dvx * vgx;
      G[1] -= dvx * vgy;
      G[2] -= dvx * vgz;
      G[3] -= dvy * vgx;
      G[4] -= dvy * vgy;
      G[5] -= dvy * vgz;
      G[6] -= dvz * vgx;
      G[7] -= dvz * vgy;
      G[8] -= dvz * vgz;
      M[0] -= dx * vgx;
      M[1] -= dx * vgy;
      M[2] -= dx * vgz;
      M[3] -= dy * vgy;
      M[4] -= dy * vgz;
      M[5] -= dz * vgz;
    }
  }

  sum.ax = detail::lane_sum(ax);
  sum.ay = detail::lane_sum(ay);
  sum.az = detail::lane_sum(az);
  sum.vv_grad = detail::lane_sum(vv_grad);
  sum.mv_grad = detail::lane_sum(mv_grad);
  sum.viscous = detail::lane_sum(viscous);
  sum.max_mu = detail::lane_max(max_mu, 0.0);
  sum.curl_x = detail::lane_sum(curl_x);
  sum.curl_y = detail::lane_sum(curl_y);
  sum.curl_z = detail::lane_sum(curl_z);
  if constexpr (solid) {
    for (int a = 0; a < 9; ++a) solid_sum.G[a] = detail::lane_sum(G[a]);
    for (int a = 0; a < 6; ++a) solid_sum.M[std::size_t(a)] = detail::lane_sum(M[a]);
    solid_sum.work = detail::lane_sum(work);
  }
  return kept;
}

// pair_sums compiled for the baseline processor and for AVX2 (pair_lanes.hpp); never inlined into each
// other or the driver, so that each keeps its own instructions.
template <class Kernel, bool solid, bool mirrored, bool artificial_stress>
[[gnu::noinline]] std::uint64_t pair_sums_baseline(const PairInputs& in, std::size_t i,
                                                   const PairCentre& centre, const FluidParticle& fi,
                                                   const SolidParticle& si, detail::PairScratch& scratch,
                                                   FluidSums& sum, SolidSums& solid_sum) {
  return pair_sums<Kernel, solid, mirrored, artificial_stress>(in, i, centre, fi, si, scratch, sum,
                                                               solid_sum);
}

template <class Kernel, bool solid, bool mirrored, bool artificial_stress>
[[gnu::noinline, CRATERKIT_WIDE_LANES]] std::uint64_t pair_sums_wide(
    const PairInputs& in, std::size_t i, const PairCentre& centre, const FluidParticle& fi,
    const SolidParticle& si, detail::PairScratch& scratch, FluidSums& sum, SolidSums& solid_sum) {
  return pair_sums<Kernel, solid, mirrored, artificial_stress>(in, i, centre, fi, si, scratch, sum,
                                                               solid_sum);
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

  const PairInputs inputs{
      frame, fluid, stress, av, pairs.offsets.data(), pairs.ends_of(), pairs.neighbours.data()};
  const bool wide = options.wide_lanes && detail::processor_has_avx2();
#pragma omp parallel reduction(min : min_signal_time) reduction(+ : interacting)
  {
    detail::PairScratch scratch;
#pragma omp for schedule(dynamic, 128)
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
      count = wide ? pair_sums_wide<Kernel, solid, mirrored, artificial_stress>(
                         inputs, i, centre, fluid_i, solid_i, scratch, sum, solid_sum)
                   : pair_sums_baseline<Kernel, solid, mirrored, artificial_stress>(
                         inputs, i, centre, fluid_i, solid_i, scratch, sum, solid_sum);

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
