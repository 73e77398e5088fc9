#pragma once
// Hydrodynamic rates of change (docs/physics.md section 1): continuity density, momentum, specific
// internal energy, Monaghan-Gingold artificial viscosity with an optional Morris-Monaghan switch,
// and the Randles-Libersky corrected velocity gradient that will drive the stress rate.
//
// One pass over the pairs: an OpenMP driver over particles i and an inline body over the
// neighbours j of i (gather form: each i writes only its own rates, so no atomics and the result
// does not depend on the number of threads). The pair body is instantiated per kernel and per
// "solid" flag (deviatoric stress terms and velocity gradient on or off), chosen once per call.
// Material physics (equations of state) is evaluated per particle before this pass
// (rates_pressure.hpp); the pair loop only reads P, c, 1/rho and m/rho.
//
// Equations for fluids (docs/physics.md section 1), with one deviation in the continuity equation:
//   drho_i/dt = rho_i sum_j (m_j/rho_j) v_ij . grad_i W_ij    (= -rho_i div v_i)
//   dv_i/dt   = sum_j m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I) . grad_i W_ij + g
//   du_i/dt   = (P_i/rho_i^2) sum_j m_j v_ij . grad_i W_ij + (1/rho_i) S_i : U_i
//               + (1/2) sum_j m_j Pi_ij v_ij . grad_i W_ij,   U_i = (1/rho_i) sum_j m_j (v_j - v_i) (x)
//               grad_i W_ij
// docs/physics.md writes sum_j m_j v_ij . grad_i W_ij for drho/dt; the two agree where the density is
// smooth, but with m_j the relative rate (1/rho_i) drho_i/dt of a particle much less dense than its
// neighbours grows as 1/rho_i and drives its density to zero in finite time (seen in the hot centre
// of the Sedov blast, where the time step then collapsed). The energy equation keeps the m_j form,
// which matches the momentum equation pair by pair: total energy is conserved to the integration
// error.
// The mix is not adiabatic where neighbour densities differ (du/dt != (P/rho^2) drho/dt), and the
// P/rho^2 force pushes the two sides of a density jump apart (Sod lattices, contact at rest: -117 and
// +629 at t = 0). The fully volume-weighted scheme, (P_i + P_j)/(rho_i rho_j) in the momentum
// equation and (P_i/rho_i) sum_j (m_j/rho_j) v_ij . grad W in the energy equation (adiabatic, and
// energy-conserving pair by pair), fixes both (contact at rest: L1 0.005 against 0.030) but moves the
// Sedov shock radius from -1.7 % to -3.2 % at 50^3 (over the 3 % bound), so it is not used. Neither
// form was the cause of the wrong Sod star state: that was the smoothing length (docs/validation.md).
//
// Solids (RateOptions::solid: a material has strength) use the kernel-gradient correction L of every
// particle (gradient_correction.hpp: in the force the L of the previous evaluation, Particles::correction_*;
// in the stress rate the one this pass computes) in the stress divergence and its work term, not only in the
// velocity gradient of the stress rate (docs/physics.md section 1):
//   dv_i/dt   = sum_j m_j (sigma_i L_i/rho_i^2 + sigma_j L_j/rho_j^2 - Pi_ij I) . grad_i W_ij + g,
//   du_i/dt   = -sum_j m_j v_ij . (sigma_i L_i/rho_i^2) grad_i W_ij
//               + (1/2) sum_j m_j Pi_ij v_ij . grad_i W_ij,
//   grad v_i  = [sum_j V_j (v_j - v_i) (x) grad_i W_ij] . L_i  (stress rate),
// sigma = S - P I; the density rate is the fluids' one. Why: with the uncorrected gradient a particle within
// 2h of a free surface sees its tangential stress gradients short by up to 20 % (the kernel moment M is
// 0.78 there instead of 1), and a free elastic plate came out too soft in bending (period +21.8 % at 6
// particles across and 1 % of L; +13.4 % with the correction; +4.6 % at 8 across and 0.1 % of L,
// docs/validation.md "Elastic plate"). The pair force keeps
// the form of the uncorrected one (any per-particle matrices L_i, L_j leave it antisymmetric, so momentum
// is conserved exactly), and the work term is the force's own (u + kinetic energy conserved pair by pair).
// The density stays uncorrected: with -rho tr(grad v) from the corrected gradient a collapsing granular
// column blew up at its front within three free-fall times (the corrected divergence of a particle short
// of neighbours need not see two particles approach), and the plate gained only 1 % from it.
//
// Mirror planes (RateOptions::mirror, mirror_image.hpp): a list entry may be a neighbour's mirror image,
// whose position, velocity and deviatoric stress the pair body reflects before using them; nothing else
// changes. The sums over i then run over the real particles of a symmetric system, so momentum normal to a
// plane is not conserved by the sum over the real particles (the plane pushes back), the components along
// the planes and the energy are.
//
// Momentum is conserved pairwise: the force term for (i, j) is built from expressions symmetric in
// i and j (hbar, cbar, rhobar, P_i/rho_i^2 + P_j/rho_j^2) times grad_i W_ij = -grad_j W_ji, so the
// pair forces cancel to round-off.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"
#include "craterkit/sph/particles/particle_selection.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/rates/artificial_stress.hpp"

namespace craterkit::sph {

enum class ViscositySwitch {
  none,            // alpha constant (Monaghan & Gingold 1983)
  morris_monaghan  // per-particle alpha evolved by Morris & Monaghan (1997), eq. 10 with the
                   // (alpha_max - alpha) source factor of Rosswog et al. (2000)
};

struct ArtificialViscosity {
  double alpha = 1.0;  // linear coefficient (the maximum when a switch is on)
  double beta = 2.0;   // quadratic coefficient; with a switch, beta_ij = beta * alpha_ij / alpha
  ViscositySwitch viscosity_switch = ViscositySwitch::none;
  double alpha_min = 0.1;     // floor the switch decays to away from shocks
  double decay_factor = 0.2;  // l in the decay time tau = h / (l c) of Morris & Monaghan
  double epsilon = 0.01;      // eta^2 regulariser in mu_ij = hbar v.x / (r^2 + eps hbar^2)
  // Balsara (1995) limiter: Pi_ij times (f_i + f_j)/2, f = |div v| / (|div v| + |curl v| + 1e-4 c/h), so
  // that shear flow (f -> 0) carries no viscosity while compression (f -> 1) keeps it. f is each
  // particle's value from its last rate evaluation (Particles::balsara).
  bool balsara = false;
};

struct RateOptions {
  KernelType kernel = KernelType::cubic_spline;
  ArtificialViscosity viscosity{};
  std::array<double, 3> gravity{0.0, 0.0, 0.0};  // constant body force, m/s^2
  // Period along each axis (upper - lower) for minimum-image displacements; 0 = not periodic.
  std::array<double, 3> period{0.0, 0.0, 0.0};
  // Symmetry planes (mirror_planes(box)): list entries with image bits are the neighbour reflected
  // across them (mirror_image.hpp). Must be the planes the lists were built with.
  MirrorPlanes mirror{};
  // Stress terms in momentum and energy with the gradient correction (above) and the corrected velocity
  // gradient. Reads Particles::correction_* (of the previous evaluation, or compute_correction_matrices)
  // and replaces them with this evaluation's. Off for fluids: the pair loop then carries no stress work.
  bool solid = false;
  // Solids only: the repulsive stress of Monaghan (2000) between close neighbours in tension
  // (artificial_stress.hpp); off unless epsilon > 0.
  ArtificialStress artificial_stress{};
  // The pair loop in 256-bit registers where the processor has AVX2; false: in the baseline processor's
  // 128-bit ones (slower). Both do the same operations and give the same results, bit for bit.
  bool wide_lanes = true;
};

// Neighbour lists (NeighbourLists): the neighbours of i are neighbours[offsets[i] .. end), where end is
// offsets[i+1] (packed lists, `ends` empty) or ends[i] (kept lists). Entries may include pairs beyond
// h_i + h_j (a search skin); the pair body drops them, so lists sorted by entry give the same sums whatever
// superset they hold. An entry is a particle index with mirror-image bits (mirror_image.hpp; zero without
// mirror planes).
struct PairList {
  std::span<const std::uint64_t> offsets;
  std::span<const std::uint32_t> neighbours;
  std::span<const std::uint64_t> ends = {};
  // Where list i ends: ends[i] reads ends_of()[i].
  [[nodiscard]] const std::uint64_t* ends_of() const {
    return ends.empty() ? offsets.data() + 1 : ends.data();
  }
};

// Corrected velocity gradient (grad v)_ab = dv_a/dx_b per particle, row-major (xx, xy, xz, yx, ...), for
// the stress rate. Filled only when RateOptions::solid is set.
struct VelocityGradients {
  std::array<std::vector<double>, 9> corrected;
  void resize(std::size_t n);
};

// Per-particle inputs derived before the pair pass (one division per particle, not per pair).
struct RateWorkspace {
  std::vector<double> inverse_density;  // 1/rho
  std::vector<double> volume;           // m/rho
  // Output of the pair pass: pairs with r < h_i + h_j per particle (drives the smoothing length).
  std::vector<std::uint32_t> neighbour_count;
  // Output of the pair pass: h_i / (c_i + 1.2 (alpha_i c_i + beta_i max_j |mu_ij|)) per particle, s (the
  // Courant time before the factor C; +infinity for fixed and ejected particles). Block time steps
  // (block_time_steps.hpp) give each particle its own step from it.
  std::vector<double> signal_time;
  // The Balsara factors computed by the pass (ArtificialViscosity::balsara), copied to Particles::balsara
  // after it.
  std::vector<double> balsara_next;
  // Solids: B = sigma L / rho^2 of every particle (xx, xy, xz, yx, yy, yz, zx, zy, zz), the per-particle
  // half of the corrected stress force, computed at the start of the pass.
  std::array<std::vector<double>, 9> stress_force;
  // Solids with RateOptions::artificial_stress on: R of every particle (xx, xy, xz, yy, yz, zz), in the
  // units of B (Pa m^6/kg^2), computed with B.
  std::array<std::vector<double>, 6> artificial_stress;

  // Bytes held (capacity, as allocated).
  [[nodiscard]] std::size_t bytes() const {
    std::size_t doubles =
        inverse_density.capacity() + volume.capacity() + signal_time.capacity() + balsara_next.capacity();
    for (const auto& v : stress_force) doubles += v.capacity();
    for (const auto& v : artificial_stress) doubles += v.capacity();
    return doubles * sizeof(double) + neighbour_count.capacity() * sizeof(std::uint32_t);
  }
};

struct RateSummary {
  // min over active particles of h_i / (c_i + 1.2 (alpha_i c_i + beta_i max_j |mu_ij|)): the Courant
  // time of docs/physics.md section 1 before the factor C.
  double min_signal_time = std::numeric_limits<double>::infinity();
  std::uint64_t interacting_pairs = 0;  // (i, j) entries with r < h_i + h_j, both orders counted
};

// Fills acceleration_{x,y,z}, density_rate, energy_rate and viscosity_alpha_rate of every active
// particle (zero for fixed and ejected ones). Requires pressure and sound_speed to be current and
// workspace.inverse_density and volume filled (update_pressure does both); fills
// workspace.neighbour_count.
RateSummary compute_rates(Particles& particles, const PairList& pairs, const RateOptions& options,
                          RateWorkspace& workspace, VelocityGradients* gradients = nullptr);
// The same for the selected particles only (block time steps): every other particle's rates, neighbour
// count and signal time are left as they were; the neighbours j of a selected particle are all particles.
RateSummary compute_rates(Particles& particles, const PairList& pairs, const RateOptions& options,
                          RateWorkspace& workspace, const ParticleSelection& selection,
                          VelocityGradients* gradients = nullptr);

// Solids (options.solid): the same pass over the selected particles, which in addition writes their stress
// rates as compute_stress_rates() would (store_stress_rate, stress_rates.hpp) from the corrected velocity
// gradient it has just computed. Why: the gradient is then not stored, so a solver that needs nothing else of
// it holds no VelocityGradients (9 doubles, 72 bytes per particle). shear_modulus as update_material_state()
// fills it; materials[m] is material id m (for the strain that weakens its cohesion). `neighbourhood`, if
// given, holds the selected particles and every neighbour of theirs within the support (the particles whose
// state the pass reads): the per-particle half of the stress force is computed for those alone.
RateSummary compute_rates_and_stress_rates(Particles& particles, const PairList& pairs,
                                           const RateOptions& options, RateWorkspace& workspace,
                                           const ParticleSelection& selection,
                                           std::span<const double> shear_modulus,
                                           std::span<const Material> materials,
                                           const ParticleSelection* neighbourhood = nullptr);

[[nodiscard]] std::string_view viscosity_switch_name(ViscositySwitch s) noexcept;

}  // namespace craterkit::sph
