#include "craterkit/sph/solver/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/neighbours/mirror_reflection.hpp"
#include "craterkit/sph/neighbours/pair_support.hpp"
#include "craterkit/sph/particles/space_filling_curve.hpp"
#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/late_stage.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/rates/rates_pressure.hpp"
#include "craterkit/sph/solver/mach_number.hpp"

namespace craterkit::sph {

namespace {

std::array<double, 3> periods(const Box& box) {
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (int a = 0; a < 3; ++a) out[a] = box.periodic[a] ? box.edge(a) : 0.0;
  return out;
}

// A distributed run with one global step finds its halos anew at every evaluation, so it cannot keep its
// lists from step to step: it builds them without a skin (which would only lengthen them), in the search's
// curve order, as a serial run with skin 0 does (docs/parallel.md, "Serial or round-off").
NeighbourSearchOptions search_options(const SolverParameters& parameters,
                                      const Decomposition* decomposition) {
  NeighbourSearchOptions options = parameters.neighbours.search;
  if (decomposition != nullptr && parameters.time_step.block_levels == 0) options.skin = 0.0;
  return options;
}

// Particles::peak_pressure of the active particles, from their states at the end of the step: the corrected
// state, whose pressure the equation of state has just refreshed (predicted states do not count).
void record_peak_pressure(Particles& p, const ParticleSelection& active) {
  for (std::size_t k = 0; k < active.size(); ++k) {
    const std::size_t i = active.at(k);
    p.peak_pressure[i] = std::max(p.peak_pressure[i], p.pressure[i]);
  }
}

}  // namespace

void Simulation::configure() {
  for (const auto& m : problem_.materials) equations_of_state_.push_back(m.eos);
  rate_options_.kernel = parameters_.kernel;
  rate_options_.viscosity = parameters_.viscosity;
  rate_options_.artificial_stress = {parameters_.artificial_stress, 1.0 / parameters_.smoothing.eta};
  rate_options_.gravity = parameters_.gravity;
  rate_options_.period = periods(problem_.box);
  rate_options_.mirror = mirror_planes(problem_.box);
  rate_options_.solid = false;
  porous_ = false;
  for (const auto& m : problem_.materials) {
    rate_options_.solid = rate_options_.solid || m.strength.has_value();
    porous_ = porous_ || m.porosity.has_value();
  }
  if (rate_options_.artificial_stress.on() && !rate_options_.solid) {
    throw InputError("artificial_stress.epsilon = " + format_number(parameters_.artificial_stress) +
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
    // Throws for gases.
    switched.push_back(late_stage_material(problem_.materials[id], plan.A_low[id], plan.tensile_porosity));
    stress_factor.push_back(std::sqrt(plan.A_low[id] / reference->bulk_modulus));
  }
  problem_.materials = std::move(switched);
  equations_of_state_.clear();
  for (const auto& m : problem_.materials) equations_of_state_.push_back(m.eos);
  late_stage_active_ = true;
  // The neighbour rule of the block steps as Saitoh & Makino (2009) give it, a factor 4 between neighbours'
  // steps, from the next block on. The shock stage keeps a factor 2: with 4 the SCI run's energy error rises
  // from 2.5e-4 to 4.1e-4 in the first millisecond (the contact), while after the switch the energy-free
  // medium of the late stage loses nothing by it and the particles thrown out of the fine core hold fewer
  // neighbours to their short steps (docs/physics.md section 1.12).
  schedule_.set_neighbour_levels(2);
  return stress_factor;
}

void Simulation::carry_stress_across_switch(const std::vector<double>& stress_factor) {
  auto& p = problem_.particles;
  const auto n = static_cast<std::int64_t>(active_);  // ejected particles stay as they left
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
    // Matrix pressure P_m = alpha P (P-alpha, docs/physics.md section 2) from the new law
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
  const auto n = static_cast<std::int64_t>(active_);
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
  if (decomposition_ != nullptr) {
    if (!(problem_.ejection.radius > 0.0)) return;  // alike on every process
    std::vector<EjectaRecord> records;              // recorded on process 0, from what it receives
    const std::size_t flagged =
        eject_particles(p, problem_.ejection, rate_workspace_.neighbour_count, time_, step_, records);
    if (!any_process(flagged > 0)) return;
    Particles leaving = decomposition_->collect_flagged(p, particle_ejected);
    for (std::size_t k = 0; k < leaving.size(); ++k)
      new_ejecta_.push_back(ejecta_record(leaving, k, time_, step_));
    if (ejected_.size() == 0) {
      ejected_ = std::move(leaving);
    } else {
      ejected_.append(leaving);
    }
    active_ = p.size();
    force_rebuild_ = true;
    return;
  }
  if (eject_particles(p, problem_.ejection, rate_workspace_.neighbour_count, time_, step_, new_ejecta_) == 0)
    return;
  order_ = ejected_last_order(p, &active_);
  p.permute(order_);
  // Kept lists lose the ejecta and are renumbered; lists of the global step are built afresh.
  if (!search_.remove_particles(order_, active_, lists_)) force_rebuild_ = true;
}

void Simulation::add_halos(double skin, double lookahead) {
  auto& p = problem_.particles;
  auto scope = timers_.measure("halos");
  const std::size_t owned_count = p.size();
  // Each particle's allowed motion: the skin, plus how far it goes in `lookahead` at its present velocity
  // and acceleration (the fast particles, few, would otherwise outgrow a skin of their h at once).
  halo_margin_.resize(owned_count);
  halo_reach_.resize(owned_count);
  for (std::size_t i = 0; i < owned_count; ++i) {
    const double speed = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    const double acceleration =
        std::sqrt(p.acceleration_x[i] * p.acceleration_x[i] + p.acceleration_y[i] * p.acceleration_y[i] +
                  p.acceleration_z[i] * p.acceleration_z[i]);
    halo_margin_[i] = skin * p.smoothing_length[i] + lookahead * (speed + 0.5 * lookahead * acceleration);
    halo_reach_[i] = p.smoothing_length[i] + halo_margin_[i];
  }
  owned_ = decomposition_->add_halos(p, halo_reach_, rate_options_.period);
  active_ = p.size();
  force_rebuild_ = true;
  // The per-particle values a particle keeps from one evaluation or step start to the next (block time
  // steps: an inactive particle's results, an active one's rates at its step's start) move with it to the
  // owned range; the halos' entries are filled anew.
  const auto place_owned = [&](auto& values) {
    if (values.size() != owned_count) return;
    values.insert(values.begin(), owned_.begin, typename std::decay_t<decltype(values)>::value_type{});
    values.resize(p.size());
  };
  place_owned(rate_workspace_.neighbour_count);
  place_owned(rate_workspace_.signal_time);
  place_owned(shear_modulus_);
  integrator_workspace_.for_each_array(place_owned);
  owned_list_.resize(owned_.size());
  for (std::size_t k = 0; k < owned_.size(); ++k)
    owned_list_[k] = static_cast<std::uint32_t>(owned_.begin + k);
  halo_skin_ = skin;
  halo_lookahead_ = lookahead;
  for (auto* anchor : {&halo_anchor_x_, &halo_anchor_y_, &halo_anchor_z_, &halo_anchor_h_})
    anchor->resize(owned_.size());
  for (std::size_t k = 0; k < owned_.size(); ++k) {
    halo_anchor_x_[k] = p.x[owned_.begin + k];
    halo_anchor_y_[k] = p.y[owned_.begin + k];
    halo_anchor_z_[k] = p.z[owned_.begin + k];
    halo_anchor_h_[k] = p.smoothing_length[owned_.begin + k];
  }
}

bool Simulation::halos_outgrown() const {
  // No particle j of another process came within h_i + h_j of an owned i unseen while every particle, here
  // and there, has |x - X| + max(0, h - H) <= m since the halos were found at (X, H) with the reach
  // (H_i + m_i) + (H_j + m_j): the triangle inequality, as for the search's kept lists
  // (neighbour_search.hpp).
  const auto& p = problem_.particles;
  const auto& period = rate_options_.period;
  const auto minimum_image = [&](double d, int axis) {
    return period[axis] > 0.0 ? d - period[axis] * std::nearbyint(d / period[axis]) : d;
  };
  const auto n = static_cast<std::int64_t>(owned_.size());
  int outgrown = 0;
#pragma omp parallel for schedule(static) reduction(max : outgrown)
  for (std::int64_t kk = 0; kk < n; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    const std::size_t i = owned_.begin + k;
    const double dx = minimum_image(p.x[i] - halo_anchor_x_[k], 0);
    const double dy = minimum_image(p.y[i] - halo_anchor_y_[k], 1);
    const double dz = minimum_image(p.z[i] - halo_anchor_z_[k], 2);
    const double moved =
        std::sqrt(dx * dx + dy * dy + dz * dz) + std::max(0.0, p.smoothing_length[i] - halo_anchor_h_[k]);
    if (moved > halo_margin_[k]) outgrown = 1;
  }
  return any_process(outgrown != 0);
}

void Simulation::keep_halos(std::span<const std::string_view> changed_fields) {
  if (halos_outgrown()) {
    drop_halos();
    add_halos(halo_skin_, halo_lookahead_);  // copies of every field
    ++halos_found_anew_;
    return;
  }
  auto scope = timers_.measure("halos");
  decomposition_->refresh_halos(problem_.particles, changed_fields);
}

void Simulation::take_share_of_the_particles() {
  if (decomposition_ == nullptr) return;
  auto& p = problem_.particles;
  // Ejected particles (of a checkpoint; configure() put them last) are nobody's share: process 0 keeps them,
  // as it keeps every later ejection.
  if (active_ < p.size()) {
    if (decomposition_->rank() == 0) {
      std::vector<std::uint32_t> ejected_first;
      for (std::size_t i = active_; i < p.size(); ++i) ejected_first.push_back(static_cast<std::uint32_t>(i));
      for (std::size_t i = 0; i < active_; ++i) ejected_first.push_back(static_cast<std::uint32_t>(i));
      ejected_ = p;
      ejected_.permute(ejected_first);
      ejected_.resize(p.size() - active_);
    }
    p.resize(active_);
  }
  decomposition_->take_share(p);
  const std::vector<double> equal_work(p.size(), 1.0);
  decomposition_->distribute(p, equal_work);
  active_ = p.size();
}

const Particles& Simulation::whole_particles(Particles& gathered) {
  if (decomposition_ == nullptr) return problem_.particles;
  gathered = decomposition_->gather(problem_.particles);
  if (ejected_.size() > 0)
    gathered.append(ejected_);  // process 0 only: behind the others, as in a serial run
  return gathered;
}

bool Simulation::any_process(bool value) const {
  if (decomposition_ == nullptr) return value;
  std::array<double, 1> none{value ? 0.0 : 1.0};
  decomposition_->min(none);
  return none[0] == 0.0;
}

double Simulation::least_over_processes(double value) const {
  std::array<double, 1> least{value};
  if (decomposition_ != nullptr) decomposition_->min(least);
  return least[0];
}

std::size_t Simulation::total_particles() const {
  if (decomposition_ == nullptr) return problem_.particles.size();
  std::array<double, 1> count{static_cast<double>(problem_.particles.size() + ejected_.size())};
  decomposition_->sum(count);
  return static_cast<std::size_t>(count[0]);
}

void Simulation::drop_halos() {
  auto scope = timers_.measure("halos");
  const auto keep_owned = [this](auto& values) {
    if (values.size() < owned_.end) return;
    values.erase(values.begin() + static_cast<std::ptrdiff_t>(owned_.end), values.end());
    values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(owned_.begin));
  };
  keep_owned(rate_workspace_.neighbour_count);
  keep_owned(rate_workspace_.signal_time);
  keep_owned(shear_modulus_);
  integrator_workspace_.for_each_array(keep_owned);
  decomposition_->remove_halos(problem_.particles);
  active_ = problem_.particles.size();
  owned_ = {0, active_};
  force_rebuild_ = true;
}

Simulation::Simulation(SolverParameters parameters, ProblemSetup problem, Decomposition* decomposition)
    : parameters_(std::move(parameters)),
      problem_(std::move(problem)),
      search_(search_options(parameters_, decomposition)),
      decomposition_(decomposition) {
  configure();
  take_share_of_the_particles();
  update_smoothing_length(problem_.particles, parameters_.smoothing);
  if (rate_options_.solid) {
    // The first force needs the correction matrices of the initial state (later ones come from the rate
    // pass before, gradient_correction.hpp). Distributed: the owners' matrices reach the halos with the
    // particles in the first rate evaluation.
    if (decomposition_ != nullptr) add_halos(exact_halo_skin, 0.0);
    update_neighbours();
    update_equation_of_state();
    const auto owned = decomposition_ != nullptr ? ParticleSelection::listed(owned_list_)
                                                 : ParticleSelection::all(problem_.particles.size());
    compute_correction_matrices(problem_.particles, PairList{lists_.offsets, lists_.neighbours, lists_.ends},
                                rate_options_, rate_workspace_, owned);
    if (decomposition_ != nullptr) drop_halos();
  }
  evaluate_rates();
  limits_ = update_time_steps(problem_.particles, rate_workspace_.signal_time, time_step_parameters(),
                              ParticleSelection::all(problem_.particles.size()));
  dt_next_ = next_block_length();
  initial_ = conserved();
}

Simulation::Simulation(SolverParameters parameters, ProblemSetup problem, Particles particles,
                       const SolverState& state, Decomposition* decomposition)
    : parameters_(std::move(parameters)),
      problem_(std::move(problem)),
      search_(search_options(parameters_, decomposition)),
      decomposition_(decomposition) {
  problem_.particles = std::move(particles);
  configure();
  take_share_of_the_particles();
  for (const auto id : problem_.particles.material) {
    if (id >= problem_.materials.size()) {
      throw InputError("checkpoint: material id " + std::to_string(id) + " not defined by the configuration");
    }
  }
  time_ = state.time;
  step_ = state.step;
  dt_next_ = state.next_time_step;
  if (state.late_stage_active) {
    if (!problem_.late_stage.planned()) {
      throw InputError("checkpoint: written after a late-stage switch, but the configuration plans none");
    }
    switch_to_late_stage();
    mach_at_transition_ = state.mach_at_transition;
    late_stage_max_mach_ = state.late_stage_max_mach;
  }
  initial_ = state.initial;
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
  update_equation_of_state(ParticleSelection::all(active_));  // ejected particles stay as they left
}

NeighbourInput Simulation::searched_input() const {
  const auto& p = problem_.particles;
  return {std::span<const double>(p.x).first(active_), std::span<const double>(p.y).first(active_),
          std::span<const double>(p.z).first(active_),
          std::span<const double>(p.smoothing_length).first(active_)};
}

void Simulation::update_neighbours() {
  // One global step with a skin: the lists are kept and searched again only for the particles that left
  // it, sorted by entry (NeighbourSearch::update), so that the sums do not depend on when a list was
  // searched: a resumed run adds the same terms in the same order as the run it continues. (Block time steps
  // keep their lists themselves; this serves only their first and switch evaluations. A distributed run with
  // one global step finds its halos anew at every evaluation and builds its lists without a skin,
  // search_options().)
  if (search_.options().skin > 0.0 && parameters_.time_step.block_levels == 0) {
    keep_neighbours();
    return;
  }
  auto scope = timers_.measure("neighbours");
  const NeighbourInput input = searched_input();
  if (force_rebuild_ || search_.needs_rebuild(input)) {
    search_.build(input, problem_.box, lists_);
    ++rebuilds_;
    force_rebuild_ = false;
  }
}

void Simulation::keep_neighbours() {
  auto scope = timers_.measure("neighbours");
  const NeighbourInput input = searched_input();
  const std::uint64_t before = search_.restructures();
  search_.update(input, problem_.box, lists_, force_rebuild_);
  rebuilds_ += search_.restructures() - before;
  force_rebuild_ = false;
}

void Simulation::renew_skin_bounds(const ParticleSelection& selection) {
  const auto& p = problem_.particles;
  const double now = schedule_.elapsed();
  const auto count = static_cast<std::int64_t>(selection.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t kk = 0; kk < count; ++kk) {
    const std::size_t i = selection.at(static_cast<std::size_t>(kk));
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) {
      within_skin_until_[i] = std::numeric_limits<double>::infinity();  // not drifted
      continue;
    }
    const double room = search_.room(i, p.x[i], p.y[i], p.z[i], p.smoothing_length[i], problem_.box);
    within_skin_until_[i] = now + drift_time_within(p, i, room);
  }
}

void Simulation::keep_neighbours_within_bounds() {
  auto scope = timers_.measure("neighbours");
  const NeighbourInput input = searched_input();
  const double now = schedule_.elapsed();
  expired_.clear();
  for (std::size_t i = 0; i < active_; ++i) {
    if (!(now < within_skin_until_[i])) expired_.push_back(static_cast<std::uint32_t>(i));
  }
  if (search_.update_moved(input, problem_.box, lists_, expired_)) {
    renew_skin_bounds(ParticleSelection::listed(expired_));
    return;
  }
  const std::uint64_t before = search_.restructures();
  search_.update(input, problem_.box, lists_, true);
  rebuilds_ += search_.restructures() - before;
  renew_skin_bounds(ParticleSelection::all(active_));
}

void Simulation::evaluate_rates() {
  if (decomposition_ == nullptr) {
    const auto all = ParticleSelection::all(active_);  // ejected particles stay as they left
    update_neighbours();
    evaluate_rates(all, all);
    return;
  }
  // The halos' own state (equation of state, returns) is evaluated here as their owners evaluate it, from
  // the same values: the rates of the owned particles then read what the serial run reads.
  add_halos(exact_halo_skin, 0.0);
  update_neighbours();
  evaluate_rates(ParticleSelection::listed(owned_list_), ParticleSelection::all(problem_.particles.size()));
  drop_halos();
}

void Simulation::evaluate_rates(const ParticleSelection& rates_for, const ParticleSelection& state_for) {
  auto& p = problem_.particles;
  if (parameters_.density == DensityMethod::summation) {
    auto scope = timers_.measure("density");
    compute_summation_density(p, PairList{lists_.offsets, lists_.neighbours, lists_.ends}, parameters_.kernel,
                              rate_options_.period, rate_options_.mirror);
    scope.stop();
    if (decomposition_ != nullptr) {
      // A halo's sum misses the neighbours its owner has and this process has not: take the owner's.
      auto halo_scope = timers_.measure("halos");
      constexpr std::array<std::string_view, 1> summed{"density"};
      decomposition_->refresh_halos(p, summed);
    }
  }
  update_equation_of_state(state_for);
  {
    auto scope = timers_.measure("rates");
    const PairList pairs{lists_.offsets, lists_.neighbours, lists_.ends};
    // Solids: the pair pass writes the stress rates itself, so that no velocity gradient is held.
    rate_summary_ = rate_options_.solid
                        ? compute_rates_and_stress_rates(p, pairs, rate_options_, rate_workspace_, rates_for,
                                                         shear_modulus_, problem_.materials, &state_for)
                        : compute_rates(p, pairs, rate_options_, rate_workspace_, rates_for);
    if (porous_) compute_distention_rates(p, problem_.materials, rates_for);
  }
}

TimeStepParameters Simulation::time_step_parameters() const {
  // After the switch the matrix law is energy-free: the specific energy no longer feeds back into the
  // pressure, and its relative-change limit (meant to resolve Tillotson's energy dependence) is dropped.
  TimeStepParameters parameters = parameters_.time_step;
  if (late_stage_active_) parameters.energy_change = 0.0;
  return parameters;
}

namespace {

// A block's passes over every moving particle (the drift at each of its substeps, the schedule's start, the
// step limits), in rate evaluations per particle: about half of one in the SCI late stage (callgrind,
// bench/RESULTS.md "Block length by the least work").
constexpr double block_work_per_particle = 0.5;

}  // namespace

double Simulation::next_block_length() const {
  const auto& p = problem_.particles;
  double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
  for (std::size_t i = 0; i < active_; ++i) {
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    shortest = std::min(shortest, p.time_step[i]);
    longest = std::max(longest, p.time_step[i]);
  }
  if (decomposition_ != nullptr) {
    std::array<double, 2> extremes{shortest, -longest};
    decomposition_->min(extremes);
    shortest = extremes[0];
    longest = -extremes[1];
  }
  if (!(longest > 0.0)) return std::min(shortest, parameters_.time_step.max_step);  // nothing moves
  const int levels = parameters_.time_step.block_levels;
  const double block = std::min({longest, std::ldexp(shortest, levels), parameters_.time_step.max_step});
  if (levels == 0 || !late_stage_active_) return block;
  // After the late-stage switch, the phase of the levels that needs the least work (block_time_steps.hpp):
  // the bulk of an impact target steps at its own limit instead of at half of it where that pays for the
  // passes over every particle that more blocks cost. Not in the shock stage, whose energy error follows the
  // steps: with them closer to their limits the SCI run's doubled (docs/physics.md section 1.12).
  BlockStepTally tally{};
  tally_block_steps(block, p.time_step, p.flags, active_, tally);
  if (decomposition_ != nullptr) decomposition_->sum(tally);
  return cheapest_block_length(block, tally, block_work_per_particle);
}

ParticleSelection Simulation::neighbourhood_of(std::span<const std::uint32_t> particles) {
  const std::size_t n = problem_.particles.size();
  needed_mark_.assign(n, 0);
  const auto count = static_cast<std::int64_t>(particles.size());
  std::uint8_t* mark = needed_mark_.data();
  const PairSupport support = pair_support(problem_.particles, problem_.box);
  // The particles themselves first, so that their entries in one another's lists (most entries, in a substep
  // that advances many) are skipped without a support test. Static: each thread marks the neighbours of one
  // contiguous run of the (curve-ordered) particles, so the threads share marks only where their runs meet;
  // interleaved chunks made them contend for the same cache lines (2.6 times the processor time of one
  // thread, bench/RESULTS.md).
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::int64_t kk = 0; kk < count; ++kk) mark[particles[static_cast<std::size_t>(kk)]] = 1;
#pragma omp for schedule(static)
    for (std::int64_t kk = 0; kk < count; ++kk) {
      const std::size_t i = particles[static_cast<std::size_t>(kk)];
      for (const std::uint32_t entry : lists_.of(i)) {
        const std::size_t j = neighbour_index(entry);
        if (std::atomic_ref<std::uint8_t>(mark[j]).load(std::memory_order_relaxed) == 0 &&
            support(i, entry)) {
          std::atomic_ref<std::uint8_t>(mark[j]).store(1, std::memory_order_relaxed);
        }
      }
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

void Simulation::end_substep(const ParticleSelection& active, std::span<const double> step_of_particle,
                             const TimeStepParameters& parameters) {
  auto& p = problem_.particles;
  {
    auto scope = timers_.measure("integration");
    correct(p, step_of_particle, active, integrator_workspace_, rate_workspace_.neighbour_count,
            parameters_.smoothing, parameters_.density == DensityMethod::continuity);
    if (porous_) limit_compaction(p, problem_.materials, integrator_workspace_.distention, active);
  }
  update_equation_of_state(active);
  if (p.solid_fields) record_peak_pressure(p, active);
  particle_updates_ += active.size();
  auto scope = timers_.measure("schedule");
  (void)update_time_steps(p, rate_workspace_.signal_time, parameters, active);
}

void Simulation::advance_block(double block) {
  auto& p = problem_.particles;
  const auto all = ParticleSelection::all(p.size());
  {
    auto scope = timers_.measure("integration");
    begin_step(p, integrator_workspace_, all);
  }
  // Lists of every particle, kept from substep to substep (NeighbourSearch::update: only the particles that
  // moved beyond the skin are searched again) and read through the support test.
  keep_neighbours();
  {
    auto scope = timers_.measure("schedule");
    const PairSupport support = pair_support(p, problem_.box);
    try {
      schedule_.start(block, p.time_step, p.flags, active_, lists_, &support);
    } catch (const TimeStepCollapse& collapse) {
      throw_collapse(collapse, p, rate_workspace_.signal_time, time_step_parameters(), time_);
    }
  }
  const TimeStepParameters parameters = time_step_parameters();
  const bool bounded = parameters_.density == DensityMethod::continuity;
  if (bounded) {
    auto scope = timers_.measure("neighbours");
    within_skin_until_.resize(active_);
    renew_skin_bounds(ParticleSelection::all(active_));
  }
  while (!schedule_.finished()) {
    double dt = 0.0;
    {
      auto scope = timers_.measure("schedule");
      dt = schedule_.advance();
    }
    {
      auto scope = timers_.measure("integration");
      drift(p, dt, problem_.box, parameters_.smoothing);
    }
    if (bounded) {
      keep_neighbours_within_bounds();
    } else {
      keep_neighbours();
    }
    const auto active = ParticleSelection::listed(schedule_.active());
    ParticleSelection needed = all;
    {
      auto scope = timers_.measure("schedule");
      // The inactive neighbours of an active particle are read at their predicted state: their pressure,
      // sound speed and (for solids) returned stress must be of that state. Nobody else's is read.
      needed = neighbourhood_of(schedule_.active());
    }
    evaluate_rates(active, needed);
    end_substep(active, schedule_.active_steps(), parameters);
    {
      auto scope = timers_.measure("schedule");
      if (!schedule_.finished()) {
        try {
          const PairSupport support = pair_support(p, problem_.box);
          schedule_.relevel(p.time_step, lists_, &support);
        } catch (const TimeStepCollapse& collapse) {
          throw_collapse(collapse, p, rate_workspace_.signal_time, parameters, time_ + schedule_.elapsed());
        }
        begin_step(p, integrator_workspace_, active);
      }
    }
    if (bounded) {
      // The active particles' velocity, h and step rates changed; the others' bounds hold to their steps'
      // ends.
      auto scope = timers_.measure("neighbours");
      renew_skin_bounds(active);
    }
    if (between_substeps_) between_substeps_();
  }
}

void Simulation::exchange_levels() {
  decomposition_->refresh_halo_values(exchange_values_);
  held_level_.resize(exchange_values_.size());
  held_present_.resize(exchange_values_.size());
  for (std::size_t i = 0; i < exchange_values_.size(); ++i) {
    held_present_[i] = exchange_values_[i] >= 0.0 ? 1 : 0;
    held_level_[i] = exchange_values_[i] >= 0.0 ? static_cast<std::uint8_t>(exchange_values_[i]) : 0;
  }
}

NeighbourLevels Simulation::levels_with_halos() {
  const auto level = schedule_.levels();
  const auto scheduled = schedule_.scheduled();
  exchange_values_.assign(problem_.particles.size(), -1.0);  // -1: not scheduled
  for (std::size_t k = 0; k < level.size(); ++k)
    if (scheduled[k] != 0) exchange_values_[owned_.begin + k] = level[k];
  exchange_levels();
  return {held_level_, held_present_, owned_.begin};
}

std::span<const std::uint32_t> Simulation::active_with_halos(std::span<const std::uint8_t> level) {
  exchange_values_.assign(problem_.particles.size(), -1.0);  // -1: not active
  for (const std::uint32_t k : schedule_.active()) exchange_values_[owned_.begin + k] = level[k];
  exchange_levels();
  active_anywhere_.clear();
  for (std::size_t i = 0; i < held_present_.size(); ++i)
    if (held_present_[i] != 0) active_anywhere_.push_back(static_cast<std::uint32_t>(i));
  return active_anywhere_;
}

int Simulation::largest_over_processes(int value) const {
  return static_cast<int>(-least_over_processes(-static_cast<double>(value)));
}

void Simulation::advance_block_over_processes(double block) {
  auto& p = problem_.particles;
  const TimeStepParameters parameters = time_step_parameters();
  // A collapsed step is said with the particle (an owned one: its index after the halos are dropped).
  const auto collapse = [&](const TimeStepCollapse& c) {
    drop_halos();
    throw_collapse(c, p, rate_workspace_.signal_time, parameters, time_ + schedule_.elapsed());
  };
  // The halos of the whole block: found once with their skin, found again only when a particle here or
  // elsewhere has moved beyond it (halos_outgrown), refreshed in between from their owners. The lists are
  // kept as in the serial run (keep_neighbours), over the owned particles and the halos, in curve order.
  add_halos(std::max(parameters_.neighbours.halo_skin, exact_halo_skin), block);
  every_field_.clear();
  p.for_each_field([this](std::string_view name, const auto&) { every_field_.push_back(name); });
  {
    auto scope = timers_.measure("integration");
    begin_step(p, integrator_workspace_, ParticleSelection::listed(owned_list_));
  }
  keep_neighbours();
  // The levels: each process those of its own particles, under the neighbour rule with its halos' levels
  // (exchanged every sweep, so that every sweep reads the sweep before, as the serial one does).
  {
    auto scope = timers_.measure("schedule");
    const PairSupport support = pair_support(p, problem_.box);
    const auto owned_steps = std::span<const double>(p.time_step).subspan(owned_.begin, owned_.size());
    const auto owned_flags = std::span<const std::uint8_t>(p.flags).subspan(owned_.begin, owned_.size());
    try {
      schedule_.assign_levels(block, owned_steps, owned_flags, owned_.size());
    } catch (const TimeStepCollapse& c) {
      collapse(c);
    }
    while (any_process(schedule_.raise_levels(lists_, &support, levels_with_halos()))) {
    }
    schedule_.begin_ticks(largest_over_processes(schedule_.finest_scheduled_level()));
  }
  while (!schedule_.finished()) {
    double dt = 0.0;
    {
      auto scope = timers_.measure("schedule");
      dt = schedule_.advance_to(
          static_cast<std::uint64_t>(least_over_processes(static_cast<double>(schedule_.next_end()))));
    }
    {
      auto scope = timers_.measure("integration");
      drift(p, dt, problem_.box, parameters_.smoothing);  // the halos too, overwritten by their owners' below
    }
    // The rates of the active owned particles, with the halos at their owners' drifted state. Whose state is
    // refreshed: the neighbours of an active particle on any process (halos tell which of theirs are active),
    // as in the serial run, where every neighbour of an active particle is.
    keep_halos(every_field_);
    keep_neighbours();
    shifted_active_.clear();
    held_steps_.assign(p.size(), 0.0);
    for (const std::uint32_t k : schedule_.active()) {
      shifted_active_.push_back(static_cast<std::uint32_t>(owned_.begin + k));
      held_steps_[owned_.begin + k] = schedule_.active_steps()[k];
    }
    const auto active = ParticleSelection::listed(shifted_active_);
    ParticleSelection needed = ParticleSelection::all(p.size());
    {
      auto scope = timers_.measure("schedule");
      needed = neighbourhood_of(active_with_halos(schedule_.levels()));
    }
    evaluate_rates(active, needed);
    end_substep(active, held_steps_, parameters);
    if (!schedule_.finished()) {
      // New levels at the corrected positions: the neighbour rule with the halos' levels, the finest level
      // agreed, and waking by the particles whose step just ended, here and on the other processes.
      constexpr std::array<std::string_view, 4> placed{"x", "y", "z", "smoothing_length"};
      keep_halos(placed);
      keep_neighbours();
      auto scope = timers_.measure("schedule");
      const PairSupport support = pair_support(p, problem_.box);
      const auto owned_steps = std::span<const double>(p.time_step).subspan(owned_.begin, owned_.size());
      int highest = 0;
      try {
        highest = schedule_.choose_levels(owned_steps, lists_, &support, levels_with_halos());
      } catch (const TimeStepCollapse& c) {
        collapse(c);
      }
      schedule_.apply_levels(largest_over_processes(std::max(highest, schedule_.finest_level())));
      schedule_.wake(active_with_halos(schedule_.levels()), held_level_, lists_, &support, owned_.begin);
      scope.stop();
      auto integration = timers_.measure("integration");
      shifted_active_.clear();  // the halos may have been found anew
      for (const std::uint32_t k : schedule_.active())
        shifted_active_.push_back(static_cast<std::uint32_t>(owned_.begin + k));
      begin_step(p, integrator_workspace_, ParticleSelection::listed(shifted_active_));
    }
    if (between_substeps_) between_substeps_();
  }
  drop_halos();
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

  if (next_step_sorts() && decomposition_ != nullptr) {
    auto scope = timers_.measure("sort");
    // The re-split balances the pair work of the last evaluation (neighbours + 1 per particle). Weighting
    // it with each particle's evaluations per block (block time steps) was measured slower on the SCI example
    // (docs/parallel.md).
    std::vector<double> work(p.size(), 1.0);
    for (std::size_t i = 0; i < std::min(work.size(), rate_workspace_.neighbour_count.size()); ++i)
      work[i] += rate_workspace_.neighbour_count[i];
    decomposition_->distribute(p, work);
    active_ = p.size();
    force_rebuild_ = true;
  } else if (next_step_sorts()) {
    auto scope = timers_.measure("sort");
    curve_order(std::span<const double>(p.x).first(active_), std::span<const double>(p.y).first(active_),
                std::span<const double>(p.z).first(active_), order_);
    for (std::size_t k = active_; k < p.size(); ++k) order_.push_back(static_cast<std::uint32_t>(k));
    p.permute(order_);
    force_rebuild_ = true;
  }
  if (parameters_.time_step.block_levels > 0 && decomposition_ != nullptr) {
    advance_block_over_processes(dt);
  } else if (parameters_.time_step.block_levels > 0) {
    advance_block(dt);
  } else {
    {
      auto scope = timers_.measure("integration");
      predict(p, dt, problem_.box, integrator_workspace_, parameters_.smoothing);
    }
    evaluate_rates();
    {
      auto scope = timers_.measure("integration");
      correct(p, dt, integrator_workspace_, rate_workspace_.neighbour_count, parameters_.smoothing,
              parameters_.density == DensityMethod::continuity);
      if (porous_) {
        limit_compaction(p, problem_.materials, integrator_workspace_.distention,
                         ParticleSelection::all(p.size()));
      }
    }
    update_equation_of_state();
    if (p.solid_fields) record_peak_pressure(p, ParticleSelection::all(active_));
    particle_updates_ += active_;
  }
  // Every particle's own step limit, before ejection reorders the particles (the signal times of the
  // rate pass are per index).
  limits_ = update_time_steps(p, rate_workspace_.signal_time, time_step_parameters(),
                              ParticleSelection::all(p.size()));
  time_ = land ? target_time : time_ + dt;
  ++step_;
  // No new search for a particle reflected back: the skin tests of the search (needs_rebuild, update)
  // measure how far it is from where it was searched like any other particle's, and its image moves with it.
  (void)reflect_across_mirror_planes(p, problem_.box);
  eject();
  const auto mach = [&] {
    auto scope = timers_.measure("diagnostics");
    // The largest over the processes.
    return -least_over_processes(-max_mach_number(p.vx, p.vy, p.vz, p.sound_speed, p.flags).value);
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

EjectedTotals Simulation::ejected_totals() const {
  EjectedTotals totals;
  const auto add = [&totals](const Particles& p) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if ((p.flags[i] & particle_ejected) == 0) continue;
      ++totals.particles;
      totals.mass += p.mass[i];
    }
  };
  add(problem_.particles);
  add(ejected_);
  return totals;
}

double Simulation::mean_neighbours() const {
  std::size_t active = 0;
  for (const auto f : problem_.particles.flags)
    active += (f & (particle_fixed | particle_ejected)) == 0 ? 1 : 0;
  std::array<double, 2> counts{static_cast<double>(rate_summary_.interacting_pairs),
                               static_cast<double>(active)};
  if (decomposition_ != nullptr) decomposition_->sum(counts);
  return counts[1] == 0.0 ? 0.0 : counts[0] / counts[1];
}

namespace {

// The additive quantities, for sums over processes.
std::array<double, 9> additive_part(const ConservedQuantities& q) {
  return {q.mass,
          q.momentum_x,
          q.momentum_y,
          q.momentum_z,
          q.kinetic_energy,
          q.internal_energy,
          q.potential_energy,
          q.total_energy,
          q.absolute_momentum};
}

}  // namespace

ConservedQuantities Simulation::conserved() const {
  auto q = measure_conserved(problem_.particles, parameters_.gravity);
  if (decomposition_ != nullptr) {
    std::array<double, 9> sums = additive_part(q);
    if (ejected_.size() > 0) {  // process 0: the ejecta's part
      const auto ejecta = additive_part(measure_conserved(ejected_, parameters_.gravity));
      for (std::size_t k = 0; k < sums.size(); ++k) sums[k] += ejecta[k];
    }
    decomposition_->sum(sums);
    q.mass = sums[0];
    q.momentum_x = sums[1];
    q.momentum_y = sums[2];
    q.momentum_z = sums[3];
    q.kinetic_energy = sums[4];
    q.internal_energy = sums[5];
    q.potential_energy = sums[6];
    q.total_energy = sums[7];
    q.absolute_momentum = sums[8];
  }
  q.time = time_;
  q.step = step_;
  return q;
}

MemoryUse Simulation::memory_use() const {
  MemoryUse use;
  const auto n = problem_.particles.size();
  if (n == 0) return use;
  const auto per_particle = [n](std::size_t bytes) {
    return static_cast<double>(bytes) / static_cast<double>(n);
  };
  std::size_t fields = 0;
  problem_.particles.for_each_field([&](std::string_view, const auto& field) {
    fields += field.capacity() * sizeof(typename std::decay_t<decltype(field)>::value_type);
  });
  use.particle_fields = per_particle(fields);
  use.neighbour_lists = per_particle(lists_.bytes());
  use.neighbour_search = per_particle(search_.workspace_bytes());
  std::size_t integrator = 0;
  const auto& w = integrator_workspace_;
  for (const auto* v :
       {&w.acceleration_x, &w.acceleration_y, &w.acceleration_z, &w.density_rate, &w.energy_rate,
        &w.viscosity_alpha_rate, &w.stress_rate_xx, &w.stress_rate_xy, &w.stress_rate_xz, &w.stress_rate_yy,
        &w.stress_rate_yz, &w.total_strain_rate, &w.distention_rate, &w.distention}) {
    integrator += v->capacity() * sizeof(double);
  }
  use.integrator = per_particle(integrator);
  use.rate_pass = per_particle(rate_workspace_.bytes() + shear_modulus_.capacity() * sizeof(double));
  std::size_t schedule = schedule_.bytes();
  schedule += (order_.capacity() + needed_list_.capacity()) * sizeof(std::uint32_t) + needed_mark_.capacity();
  schedule += within_skin_until_.capacity() * sizeof(double) + expired_.capacity() * sizeof(std::uint32_t);
  use.schedule = per_particle(schedule);
  std::size_t distributed =
      (owned_list_.capacity() + active_anywhere_.capacity() + shifted_active_.capacity()) *
      sizeof(std::uint32_t);
  distributed += held_level_.capacity() + held_present_.capacity();
  for (const auto* v : {&exchange_values_, &held_steps_, &halo_margin_, &halo_reach_, &halo_anchor_x_,
                        &halo_anchor_y_, &halo_anchor_z_, &halo_anchor_h_}) {
    distributed += v->capacity() * sizeof(double);
  }
  use.distributed = per_particle(distributed);
  return use;
}

SolverState Simulation::state() const {
  SolverState s;
  s.time = time_;
  s.step = step_;
  s.next_time_step = dt_next_;
  s.initial = initial_;
  s.late_stage_active = late_stage_active_;
  if (late_stage_active_) {
    s.transition_time = problem_.late_stage.transition_time;
    s.A_low = problem_.late_stage.A_low[0];
  }
  s.mach_at_transition = mach_at_transition_;
  s.late_stage_max_mach = late_stage_max_mach_;
  return s;
}

}  // namespace craterkit::sph
