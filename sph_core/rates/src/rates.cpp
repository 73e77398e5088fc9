#include "craterkit/sph/rates/rates.hpp"

#include "craterkit/sph/rates/artificial_stress.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/particles/minimum_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace craterkit::sph {

void VelocityGradients::resize(std::size_t n) {
  for (auto& component : corrected) component.resize(n);
}

std::string_view viscosity_switch_name(ViscositySwitch s) noexcept {
  return s == ViscositySwitch::morris_monaghan ? "morris_monaghan" : "none";
}

namespace {

// artificial_stress: solids with RateOptions::artificial_stress on (a separate instantiation, so that the
// pair loop without it is the one it was: +4.6 % instructions in the solid pass behind a run-time flag).
template <class Kernel, bool solid, bool mirrored, bool artificial_stress = false>
RateSummary rates_impl(Particles& p, const PairList& pairs, const RateOptions& options,
                       RateWorkspace& workspace, VelocityGradients* gradients,
                       const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* z = p.z.data();
  const double* vx = p.vx.data();
  const double* vy = p.vy.data();
  const double* vz = p.vz.data();
  const double* mass = p.mass.data();
  const double* rho = p.density.data();
  const double* h = p.smoothing_length.data();
  const double* c = p.sound_speed.data();
  const double* alpha = p.viscosity_alpha.data();
  // The Balsara factors of the last evaluation are read (for i and j); the new ones go to the workspace
  // and replace them after the pass, so that no particle reads a neighbour's value of this pass (the
  // result would depend on the thread schedule).
  p.balsara.resize(p.size(), 1.0);
  const double* balsara = p.balsara.data();
  if (options.viscosity.balsara) workspace.balsara_next.resize(p.size());
  double* balsara_next = workspace.balsara_next.data();
  const double* pressure = p.pressure.data();
  const double* inv_rho = workspace.inverse_density.data();
  const double* volume = workspace.volume.data();
  workspace.neighbour_count.resize(p.size());
  std::uint32_t* neighbour_count = workspace.neighbour_count.data();
  workspace.signal_time.resize(p.size());
  double* signal_time = workspace.signal_time.data();
  // Solids: B = sigma L / rho^2 (sigma = S - P I, L the stored correction matrix of
  // gradient_correction.hpp) of every particle, the half of the corrected stress force and of the work term
  // that belongs to one particle of a pair. Computed once per particle here instead of once per pair in the
  // loop (a pair then reads 9 values of B_j instead of S_j, P_j and L_j and computing sigma_j L_j);
  // every particle, because the selected ones read the neighbours' B.
  std::array<const double*, 9> stress_force{};
  // Solids: the artificial stress R of every particle (artificial_stress.hpp), with B.
  constexpr bool use_artificial_stress = solid && artificial_stress;
  std::array<double*, 6> artificial{};
  if constexpr (use_artificial_stress) {
    for (int k = 0; k < 6; ++k) {
      workspace.artificial_stress[k].resize(p.size());
      artificial[k] = workspace.artificial_stress[k].data();
    }
  }
  const double* rxx_all = artificial[0];
  const double* rxy_all = artificial[1];
  const double* rxz_all = artificial[2];
  const double* ryy_all = artificial[3];
  const double* ryz_all = artificial[4];
  const double* rzz_all = artificial[5];
  // f_ij = W(r_ij, h_ij) / W(dp, h_ij) with dp = h_ij spacing_over_h: W scales as h^-3, so the ratio is that
  // of the kernel at unit h.
  const double inverse_kernel_at_spacing =
      use_artificial_stress ? 1.0 / Kernel::value(options.artificial_stress.spacing_over_h, 1.0) : 0.0;
  if constexpr (solid) {
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
      stress_force[k] = B[k];
    }
    const auto all = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < all; ++i) {
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
      if constexpr (use_artificial_stress) {
        const std::array<double, 6> R = artificial_stress_tensor({s_xx, s_xy, s_xz, s_yy, s_yz, s_zz},
                                                                 inv_rho2, options.artificial_stress.epsilon);
        for (int k = 0; k < 6; ++k) artificial[k][i] = R[k];
      }
    }
  }
  const double* bxx_all = stress_force[0];
  const double* bxy_all = stress_force[1];
  const double* bxz_all = stress_force[2];
  const double* byx_all = stress_force[3];
  const double* byy_all = stress_force[4];
  const double* byz_all = stress_force[5];
  const double* bzx_all = stress_force[6];
  const double* bzy_all = stress_force[7];
  const double* bzz_all = stress_force[8];
  // This evaluation's correction matrices are written over the stored ones as the pass goes: the pair loop
  // reads the stored L only through B, computed above, so no particle sees a neighbour's new L.
  std::array<double*, 6> correction{};
  if constexpr (solid) {
    correction = {p.correction_xx.data(), p.correction_xy.data(), p.correction_xz.data(),
                  p.correction_yy.data(), p.correction_yz.data(), p.correction_zz.data()};
  }
  const std::uint8_t* flags = p.flags.data();
  const std::uint64_t* offsets = pairs.offsets.data();
  const std::uint32_t* neighbours = pairs.neighbours.data();

  double* ax_out = p.acceleration_x.data();
  double* ay_out = p.acceleration_y.data();
  double* az_out = p.acceleration_z.data();
  double* drho_out = p.density_rate.data();
  double* du_out = p.energy_rate.data();
  double* dalpha_out = p.viscosity_alpha_rate.data();

  const auto& av = options.viscosity;
  const bool use_switch = av.viscosity_switch != ViscositySwitch::none;
  const bool use_balsara = av.balsara;
  const double beta_over_alpha = av.alpha > 0.0 ? av.beta / av.alpha : 0.0;
  const double eps = av.epsilon;
  const double inf = std::numeric_limits<double>::infinity();
  const double Lx = options.period[0], Ly = options.period[1], Lz = options.period[2];
  const double hx = Lx > 0.0 ? 0.5 * Lx : inf;
  const double hy = Ly > 0.0 ? 0.5 * Ly : inf;
  const double hz = Lz > 0.0 ? 0.5 * Lz : inf;
  const double gx_body = options.gravity[0], gy_body = options.gravity[1], gz_body = options.gravity[2];
  const MirrorPlanes planes = options.mirror;

  double min_signal_time = inf;
  std::uint64_t interacting = 0;

#pragma omp parallel for schedule(dynamic, 128) reduction(min : min_signal_time) reduction(+ : interacting)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    if ((flags[i] & (particle_fixed | particle_ejected)) != 0) {
      ax_out[i] = ay_out[i] = az_out[i] = 0.0;
      drho_out[i] = du_out[i] = dalpha_out[i] = 0.0;
      neighbour_count[i] = 0;
      signal_time[i] = inf;
      continue;
    }
    const double xi = x[i], yi = y[i], zi = z[i];
    const double vxi = vx[i], vyi = vy[i], vzi = vz[i];
    const double hi = h[i], ci = c[i], rhoi = rho[i], inv_rhoi = inv_rho[i];
    const double pr2i = pressure[i] * (inv_rhoi * inv_rhoi);  // P_i/rho_i^2, rounded as for j
    const double alphai = use_switch ? alpha[i] : av.alpha;
    const double balsarai = balsara[i];

    double ax = 0.0, ay = 0.0, az = 0.0;
    double vv_grad = 0.0;                             // sum_j (m_j/rho_j) v_ij . grad_i W_ij  (= -div v_i)
    double mv_grad = 0.0;                             // sum_j m_j v_ij . grad_i W_ij
    double viscous = 0.0;                             // sum_j m_j Pi_ij v_ij . grad_i W_ij
    double max_mu = 0.0;                              // max_j |mu_ij| over approaching pairs
    double curl_x = 0.0, curl_y = 0.0, curl_z = 0.0;  // sum_j V_j (v_j - v_i) x grad_i W_ij (Balsara, fluids)
    std::uint64_t count = 0;

    // Solid-only state and accumulators (dead code, removed by the compiler, for fluids; the stress and
    // correction arrays are not even allocated then, so they are read only under `solid`).
    double bxx = 0.0, bxy = 0.0, bxz = 0.0, byx = 0.0, byy = 0.0, byz = 0.0, bzx = 0.0, bzy = 0.0, bzz = 0.0;
    if constexpr (solid) {
      bxx = bxx_all[i], bxy = bxy_all[i], bxz = bxz_all[i];
      byx = byx_all[i], byy = byy_all[i], byz = byz_all[i];
      bzx = bzx_all[i], bzy = bzy_all[i], bzz = bzz_all[i];
    }
    double rxx = 0.0, rxy = 0.0, rxz = 0.0, ryy = 0.0, ryz = 0.0, rzz = 0.0;  // artificial stress R_i
    if constexpr (use_artificial_stress) {
      rxx = rxx_all[i], rxy = rxy_all[i], rxz = rxz_all[i], ryy = ryy_all[i], ryz = ryz_all[i],
      rzz = rzz_all[i];
    }
    double G[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  // sum V_j (v_j - v_i) (x) grad W
    std::array<double, 6> M{0, 0, 0, 0, 0, 0};  // sum V_j (x_j - x_i) (x) grad W: xx, xy, xz, yy, yz, zz
    double work = 0.0;  // -sum_j m_j v_ij . (B_i grad W): pressure and deviatoric work, matched to the force

    for (std::uint64_t k = offsets[i]; k < offsets[i + 1]; ++k) {
      // The neighbour, or its mirror image: position, velocity and deviatoric stress of j mapped to the
      // image (without mirror planes bits is the constant 0 and the mapping compiles away).
      const MirrorImage image = mirror_image<mirrored>(neighbours[k]);
      const std::size_t j = image.index;
      const double dx = minimum_image(xi - image.position(0, planes, x[j]), Lx, hx);
      const double dy = minimum_image(yi - image.position(1, planes, y[j]), Ly, hy);
      const double dz = minimum_image(zi - image.position(2, planes, z[j]), Lz, hz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double hsum = hi + h[j];
      if (r2 >= hsum * hsum || r2 <= 0.0) continue;
      ++count;
      const double r = std::sqrt(r2);
      const double hbar = 0.5 * hsum;
      const double dwdr_over_r = Kernel::derivative(r, hbar) / r;
      const double gx = dx * dwdr_over_r, gy = dy * dwdr_over_r, gz = dz * dwdr_over_r;  // grad_i W_ij
      const double dvx = vxi - image.vector(0, vx[j]), dvy = vyi - image.vector(1, vy[j]),
                   dvz = vzi - image.vector(2, vz[j]);
      const double v_dot_g = dvx * gx + dvy * gy + dvz * gz;
      const double v_dot_x = dvx * dx + dvy * dy + dvz * dz;
      const double mj = mass[j];

      // Monaghan & Gingold (1983) viscosity, only for approaching pairs.
      double pi_ij = 0.0;
      if (v_dot_x < 0.0) {
        const double mu = hbar * v_dot_x / (r2 + eps * hbar * hbar);
        const double cbar = 0.5 * (ci + c[j]);
        const double rhobar = 0.5 * (rhoi + rho[j]);
        const double alpha_ij = use_switch ? 0.5 * (alphai + alpha[j]) : av.alpha;
        const double beta_ij = use_switch ? beta_over_alpha * alpha_ij : av.beta;
        pi_ij = (-alpha_ij * cbar * mu + beta_ij * mu * mu) / rhobar;
        if (use_balsara) pi_ij *= 0.5 * (balsarai + balsara[j]);
        max_mu = std::max(max_mu, -mu);
      }

      const double inv_rho2j = inv_rho[j] * inv_rho[j];
      double f = pi_ij;  // the pressure of solids is in their stress force below
      if constexpr (!solid) f += pr2i + pressure[j] * inv_rho2j;  // symmetric in i, j
      ax -= mj * f * gx;
      ay -= mj * f * gy;
      az -= mj * f * gz;
      vv_grad += volume[j] * v_dot_g;
      if constexpr (!solid) mv_grad += mj * v_dot_g;
      viscous += mj * pi_ij * v_dot_g;
      if constexpr (!solid) {
        if (use_balsara) {  // (v_j - v_i) x grad W = grad W x dv (solids take it from G below)
          curl_x += volume[j] * (gy * dvz - gz * dvy);
          curl_y += volume[j] * (gz * dvx - gx * dvz);
          curl_z += volume[j] * (gx * dvy - gy * dvx);
        }
      }

      if constexpr (solid) {
        // + m_j (B_i + B_j) grad_i W_ij, B = sigma L / rho^2 (the image's B: off-diagonals reflected like S).
        double tix = bxx * gx + bxy * gy + bxz * gz;
        double tiy = byx * gx + byy * gy + byz * gz;
        double tiz = bzx * gx + bzy * gy + bzz * gz;
        double tjx =
            bxx_all[j] * gx + image.shear(0, 1, bxy_all[j]) * gy + image.shear(0, 2, bxz_all[j]) * gz;
        double tjy =
            image.shear(0, 1, byx_all[j]) * gx + byy_all[j] * gy + image.shear(1, 2, byz_all[j]) * gz;
        double tjz =
            image.shear(0, 2, bzx_all[j]) * gx + image.shear(1, 2, bzy_all[j]) * gy + bzz_all[j] * gz;
        if constexpr (use_artificial_stress) {
          // + m_j f_ij^4 (R_i + R_j) grad_i W_ij, added to the stress force of each side (and so to its
          // work).
          const double ratio = Kernel::value(r / hbar, 1.0) * inverse_kernel_at_spacing;
          const double f2 = ratio * ratio;
          const double f4 = f2 * f2;
          static_assert(artificial_stress_exponent == 4);
          const double rxy_j = image.shear(0, 1, rxy_all[j]), rxz_j = image.shear(0, 2, rxz_all[j]),
                       ryz_j = image.shear(1, 2, ryz_all[j]);
          tix += f4 * (rxx * gx + rxy * gy + rxz * gz);
          tiy += f4 * (rxy * gx + ryy * gy + ryz * gz);
          tiz += f4 * (rxz * gx + ryz * gy + rzz * gz);
          tjx += f4 * (rxx_all[j] * gx + rxy_j * gy + rxz_j * gz);
          tjy += f4 * (rxy_j * gx + ryy_all[j] * gy + ryz_j * gz);
          tjz += f4 * (rxz_j * gx + ryz_j * gy + rzz_all[j] * gz);
        }
        ax += mj * (tix + tjx);
        ay += mj * (tiy + tjy);
        az += mj * (tiz + tjz);
        work -= mj * (dvx * tix + dvy * tiy + dvz * tiz);
        // (v_j - v_i) = -dv, grad W = g.
        const double vgx = volume[j] * gx, vgy = volume[j] * gy, vgz = volume[j] * gz;
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

    ax_out[i] = ax + gx_body;
    ay_out[i] = ay + gy_body;
    az_out[i] = az + gz_body;
    drho_out[i] = rhoi * vv_grad;
    if constexpr (solid) {
      du_out[i] = work + 0.5 * viscous;
      // This evaluation's L_i: for the corrected velocity gradient G . L_i (Randles & Libersky 1996) of the
      // stress rate now, and for the force in the next evaluation (gradient_correction.hpp).
      const std::array<double, 6> L = correction_matrix(M);
      for (int k = 0; k < 6; ++k) correction[k][i] = L[k];
      if (gradients != nullptr) {
        const double Lm[9] = {L[0], L[1], L[2], L[1], L[3], L[4], L[2], L[4], L[5]};
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) {
            gradients->corrected[3 * a + b][i] =
                G[3 * a] * Lm[b] + G[3 * a + 1] * Lm[3 + b] + G[3 * a + 2] * Lm[6 + b];
          }
        }
      }
    } else {
      du_out[i] = pr2i * mv_grad + 0.5 * viscous;
    }

    if (use_balsara) {
      // Balsara (1995) factor |div v| / (|div v| + |curl v| + 1e-4 c/h) for the next evaluation, from the
      // uncorrected (kernel-sum) gradient: G[3a + b] = dv_a/dx_b for solids.
      if constexpr (solid) {
        curl_x = G[7] - G[5];
        curl_y = G[2] - G[6];
        curl_z = G[3] - G[1];
      }
      const double div_v = std::abs(vv_grad);
      const double curl_v = std::sqrt(curl_x * curl_x + curl_y * curl_y + curl_z * curl_z);
      const double denominator = div_v + curl_v + 1e-4 * ci / hi;
      balsara_next[i] = denominator > 0.0 ? div_v / denominator : 1.0;
    }
    if (use_switch) {
      // Morris & Monaghan (1997): decay towards alpha_min on tau = h / (l c), growth in compression.
      const double div_v = -vv_grad;
      const double source = std::max(-div_v, 0.0) * (av.alpha - alphai);
      dalpha_out[i] = -(alphai - av.alpha_min) * av.decay_factor * ci / hi + source;
    } else {
      dalpha_out[i] = 0.0;
    }

    const double beta_i = use_switch ? beta_over_alpha * alphai : av.beta;
    const double signal = ci + 1.2 * (alphai * ci + beta_i * max_mu);
    signal_time[i] = signal > 0.0 ? hi / signal : inf;
    min_signal_time = std::min(min_signal_time, signal_time[i]);
    interacting += count;
    neighbour_count[i] = static_cast<std::uint32_t>(count);
  }
  if (use_balsara) {
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

RateSummary compute_rates(Particles& particles, const PairList& pairs, const RateOptions& options,
                          RateWorkspace& workspace, const ParticleSelection& selection,
                          VelocityGradients* gradients) {
  if (gradients != nullptr) gradients->resize(particles.size());
  return with_kernel(options.kernel, [&](auto kernel) {
    using K = decltype(kernel);
    const bool artificial = options.solid && options.artificial_stress.on();
    if (options.mirror.any()) {
      if (artificial)
        return rates_impl<K, true, true, true>(particles, pairs, options, workspace, gradients, selection);
      return options.solid
                 ? rates_impl<K, true, true>(particles, pairs, options, workspace, gradients, selection)
                 : rates_impl<K, false, true>(particles, pairs, options, workspace, gradients, selection);
    }
    if (artificial)
      return rates_impl<K, true, false, true>(particles, pairs, options, workspace, gradients, selection);
    return options.solid
               ? rates_impl<K, true, false>(particles, pairs, options, workspace, gradients, selection)
               : rates_impl<K, false, false>(particles, pairs, options, workspace, gradients, selection);
  });
}

}  // namespace craterkit::sph
