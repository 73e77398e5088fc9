#pragma once
// Particle storage: structure-of-arrays, one contiguous std::vector per field, owned by Particles.
// Phases take the arrays they need (spans), so what each phase reads and writes is visible in its
// signature. Distention is always present (one when non-porous). The solid-mechanics group
// (deviatoric stress, accumulated strain and their rates, the distention rate, the kernel-gradient
// correction matrix and the peak pressure: 20 doubles, 160 bytes per particle) is present only while
// `solid_fields` is true; a run whose materials have neither strength nor porosity drops it
// (set_solid_fields(false)), and snapshots and checkpoints then simply do not hold it. The distention rate
// belongs to this group rather than to the core so that fluid runs (Sedov, Sod) carry nothing of the material
// models; a porous material without strength therefore carries the (zero) stress fields too, a cost paid only
// in that rare case.
//
// Every field is registered in for_each_field(), which is the single list used by sorting along the
// space-filling curve, by snapshots and by checkpoints: adding a field means adding one line there.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace craterkit::sph {

// Per-particle state bits.
enum ParticleFlag : std::uint8_t {
  particle_active = 0,
  particle_fixed = 1u << 0,    // boundary particle: takes part in sums, never moves
  particle_ejected = 1u << 1,  // removed from the hydrodynamics (recorded as ejecta)
};

struct Particles {
  // Identity and material.
  std::vector<std::uint64_t> id;        // persistent across sorting and restarts
  std::vector<std::uint16_t> material;  // index into the run's material table
  std::vector<std::uint8_t> flags;      // ParticleFlag bits

  // Kinematics.
  std::vector<double> x, y, z;     // position, m
  std::vector<double> vx, vy, vz;  // velocity, m/s

  // Thermodynamic state.
  std::vector<double> mass;              // kg
  std::vector<double> density;           // bulk density rho, kg/m^3
  std::vector<double> specific_energy;   // u, J/kg
  std::vector<double> smoothing_length;  // h, m (kernel support 2h)
  std::vector<double> pressure;          // bulk pressure P, Pa (derived each step by the EOS)
  std::vector<double> sound_speed;       // c, m/s (derived each step by the EOS)

  // Solid mechanics (only while solid_fields): symmetric traceless deviatoric stress S (Pa);
  // S_zz = -(S_xx + S_yy).
  std::vector<double> stress_xx, stress_xy, stress_xz, stress_yy, stress_yz;
  std::vector<double> total_strain;  // accumulated total (deviatoric) strain, dimensionless
  std::vector<double> distention;    // P-alpha alpha = rho_matrix / rho >= 1 (1 when non-porous)

  // Artificial viscosity coefficient per particle (for switches; constant alpha when none).
  std::vector<double> viscosity_alpha;
  // Balsara factor f in [0, 1] of the viscosity (rates.hpp), from the last rate evaluation; 1 without.
  std::vector<double> balsara;

  // Time derivatives from the last rate evaluation (rates.hpp). They are state, not scratch: the
  // second-order integrator (integrator.hpp) reuses them in the next step, so checkpoints must
  // hold them for a restart to continue bitwise.
  std::vector<double> acceleration_x, acceleration_y, acceleration_z;  // dv/dt, m/s^2
  std::vector<double> density_rate;                                    // drho/dt, kg/m^3/s
  std::vector<double> energy_rate;                                     // du/dt, W/kg
  std::vector<double> viscosity_alpha_rate;                            // dalpha/dt, 1/s
  // The step this particle may take on its own, s (time_step.hpp: the smallest of its Courant,
  // acceleration, density, energy and velocity-change limits) from its last rate evaluation. State for
  // block time steps (block_time_steps.hpp: the next block's levels come from it, also after a restart);
  // with a global step it shows which particles hold the step down.
  std::vector<double> time_step;
  // Solid mechanics (stress_rates.hpp; only while solid_fields): the Jaumann rate dS/dt, Pa/s, and the
  // rate of the accumulated strain, 1/s.
  std::vector<double> stress_rate_xx, stress_rate_xy, stress_rate_xz, stress_rate_yy, stress_rate_yz;
  std::vector<double> total_strain_rate;
  // P-alpha (only while solid_fields): dalpha/dt of the consistent rate of Jutzi et al. (2008), 1/s
  // (stress_rates.hpp, compute_distention_rates); zero for non-porous particles.
  std::vector<double> distention_rate;
  // Randles & Libersky (1996) correction matrix L_i = [sum_j V_j (x_j - x_i) (x) grad_i W_ij]^-1 of the
  // last rate evaluation (gradient_correction.hpp; only while solid_fields): symmetric, dimensionless,
  // the identity in the bulk of a lattice and where the matrix is ill-conditioned. State, not scratch:
  // with block time steps an inactive neighbour's L is the one of its last evaluation, so checkpoints
  // hold it for a bitwise restart.
  std::vector<double> correction_xx, correction_xy, correction_xz, correction_yy, correction_yz,
      correction_zz;
  // The largest pressure of the particle's states at the ends of its steps, Pa (only while solid_fields): the
  // peak shock pressure it went through (docs/output.md). A diagnostic; nothing reads it back. Zero in a run
  // resumed from a file written before the field existed, until the next step.
  std::vector<double> peak_pressure;

  // Whether the solid-mechanics group (strength and porosity) is allocated (and visited by for_each_field).
  bool solid_fields = true;

  [[nodiscard]] std::size_t size() const { return x.size(); }
  void resize(std::size_t n);  // new entries: zeros, distention 1, identity correction, flags active
  // Allocates the solid-mechanics group (zeros, identity correction) or releases it; no-op if already so.
  void set_solid_fields(bool present);
  void reserve(std::size_t n);
  void shrink_to_fit();  // releases the growth slack of every field (set-ups build by push_back)

  // Appends the particles of `other`, which must hold the same fields (solid_fields alike).
  void append(const Particles& other);

  // Reorders every registered field: new index k takes the particle at old index order[k].
  void permute(std::span<const std::uint32_t> order);

  // Visits every field as (name, vector&). Names are the snapshot/checkpoint dataset names.
  template <class Visitor>
  void for_each_field(Visitor&& visit) {
    visit(std::string_view{"id"}, id);
    visit(std::string_view{"material"}, material);
    visit(std::string_view{"flags"}, flags);
    visit(std::string_view{"x"}, x);
    visit(std::string_view{"y"}, y);
    visit(std::string_view{"z"}, z);
    visit(std::string_view{"vx"}, vx);
    visit(std::string_view{"vy"}, vy);
    visit(std::string_view{"vz"}, vz);
    visit(std::string_view{"mass"}, mass);
    visit(std::string_view{"density"}, density);
    visit(std::string_view{"specific_energy"}, specific_energy);
    visit(std::string_view{"smoothing_length"}, smoothing_length);
    visit(std::string_view{"pressure"}, pressure);
    visit(std::string_view{"sound_speed"}, sound_speed);
    visit(std::string_view{"distention"}, distention);
    visit(std::string_view{"viscosity_alpha"}, viscosity_alpha);
    visit(std::string_view{"balsara"}, balsara);
    visit(std::string_view{"acceleration_x"}, acceleration_x);
    visit(std::string_view{"acceleration_y"}, acceleration_y);
    visit(std::string_view{"acceleration_z"}, acceleration_z);
    visit(std::string_view{"density_rate"}, density_rate);
    visit(std::string_view{"energy_rate"}, energy_rate);
    visit(std::string_view{"viscosity_alpha_rate"}, viscosity_alpha_rate);
    visit(std::string_view{"time_step"}, time_step);
    if (solid_fields) for_each_solid_field(visit);
  }
  // The solid-mechanics group alone (visited whether or not it is allocated).
  template <class Visitor>
  void for_each_solid_field(Visitor&& visit) {
    visit(std::string_view{"stress_xx"}, stress_xx);
    visit(std::string_view{"stress_xy"}, stress_xy);
    visit(std::string_view{"stress_xz"}, stress_xz);
    visit(std::string_view{"stress_yy"}, stress_yy);
    visit(std::string_view{"stress_yz"}, stress_yz);
    visit(std::string_view{"total_strain"}, total_strain);
    visit(std::string_view{"stress_rate_xx"}, stress_rate_xx);
    visit(std::string_view{"stress_rate_xy"}, stress_rate_xy);
    visit(std::string_view{"stress_rate_xz"}, stress_rate_xz);
    visit(std::string_view{"stress_rate_yy"}, stress_rate_yy);
    visit(std::string_view{"stress_rate_yz"}, stress_rate_yz);
    visit(std::string_view{"total_strain_rate"}, total_strain_rate);
    visit(std::string_view{"distention_rate"}, distention_rate);
    visit(std::string_view{"correction_xx"}, correction_xx);
    visit(std::string_view{"correction_xy"}, correction_xy);
    visit(std::string_view{"correction_xz"}, correction_xz);
    visit(std::string_view{"correction_yy"}, correction_yy);
    visit(std::string_view{"correction_yz"}, correction_yz);
    visit(std::string_view{"correction_zz"}, correction_zz);
    visit(std::string_view{"peak_pressure"}, peak_pressure);
  }
  // The value of a field that files written before it existed do not hold (the identity correction
  // matrix), or nullopt for a field every particle file must hold.
  [[nodiscard]] static std::optional<double> default_for_absent_field(std::string_view name);
  template <class Visitor>
  void for_each_field(Visitor&& visit) const {
    const_cast<Particles*>(this)->for_each_field(
        [&](std::string_view name, const auto& field) { visit(name, field); });
  }
};

}  // namespace craterkit::sph
