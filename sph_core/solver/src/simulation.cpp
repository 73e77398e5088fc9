#include "craterkit/sph/solver/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/impact/crater_growth.hpp"
#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/neighbours/mirror_reflection.hpp"
#include "craterkit/sph/run/progress.hpp"
#include "craterkit/sph/rates/rates_pressure.hpp"
#include "craterkit/sph/particles/space_filling_curve.hpp"
#include "craterkit/sph/io/step_csv_log.hpp"
#include "craterkit/sph/io/xdmf.hpp"

namespace craterkit::sph {

namespace {

std::array<double, 3> periods(const Box& box) {
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (int a = 0; a < 3; ++a) out[a] = box.periodic[a] ? box.edge(a) : 0.0;
  return out;
}

// The initial conserved quantities travel in the checkpoint attributes (relative errors of a
// resumed run refer to the start of the run, not to the restart).
constexpr const char* initial_keys[] = {"initial_mass",
                                        "initial_momentum_x",
                                        "initial_momentum_y",
                                        "initial_momentum_z",
                                        "initial_kinetic_energy",
                                        "initial_internal_energy",
                                        "initial_potential_energy",
                                        "initial_total_energy",
                                        "initial_absolute_momentum"};

std::array<double*, 9> initial_fields(ConservedQuantities& q) {
  return {&q.mass,
          &q.momentum_x,
          &q.momentum_y,
          &q.momentum_z,
          &q.kinetic_energy,
          &q.internal_energy,
          &q.potential_energy,
          &q.total_energy,
          &q.absolute_momentum};
}

double number_attribute(const RunAttributes& a, const std::string& key, const std::string& source) {
  const auto it = a.numbers.find(key);
  if (it == a.numbers.end()) throw InputError(source + ": checkpoint attribute " + key + " missing");
  return it->second;
}

}  // namespace

Scenario build_scenario(const SimulationConfig& config) {
  const double alpha = config.viscosity.alpha;
  const double eta = config.smoothing.eta;
  Scenario out;
  if (const auto* s = std::get_if<ImpactSetup>(&config.setup)) {
    ImpactScenario impact = make_impact(*s, eta, alpha, config.run.gravity);
    const ImpactSummary& summary = impact.summary;
    out.problem = std::move(impact.problem);
    auto& plan = out.problem.late_stage;
    plan.transition_time = summary.transition_time;
    plan.A_low.assign(out.problem.materials.size(), summary.low_sound_speed_modulus);
    // The density-scaled stand-in (material 1) keeps the sound speed of the material it stands for only
    // if its A_low is scaled by the same k as its other stress-like parameters (docs/impact_setup.md).
    plan.A_low[1] *= summary.model_density_scale;
    out.problem.ejection = {summary.domain_radius, summary.escape_speed};
    out.problem.attributes = impact_run_attributes(summary, config.kernel);
    out.problem.attributes.numbers["A_low_projectile"] = plan.A_low[1];
    out.impact = summary;
    return out;
  }
  if (const auto* sedov = std::get_if<SedovSetup>(&config.setup)) {
    out.problem = make_sedov(*sedov, eta, alpha);
  } else if (const auto* sod = std::get_if<SodSetup>(&config.setup)) {
    out.problem = make_sod(*sod, eta, alpha);
  } else {
    out.problem = make_plate_impact(std::get<PlateImpactSetup>(config.setup), eta, alpha);
  }
  if (config.late_stage.transition_time > 0.0) {
    out.problem.late_stage.transition_time = config.late_stage.transition_time;
    out.problem.late_stage.A_low.assign(out.problem.materials.size(), config.late_stage.A_low);
    // Fails early (naming the material) for a law without a bulk modulus, e.g. an ideal gas.
    for (const auto& m : out.problem.materials) (void)late_stage_material(m, config.late_stage.A_low);
  }
  return out;
}

ProblemSetup build_problem(const SimulationConfig& config) {
  return build_scenario(config).problem;
}

void Simulation::configure() {
  for (const auto& m : problem_.materials) equations_of_state_.push_back(m.eos);
  rate_options_.kernel = config_.kernel;
  rate_options_.viscosity = config_.viscosity;
  rate_options_.artificial_stress = {config_.artificial_stress, 1.0 / config_.smoothing.eta};
  rate_options_.gravity = config_.run.gravity;
  rate_options_.period = periods(problem_.box);
  rate_options_.mirror = mirror_planes(problem_.box);
  rate_options_.solid = false;
  porous_ = false;
  for (const auto& m : problem_.materials) {
    rate_options_.solid = rate_options_.solid || m.strength.has_value();
    porous_ = porous_ || m.porosity.has_value();
  }
  if (rate_options_.artificial_stress.on() && !rate_options_.solid) {
    throw InputError("artificial_stress.epsilon = " + format_number(config_.artificial_stress) +
                     ": the artificial stress acts on solids, and no material of this problem has strength "
                     "(set 0 or leave the key out)");
  }
  problem_.particles.set_solid_fields(rate_options_.solid || porous_);
  problem_.particles.shrink_to_fit();
  // Ejected particles (e.g. from a checkpoint) stay behind the active ones.
  order_ = ejected_last_order(problem_.particles, &active_);
  if (active_ < problem_.particles.size()) problem_.particles.permute(order_);
}

std::vector<double> Simulation::switch_to_late_stage() {
  const auto& plan = problem_.late_stage;
  std::vector<Material> switched;
  std::vector<double> stress_factor;
  for (std::size_t id = 0; id < problem_.materials.size(); ++id) {
    const auto reference = solid_reference(problem_.materials[id].eos);
    switched.push_back(late_stage_material(problem_.materials[id], plan.A_low[id]));  // throws for gases
    stress_factor.push_back(std::sqrt(plan.A_low[id] / reference->bulk_modulus));
  }
  problem_.materials = std::move(switched);
  equations_of_state_.clear();
  for (const auto& m : problem_.materials) equations_of_state_.push_back(m.eos);
  late_stage_active_ = true;
  return stress_factor;
}

void Simulation::carry_stress_across_switch(const std::vector<double>& stress_factor) {
  auto& p = problem_.particles;
  const auto n = static_cast<std::int64_t>(p.size());
  constexpr double max_strain = late_stage_max_reference_strain;
  const double g_down = std::max(0.0, -rate_options_.gravity[2]);
  const bool solid = p.solid_fields;
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const auto* law = std::get_if<LowSoundSpeed>(&problem_.materials[p.material[i]].eos);
    if (law == nullptr) continue;
    const double factor = stress_factor[p.material[i]];
    // The lithostatic part is kept, the wave part scaled to keep its energy (simulation.hpp).
    const double lithostatic = p.density[i] * g_down * std::max(0.0, -p.z[i]);
    const double kept = std::clamp(p.pressure[i], 0.0, lithostatic);
    const double pressure = kept + (p.pressure[i] - kept) * factor;
    // Matrix pressure P_m = alpha P (P-alpha, physics.md section 2) from the new law
    // P_m = A_low (rho_m / rho_m0 - 1): rho_m = rho_m0 (1 + alpha P / A_low), capped.
    const double alpha = p.distention[i];
    const double strain = std::clamp(alpha * pressure / law->A, -max_strain, max_strain);
    p.density[i] = law->reference_density * (1.0 + strain) / alpha;
    if (solid) {
      p.stress_xx[i] *= factor;
      p.stress_xy[i] *= factor;
      p.stress_xz[i] *= factor;
      p.stress_yy[i] *= factor;
      p.stress_yz[i] *= factor;
    }
  }
}

void Simulation::cap_elastic_shear_strain() {
  auto& p = problem_.particles;
  const auto n = static_cast<std::int64_t>(p.size());
  constexpr double max_strain = late_stage_max_reference_strain;
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    // Elastic shear strain sqrt(J2) / (2 G) at most max_strain: S <- S min(1, 2 G max_strain / sqrt(J2)).
    const double J2 = second_invariant(
        DeviatoricStress{p.stress_xx[i], p.stress_xy[i], p.stress_xz[i], p.stress_yy[i], p.stress_yz[i]});
    const double limit = 2.0 * shear_modulus_[i] * max_strain;
    if (!(J2 > limit * limit)) continue;
    const double f = limit / std::sqrt(J2);
    p.stress_xx[i] *= f;
    p.stress_xy[i] *= f;
    p.stress_xz[i] *= f;
    p.stress_yy[i] *= f;
    p.stress_yz[i] *= f;
  }
}

void Simulation::eject() {
  auto& p = problem_.particles;
  if (eject_particles(p, problem_.ejection, rate_workspace_.neighbour_count, time_, step_, new_ejecta_) == 0)
    return;
  order_ = ejected_last_order(p, &active_);
  p.permute(order_);
  force_rebuild_ = true;
}

Simulation::Simulation(SimulationConfig config, ProblemSetup problem)
    : config_(std::move(config)), problem_(std::move(problem)), search_(config_.neighbours.search) {
  configure();
  update_smoothing_length(problem_.particles, config_.smoothing);
  if (rate_options_.solid) {
    // The first force needs the correction matrices of the initial state (later ones come from the rate
    // pass before, gradient_correction.hpp).
    update_neighbours();
    update_equation_of_state();
    compute_correction_matrices(problem_.particles, PairList{lists_.offsets, lists_.neighbours},
                                rate_options_, rate_workspace_,
                                ParticleSelection::all(problem_.particles.size()));
  }
  evaluate_rates();
  limits_ = update_time_steps(problem_.particles, rate_workspace_.signal_time, time_step_parameters(),
                              ParticleSelection::all(problem_.particles.size()));
  dt_next_ = next_block_length();
  initial_ = conserved();
}

Simulation::Simulation(SimulationConfig config, ProblemSetup problem, Particles particles,
                       const RunAttributes& attributes)
    : config_(std::move(config)), problem_(std::move(problem)), search_(config_.neighbours.search) {
  problem_.particles = std::move(particles);
  configure();
  for (const auto id : problem_.particles.material) {
    if (id >= problem_.materials.size()) {
      throw InputError("checkpoint: material id " + std::to_string(id) + " not defined by the configuration");
    }
  }
  time_ = attributes.time;
  step_ = attributes.step;
  dt_next_ = number_attribute(attributes, "next_time_step", "checkpoint");
  if (attributes.numbers.count("late_stage_transition_time") != 0) {
    if (!problem_.late_stage.planned()) {
      throw InputError("checkpoint: written after a late-stage switch, but the configuration plans none");
    }
    switch_to_late_stage();
    mach_at_transition_ = number_attribute(attributes, "late_stage_max_mach_at_transition", "checkpoint");
    late_stage_max_mach_ = number_attribute(attributes, "late_stage_max_mach", "checkpoint");
  }
  auto fields = initial_fields(initial_);
  for (std::size_t k = 0; k < fields.size(); ++k)
    *fields[k] = number_attribute(attributes, initial_keys[k], "checkpoint");
  // The pressure workspace is derived state: recompute it (the rate pass of the next step does anyway).
  update_equation_of_state();
  force_rebuild_ = true;
}

void Simulation::update_equation_of_state(const ParticleSelection& selection) {
  auto scope = timers_.measure("equation_of_state");
  if (problem_.particles.solid_fields) {
    update_material_state(problem_.particles, problem_.materials, rate_workspace_, shear_modulus_, selection);
  } else {
    update_pressure(problem_.particles, equations_of_state_, rate_workspace_, selection);
  }
}

void Simulation::update_equation_of_state() {
  update_equation_of_state(ParticleSelection::all(problem_.particles.size()));
}

void Simulation::update_neighbours() {
  auto& p = problem_.particles;
  auto scope = timers_.measure("neighbours");
  // Only the active particles (ejecta are behind them) enter the search and hence the pair loops.
  const NeighbourInput input{std::span<const double>(p.x).first(active_),
                             std::span<const double>(p.y).first(active_),
                             std::span<const double>(p.z).first(active_),
                             std::span<const double>(p.smoothing_length).first(active_)};
  if (force_rebuild_ || search_.needs_rebuild(input)) {
    search_.build(input, problem_.box, lists_);
    ++rebuilds_;
    force_rebuild_ = false;
  }
}

void Simulation::update_neighbours(std::span<const std::uint32_t> queries) {
  auto& p = problem_.particles;
  auto scope = timers_.measure("neighbours");
  const NeighbourInput input{std::span<const double>(p.x).first(active_),
                             std::span<const double>(p.y).first(active_),
                             std::span<const double>(p.z).first(active_),
                             std::span<const double>(p.smoothing_length).first(active_)};
  const std::uint64_t before = search_.restructures();
  search_.build_for(input, problem_.box, queries, lists_, force_rebuild_);
  rebuilds_ += search_.restructures() - before;
  force_rebuild_ = false;
}

void Simulation::evaluate_rates() {
  const auto all = ParticleSelection::all(problem_.particles.size());
  update_neighbours();
  evaluate_rates(all, all);
}

void Simulation::evaluate_rates(const ParticleSelection& rates_for, const ParticleSelection& state_for) {
  auto& p = problem_.particles;
  if (config_.density == DensityMethod::summation) {
    auto scope = timers_.measure("density");
    compute_summation_density(p, PairList{lists_.offsets, lists_.neighbours}, config_.kernel,
                              rate_options_.period, rate_options_.mirror);
  }
  update_equation_of_state(state_for);
  {
    auto scope = timers_.measure("rates");
    rate_summary_ = compute_rates(p, PairList{lists_.offsets, lists_.neighbours}, rate_options_,
                                  rate_workspace_, rates_for, rate_options_.solid ? &gradients_ : nullptr);
    if (rate_options_.solid) compute_stress_rates(p, gradients_, shear_modulus_, rates_for);
    if (porous_) compute_distention_rates(p, problem_.materials, rates_for);
  }
}

TimeStepParameters Simulation::time_step_parameters() const {
  // After the switch the matrix law is energy-free: the specific energy no longer feeds back into the
  // pressure, and its relative-change limit (meant to resolve Tillotson's energy dependence) is dropped.
  TimeStepParameters parameters = config_.time_step;
  if (late_stage_active_) parameters.energy_change = 0.0;
  return parameters;
}

double Simulation::next_block_length() const {
  const auto& p = problem_.particles;
  double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
  for (std::size_t i = 0; i < active_; ++i) {
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    shortest = std::min(shortest, p.time_step[i]);
    longest = std::max(longest, p.time_step[i]);
  }
  if (!(longest > 0.0)) return std::min(shortest, config_.time_step.max_step);  // nothing moves
  const int levels = config_.time_step.block_levels;
  return std::min({longest, std::ldexp(shortest, levels), config_.time_step.max_step});
}

ParticleSelection Simulation::neighbourhood_of(std::span<const std::uint32_t> particles) {
  const std::size_t n = problem_.particles.size();
  needed_mark_.assign(n, 0);
  const auto count = static_cast<std::int64_t>(particles.size());
  std::uint8_t* mark = needed_mark_.data();
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t kk = 0; kk < count; ++kk) {
    const std::size_t i = particles[static_cast<std::size_t>(kk)];
    std::atomic_ref<std::uint8_t>(mark[i]).store(1, std::memory_order_relaxed);
    for (const std::uint32_t entry : lists_.of(i)) {
      std::atomic_ref<std::uint8_t>(mark[neighbour_index(entry)]).store(1, std::memory_order_relaxed);
    }
  }
  needed_list_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (mark[i] != 0) needed_list_.push_back(static_cast<std::uint32_t>(i));
  }
  return ParticleSelection::listed(needed_list_);
}

namespace {

// A collapsed block step, said with the particle and its limits (time_step.hpp), so that a user can tell
// where and why (a particle squeezed to nothing, a runaway acceleration, ...).
[[noreturn]] void throw_collapse(const TimeStepCollapse& collapse, const Particles& p,
                                 std::span<const double> signal_time, const TimeStepParameters& parameters,
                                 double time) {
  const std::size_t i = collapse.particle;
  const TimeStepLimits l = particle_time_step_limits(p, i, signal_time[i], parameters);
  const double speed = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  char text[512];
  std::snprintf(
      text, sizeof text,
      "%s, at t = %.6g s: particle id %llu (material %u) at (%.4g, %.4g, %.4g) m, density %.4g kg/m^3, "
      "smoothing length %.3g m, sound speed %.4g m/s, speed %.4g m/s; its limits (s): Courant %.3g, "
      "acceleration %.3g, density change %.3g, energy change %.3g, velocity change %.3g",
      collapse.what(), time, static_cast<unsigned long long>(p.id[i]), unsigned(p.material[i]), p.x[i],
      p.y[i], p.z[i], p.density[i], p.smoothing_length[i], p.sound_speed[i], speed, l.courant, l.acceleration,
      l.density, l.energy, l.velocity);
  throw std::runtime_error(text);
}

}  // namespace

void Simulation::advance_block(double block) {
  auto& p = problem_.particles;
  const auto all = ParticleSelection::all(p.size());
  const bool integrate_density = config_.density == DensityMethod::continuity;
  {
    auto scope = timers_.measure("integration");
    begin_step(p, integrator_workspace_, all);
  }
  // Lists of every particle at the start (the neighbour rule of the schedule), then of the active ones at
  // each substep (NeighbourSearch::build_for: the octree refit, not rebuilt).
  all_indices_.resize(active_);
  for (std::size_t i = 0; i < active_; ++i) all_indices_[i] = static_cast<std::uint32_t>(i);
  update_neighbours(all_indices_);
  {
    auto scope = timers_.measure("schedule");
    try {
      schedule_.start(block, p.time_step, p.flags, active_, lists_);
    } catch (const TimeStepCollapse& collapse) {
      throw_collapse(collapse, p, rate_workspace_.signal_time, time_step_parameters(), time_);
    }
  }
  const TimeStepParameters parameters = time_step_parameters();
  while (!schedule_.finished()) {
    double dt = 0.0;
    {
      auto scope = timers_.measure("schedule");
      dt = schedule_.advance();
    }
    {
      auto scope = timers_.measure("integration");
      drift(p, dt, problem_.box, config_.smoothing);
    }
    update_neighbours(schedule_.active());
    const auto active = ParticleSelection::listed(schedule_.active());
    ParticleSelection needed = all;
    {
      auto scope = timers_.measure("schedule");
      // The inactive neighbours of an active particle are read at their predicted state: their pressure,
      // sound speed and (for solids) returned stress must be of that state. Nobody else's is read.
      needed = neighbourhood_of(schedule_.active());
    }
    evaluate_rates(active, needed);
    {
      auto scope = timers_.measure("integration");
      correct(p, schedule_.active_steps(), active, integrator_workspace_, rate_workspace_.neighbour_count,
              config_.smoothing, integrate_density);
      if (porous_) limit_compaction(p, problem_.materials, integrator_workspace_.distention, active);
    }
    update_equation_of_state(active);
    particle_updates_ += active.size();
    {
      auto scope = timers_.measure("schedule");
      (void)update_time_steps(p, rate_workspace_.signal_time, parameters, active);
      if (!schedule_.finished()) {
        try {
          schedule_.relevel(p.time_step, lists_);
        } catch (const TimeStepCollapse& collapse) {
          throw_collapse(collapse, p, rate_workspace_.signal_time, parameters, time_ + schedule_.elapsed());
        }
        begin_step(p, integrator_workspace_, active);
      }
    }
  }
}

void Simulation::step(double target_time) {
  auto& p = problem_.particles;
  const auto& plan = problem_.late_stage;
  if (plan.planned() && !late_stage_active_ && plan.transition_time > time_) {
    target_time = std::min(target_time, plan.transition_time);
  }
  double dt = dt_next_;
  bool land = false;
  if (time_ + dt * (1.0 + 1e-9) >= target_time) {
    dt = target_time - time_;
    land = true;
  }
  if (!(dt > 0.0)) throw std::runtime_error("time step not positive at t = " + std::to_string(time_));

  const auto sort_interval = config_.neighbours.sort_interval;
  if (sort_interval > 0 && step_ % sort_interval == 0) {
    auto scope = timers_.measure("sort");
    curve_order(std::span<const double>(p.x).first(active_), std::span<const double>(p.y).first(active_),
                std::span<const double>(p.z).first(active_), order_);
    for (std::size_t k = active_; k < p.size(); ++k) order_.push_back(static_cast<std::uint32_t>(k));
    p.permute(order_);
    force_rebuild_ = true;
  }
  if (config_.time_step.block_levels > 0) {
    advance_block(dt);
  } else {
    {
      auto scope = timers_.measure("integration");
      predict(p, dt, problem_.box, integrator_workspace_, config_.smoothing);
    }
    evaluate_rates();
    {
      auto scope = timers_.measure("integration");
      correct(p, dt, integrator_workspace_, rate_workspace_.neighbour_count, config_.smoothing,
              config_.density == DensityMethod::continuity);
      if (porous_) {
        limit_compaction(p, problem_.materials, integrator_workspace_.distention,
                         ParticleSelection::all(p.size()));
      }
    }
    update_equation_of_state();
    particle_updates_ += active_;
  }
  // Every particle's own step limit, before ejection reorders the particles (the signal times of the
  // rate pass are per index).
  limits_ = update_time_steps(p, rate_workspace_.signal_time, time_step_parameters(),
                              ParticleSelection::all(p.size()));
  time_ = land ? target_time : time_ + dt;
  ++step_;
  if (reflect_across_mirror_planes(p, problem_.box) > 0) force_rebuild_ = true;
  eject();
  const auto mach = [&] {
    auto scope = timers_.measure("diagnostics");
    return max_mach_number(p.vx, p.vy, p.vz, p.sound_speed, p.flags).value;
  };
  if (plan.planned() && !late_stage_active_ && time_ >= plan.transition_time) {
    carry_stress_across_switch(switch_to_late_stage());
    if (rate_options_.solid) {
      update_equation_of_state();  // the switched shear moduli per particle
      cap_elastic_shear_strain();
    }
    // The integrator reuses the rates of this evaluation in the next step: they must be the switched
    // medium's (evaluate_rates() evaluates the equation of state first).
    evaluate_rates();
    limits_ = update_time_steps(p, rate_workspace_.signal_time, time_step_parameters(),
                                ParticleSelection::all(p.size()));
    mach_at_transition_ = mach();
    late_stage_max_mach_ = mach_at_transition_;
  } else if (late_stage_active_) {
    late_stage_max_mach_ = std::max(late_stage_max_mach_, mach());
  }
  dt_next_ = next_block_length();
  if (!(dt_next_ > 0.0) || !std::isfinite(dt_next_)) {
    throw std::runtime_error("time step collapsed to " + std::to_string(dt_next_) +
                             " s at t = " + std::to_string(time_) + " s, step " + std::to_string(step_) +
                             " (limits: courant " + std::to_string(limits_.courant) + ", acceleration " +
                             std::to_string(limits_.acceleration) + ", density " +
                             std::to_string(limits_.density) + ", energy " + std::to_string(limits_.energy) +
                             ", velocity " + std::to_string(limits_.velocity) + ")");
  }
}

double Simulation::mean_neighbours() const {
  std::size_t active = 0;
  for (const auto f : problem_.particles.flags)
    active += (f & (particle_fixed | particle_ejected)) == 0 ? 1 : 0;
  return active == 0 ? 0.0
                     : static_cast<double>(rate_summary_.interacting_pairs) / static_cast<double>(active);
}

ConservedQuantities Simulation::conserved() const {
  auto q = measure_conserved(problem_.particles, config_.run.gravity);
  q.time = time_;
  q.step = step_;
  return q;
}

double Simulation::bytes_per_particle() const {
  const auto n = problem_.particles.size();
  if (n == 0) return 0.0;
  std::size_t bytes = 0;
  problem_.particles.for_each_field([&](std::string_view, const auto& field) {
    bytes += field.capacity() * sizeof(typename std::decay_t<decltype(field)>::value_type);
  });
  bytes += lists_.bytes() + search_.workspace_bytes();
  const auto& w = integrator_workspace_;
  for (const auto* v :
       {&w.acceleration_x, &w.acceleration_y, &w.acceleration_z, &w.density_rate, &w.energy_rate,
        &w.viscosity_alpha_rate, &w.stress_rate_xx, &w.stress_rate_xy, &w.stress_rate_xz, &w.stress_rate_yy,
        &w.stress_rate_yz, &w.total_strain_rate, &w.distention_rate, &w.distention, &shear_modulus_}) {
    bytes += v->capacity() * sizeof(double);
  }
  for (const auto& v : gradients_.corrected) bytes += v.capacity() * sizeof(double);
  for (const auto& v : rate_workspace_.stress_force) bytes += v.capacity() * sizeof(double);
  bytes += rate_workspace_.inverse_density.capacity() * sizeof(double);
  bytes += rate_workspace_.volume.capacity() * sizeof(double);
  bytes += order_.capacity() * sizeof(std::uint32_t);
  return static_cast<double>(bytes) / static_cast<double>(n);
}

RunAttributes Simulation::attributes() const {
  RunAttributes a;
  a.time = time_;
  a.step = step_;
  a.numbers["next_time_step"] = dt_next_;
  auto initial = initial_;
  auto fields = initial_fields(initial);
  for (std::size_t k = 0; k < fields.size(); ++k) a.numbers[initial_keys[k]] = *fields[k];
  a.texts["problem_name"] = config_.name;
  a.texts["setup"] = setup_name(config_.setup);
  for (const auto& [key, value] : problem_.attributes.numbers) a.numbers[key] = value;
  for (const auto& [key, value] : problem_.attributes.texts) a.texts[key] = value;
  if (late_stage_active_) {
    record_late_stage(
        a, {problem_.late_stage.transition_time, problem_.late_stage.A_low[0], mach_at_transition_});
    a.numbers["late_stage_max_mach"] = late_stage_max_mach_;
  }
  return a;
}

SimulationSummary run_simulation(const SimulationConfig& config, const RunOptions& options) {
  namespace fs = std::filesystem;
  const auto wall_start = std::chrono::steady_clock::now();
  const bool files = !options.output_directory.empty();
  const fs::path out = options.output_directory;
  const fs::path checkpoint_path = out / "checkpoint.h5";
  if (files) fs::create_directories(out);

  SimulationSummary summary;
  summary.name = config.name;
  summary.setup = setup_name(config.setup);
  summary.threads = omp_get_max_threads();

  Scenario scenario = build_scenario(config);
  if (options.log && scenario.impact) std::fprintf(stderr, "%s", describe_impact(*scenario.impact).c_str());
  // The crater measurement's settings (boulders are found in the initial particle set).
  CraterMeasurementOptions measurement;
  if (scenario.impact) {
    measurement.rho_initial = scenario.impact->initial_bulk_density;
    measurement.particle_spacing = scenario.impact->particle_spacing;
    if (scenario.impact->graded) {  // the local spacing of a graded target (graded_spacing.hpp)
      measurement.inner_spacing = scenario.impact->inner_spacing;
      measurement.inner_radius = scenario.impact->inner_radius;
      measurement.grading = scenario.impact->grading;
    }
    measurement.kernel = config.kernel;
    measurement.quarter_symmetric = scenario.impact->symmetry == DomainSymmetry::quarter;
    measurement.boulders = impact_boulder_specs(scenario.problem.particles, *scenario.impact);
    // Rays end at the inner face of the fixed shell (the default, from the particles' extent and the
    // largest h, is thrown off by isolated particles with large h above the target).
    measurement.max_radius = scenario.impact->domain_radius - scenario.impact->fixed_shell_thickness;
  }
  ProblemSetup problem = std::move(scenario.problem);
  std::unique_ptr<Simulation> sim;
  std::size_t next_snapshot = 0;
  if (files && options.resume && fs::exists(checkpoint_path)) {
    RunAttributes attributes;
    Particles particles = read_checkpoint(checkpoint_path, &attributes);
    const auto setup = attributes.texts.find("setup");
    if (setup == attributes.texts.end() || setup->second != summary.setup) {
      throw InputError(checkpoint_path.string() + ": checkpoint of a different problem (setup \"" +
                       (setup == attributes.texts.end() ? std::string("?") : setup->second) +
                       "\", configuration: \"" + summary.setup + "\")");
    }
    next_snapshot =
        static_cast<std::size_t>(number_attribute(attributes, "next_snapshot", checkpoint_path.string()));
    sim = std::make_unique<Simulation>(config, std::move(problem), std::move(particles), attributes);
    summary.resumed = true;
  } else {
    sim = std::make_unique<Simulation>(config, std::move(problem));
  }
  auto& timers = sim->timers();
  const auto& snapshot_times = config.output.snapshot_times;

  std::unique_ptr<ConservationLog> log;
  if (files && config.output.conservation_log) {
    const fs::path csv = out / "conservation.csv";
    if (summary.resumed) {
      log = std::make_unique<ConservationLog>(csv, sim->step_count());
    } else {
      log = std::make_unique<ConservationLog>(csv);
      log->append(sim->conserved());
    }
    summary.conservation_log = csv.string();
  }

  std::unique_ptr<StepCsvLog> ejecta_log;
  if (files && sim->problem().ejection.radius > 0.0) {
    ejecta_log =
        std::make_unique<StepCsvLog>(out / "ejecta.csv", ejecta_csv_header(), ejecta_csv_step_column,
                                     summary.resumed ? static_cast<std::int64_t>(sim->step_count()) : -1);
    summary.ejecta_log = ejecta_log->path().string();
  }

  // End of crater growth (impact runs): samples every check interval, logged to crater_growth.csv so
  // that a resumed run continues with the same history.
  std::vector<CraterGrowthSample> growth;
  std::unique_ptr<StepCsvLog> growth_log;
  const double check_interval =
      config.crater.check_interval > 0.0 ? config.crater.check_interval : config.run.end_time / 200.0;
  double next_check = 0.0;
  if (scenario.impact && files) {
    growth_log =
        std::make_unique<StepCsvLog>(out / "crater_growth.csv", "time,step,crater_radius,kinetic_energy", 1,
                                     summary.resumed ? static_cast<std::int64_t>(sim->step_count()) : -1);
    for (const auto& row : growth_log->kept_rows()) {
      growth.push_back({std::stod(row[0]), std::stoull(row[1]), std::stod(row[2]), std::stod(row[3])});
    }
    if (!growth.empty()) next_check = growth.back().time + check_interval;
  }
  CraterGrowthCriteria criteria;
  criteria.radius_tolerance = config.crater.radius_tolerance;
  criteria.kinetic_energy_fraction = config.crater.kinetic_energy_fraction;
  criteria.window_fraction = config.crater.window_fraction;
  auto check_crater_growth = [&]() {
    if (!scenario.impact || sim->time() < next_check) return false;
    auto scope = sim->timers().measure("crater");
    // The radius alone (the mean of the +-x and +-y rays): the four axis rays, which are the same sample
    // columns as in the full measurement (its azimuths are multiples of 2 pi / n_azimuths), so the
    // same radius at a sixteenth of the cost.
    CraterMeasurementOptions axes = measurement;
    axes.n_azimuths = 4;
    const CraterMeasurement m = measure_crater(sim->particles(), axes);
    const CraterGrowthSample sample{sim->time(), sim->step_count(), m.crater_radius,
                                    moving_kinetic_energy(sim->particles())};
    growth.push_back(sample);
    if (growth_log) {
      char row[256];
      std::snprintf(row, sizeof row, "%.17g,%llu,%.17g,%.17g", sample.time,
                    static_cast<unsigned long long>(sample.step), sample.radius, sample.kinetic_energy);
      growth_log->append(row);
    }
    next_check = sample.time + check_interval;
    return config.crater.stop_when_grown && crater_growth_ended(growth, criteria);
  };

  auto write_checkpoint_now = [&](std::size_t snapshot_index) {
    if (!files) return;
    auto scope = timers.measure("output");
    RunAttributes a = sim->attributes();
    a.numbers["next_snapshot"] = static_cast<double>(snapshot_index);
    write_checkpoint(checkpoint_path, sim->particles(), a);
    sim->force_neighbour_rebuild();
    summary.checkpoint = checkpoint_path.string();
  };
  auto write_snapshot_now = [&](std::size_t index) {
    if (!files) return;
    auto scope = timers.measure("output");
    char name[32];
    std::snprintf(name, sizeof name, "snap_%06zu.h5", index);
    RunAttributes a = sim->attributes();
    write_snapshot(out / name, sim->particles(), a);
    write_time_series_xdmf(out / "snapshots.xdmf", find_snapshots(out));
    summary.snapshots.push_back((out / name).string());
  };

  // Snapshots at t = 0 (and any requested time already reached).
  while (!summary.resumed && next_snapshot < snapshot_times.size() &&
         snapshot_times[next_snapshot] <= sim->time()) {
    write_snapshot_now(next_snapshot++);
  }

  ProgressOptions progress_options;
  progress_options.enabled = options.progress;
  progress_options.end_time = config.run.end_time;
  if (sim->problem().late_stage.planned())
    progress_options.stage_end_time = sim->problem().late_stage.transition_time;
  Progress progress(progress_options);

  const std::uint64_t first_step = sim->step_count();
  const std::uint64_t first_updates = sim->particle_updates();
  auto last_checkpoint_wall = std::chrono::steady_clock::now();
  const auto& p = sim->particles();
  if (!summary.resumed) {
    summary.crater_growth_ended = check_crater_growth();
  } else {
    summary.crater_growth_ended = config.crater.stop_when_grown && crater_growth_ended(growth, criteria);
  }
  while (!summary.crater_growth_ended && sim->time() < config.run.end_time &&
         (config.run.max_steps == 0 || sim->step_count() < config.run.max_steps)) {
    double target = config.run.end_time;
    if (next_snapshot < snapshot_times.size()) target = std::min(target, snapshot_times[next_snapshot]);
    const bool was_late = sim->late_stage_active();
    const double dt_before = sim->next_time_step();
    sim->step(target);
    if (!was_late && sim->late_stage_active() && options.log) {
      std::fprintf(
          stderr,
          "\nlate stage: switched to the low-sound-speed medium at t = %.6g s (step %llu), A_low = %.6g "
          "Pa; largest Mach number |v|/c just after the switch %.4g; time step %.4g s -> %.4g s\n",
          sim->time(), static_cast<unsigned long long>(sim->step_count()), sim->problem().late_stage.A_low[0],
          sim->mach_at_transition(), dt_before, sim->next_time_step());
    }
    if (ejecta_log) {
      auto scope = timers.measure("output");
      for (const auto& record : sim->take_new_ejecta()) ejecta_log->append(ejecta_csv_row(record));
    } else {
      (void)sim->take_new_ejecta();
    }
    if (log) {
      auto scope = timers.measure("output");
      log->append(sim->conserved());
    }
    while (next_snapshot < snapshot_times.size() && snapshot_times[next_snapshot] <= sim->time()) {
      write_snapshot_now(next_snapshot++);
    }
    const auto now = std::chrono::steady_clock::now();
    const bool by_steps = config.output.checkpoint_interval_steps > 0 &&
                          sim->step_count() % config.output.checkpoint_interval_steps == 0;
    const bool by_wall = config.output.checkpoint_interval_seconds > 0 &&
                         std::chrono::duration<double>(now - last_checkpoint_wall).count() >=
                             config.output.checkpoint_interval_seconds;
    if (by_steps || by_wall) {
      write_checkpoint_now(next_snapshot);
      last_checkpoint_wall = now;
    }
    summary.crater_growth_ended = check_crater_growth();
    progress.update(sim->time(), sim->step_count(), sim->next_time_step(), sim->particle_updates());
  }
  progress.finish(sim->time(), sim->step_count(), sim->next_time_step(), sim->particle_updates());

  // The final state: a snapshot (unless one was just written at this time) and a checkpoint, so that
  // --resume of a finished run does nothing and a longer end_time continues it.
  if (files) {
    const bool written =
        !snapshot_times.empty() && next_snapshot > 0 && snapshot_times[next_snapshot - 1] == sim->time();
    if (!written) write_snapshot_now(std::max<std::size_t>(next_snapshot, snapshot_times.size()));
    write_checkpoint_now(next_snapshot);
  }

  if (sim->problem().late_stage.planned()) {
    summary.transition_time = sim->problem().late_stage.transition_time;
    summary.late_stage = sim->late_stage_active();
    summary.mach_at_transition = sim->mach_at_transition();
    summary.late_stage_max_mach = sim->late_stage_max_mach();
    if (summary.late_stage && options.log) {
      std::fprintf(stderr,
                   "late stage: largest Mach number |v|/c since the switch %.4g (at the switch %.4g)\n",
                   summary.late_stage_max_mach, summary.mach_at_transition);
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) == 0) continue;
    ++summary.ejected_particles;
    summary.ejected_mass += p.mass[i];
  }
  if (scenario.impact) {
    auto scope = timers.measure("crater");
    if (const auto k = first_sample_of_ended_growth(growth, criteria)) {
      summary.crater_growth_end_time = growth[*k].time;
      summary.crater_growth_end_radius = growth[*k].radius;
    }
    summary.crater = measure_crater(p, measurement);
    if (files) {
      write_crater_files(out, *summary.crater, sim->time());
      summary.crater_json = (out / "crater.json").string();
    }
    if (options.log) {
      std::fprintf(stderr, "crater: radius %.4g +- %.2g m at t = %.6g s%s\n", summary.crater->crater_radius,
                   summary.crater->crater_radius_uncertainty, sim->time(),
                   summary.crater_growth_ended ? " (growth ended)" : "");
    }
  }
  const auto final_state = sim->conserved();
  summary.particles = p.size();
  summary.steps = sim->step_count();
  summary.steps_this_run = sim->step_count() - first_step;
  summary.time = sim->time();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  summary.particle_updates = sim->particle_updates() - first_updates;
  summary.particle_updates_per_second =
      summary.wall_seconds > 0 ? static_cast<double>(summary.particle_updates) / summary.wall_seconds : 0.0;
  summary.mean_neighbours = sim->mean_neighbours();
  summary.relative_energy_error = relative_energy_error(sim->initial_conserved(), final_state);
  summary.relative_momentum_error = relative_momentum_error(sim->initial_conserved(), final_state);
  const auto& gravity = sim->config().run.gravity;
  const bool has_fixed =
      std::any_of(p.flags.begin(), p.flags.end(), [](std::uint8_t f) { return (f & particle_fixed) != 0; });
  summary.momentum_conserved = gravity[0] == 0.0 && gravity[1] == 0.0 && gravity[2] == 0.0 && !has_fixed &&
                               !mirror_planes(sim->box()).any();
  summary.bytes_per_particle = sim->bytes_per_particle();
  summary.neighbour_rebuilds = sim->neighbour_rebuilds();
  summary.phase_seconds = timers.seconds_by_phase();
  summary.phase_table = timers.table();
  return summary;
}

}  // namespace craterkit::sph
