#include "craterkit/sph/simulation.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/checkpoint.hpp"
#include "craterkit/sph/progress.hpp"
#include "craterkit/sph/rates_pressure.hpp"
#include "craterkit/sph/space_filling_curve.hpp"
#include "craterkit/sph/xdmf.hpp"

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

ProblemSetup build_problem(const SimulationConfig& config) {
  const double alpha = config.viscosity.alpha;
  const double eta = config.smoothing.eta;
  if (const auto* s = std::get_if<SedovSetup>(&config.setup)) return make_sedov(*s, eta, alpha);
  if (const auto* s = std::get_if<SodSetup>(&config.setup)) return make_sod(*s, eta, alpha);
  return make_plate_impact(std::get<PlateImpactSetup>(config.setup), eta, alpha);
}

void Simulation::configure() {
  for (const auto& m : problem_.materials) equations_of_state_.push_back(m.eos);
  rate_options_.kernel = config_.kernel;
  rate_options_.viscosity = config_.viscosity;
  rate_options_.gravity = config_.run.gravity;
  rate_options_.period = periods(problem_.box);
  rate_options_.solid = false;
  porous_ = false;
  for (const auto& m : problem_.materials) {
    rate_options_.solid = rate_options_.solid || m.strength.has_value();
    porous_ = porous_ || m.porosity.has_value();
  }
  problem_.particles.set_solid_fields(rate_options_.solid || porous_);
  problem_.particles.shrink_to_fit();
}

Simulation::Simulation(SimulationConfig config, ProblemSetup problem)
    : config_(std::move(config)), problem_(std::move(problem)), search_(config_.neighbours.search) {
  configure();
  update_smoothing_length(problem_.particles, config_.smoothing);
  evaluate_rates();
  limits_ = sph::time_step_limits(problem_.particles, rate_summary_, config_.time_step);
  dt_next_ = limits_.step(config_.time_step.max_step);
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
  auto fields = initial_fields(initial_);
  for (std::size_t k = 0; k < fields.size(); ++k)
    *fields[k] = number_attribute(attributes, initial_keys[k], "checkpoint");
  // The pressure workspace is derived state: recompute it (the rate pass of the next step does anyway).
  update_equation_of_state();
  force_rebuild_ = true;
}

void Simulation::update_equation_of_state() {
  auto scope = timers_.measure("equation_of_state");
  if (problem_.particles.solid_fields) {
    update_material_state(problem_.particles, problem_.materials, rate_workspace_, shear_modulus_);
  } else {
    update_pressure(problem_.particles, equations_of_state_, rate_workspace_);
  }
}

void Simulation::evaluate_rates() {
  auto& p = problem_.particles;
  {
    auto scope = timers_.measure("neighbours");
    const auto input = neighbour_input(p);
    if (force_rebuild_ || search_.needs_rebuild(input)) {
      search_.build(input, problem_.box, lists_);
      ++rebuilds_;
      force_rebuild_ = false;
    }
  }
  if (config_.density == DensityMethod::summation) {
    auto scope = timers_.measure("density");
    compute_summation_density(p, PairList{lists_.offsets, lists_.neighbours}, config_.kernel,
                              rate_options_.period);
  }
  update_equation_of_state();
  {
    auto scope = timers_.measure("rates");
    rate_summary_ = compute_rates(p, PairList{lists_.offsets, lists_.neighbours}, rate_options_,
                                  rate_workspace_, rate_options_.solid ? &gradients_ : nullptr);
    if (rate_options_.solid) compute_stress_rates(p, gradients_, shear_modulus_);
    if (porous_) compute_distention_rates(p, problem_.materials);
  }
}

void Simulation::step(double target_time) {
  auto& p = problem_.particles;
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
    curve_order(p.x, p.y, p.z, order_);
    p.permute(order_);
    force_rebuild_ = true;
  }
  {
    auto scope = timers_.measure("integration");
    predict(p, dt, problem_.box, integrator_workspace_, config_.smoothing);
  }
  evaluate_rates();
  {
    auto scope = timers_.measure("integration");
    correct(p, dt, integrator_workspace_, rate_workspace_.neighbour_count, config_.smoothing,
            config_.density == DensityMethod::continuity);
    if (porous_) limit_compaction(p, problem_.materials, integrator_workspace_.distention);
  }
  update_equation_of_state();
  time_ = land ? target_time : time_ + dt;
  ++step_;
  limits_ = sph::time_step_limits(p, rate_summary_, config_.time_step);
  dt_next_ = limits_.step(config_.time_step.max_step);
  if (!(dt_next_ > 0.0) || !std::isfinite(dt_next_)) {
    throw std::runtime_error(
        "time step collapsed to " + std::to_string(dt_next_) + " s at t = " + std::to_string(time_) +
        " s, step " + std::to_string(step_) + " (limits: courant " + std::to_string(limits_.courant) +
        ", acceleration " + std::to_string(limits_.acceleration) + ", density " +
        std::to_string(limits_.density) + ", energy " + std::to_string(limits_.energy) + ")");
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

  ProblemSetup problem = build_problem(config);
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
  Progress progress(progress_options);

  const std::uint64_t first_step = sim->step_count();
  auto last_checkpoint_wall = std::chrono::steady_clock::now();
  const auto& p = sim->particles();
  while (sim->time() < config.run.end_time &&
         (config.run.max_steps == 0 || sim->step_count() < config.run.max_steps)) {
    double target = config.run.end_time;
    if (next_snapshot < snapshot_times.size()) target = std::min(target, snapshot_times[next_snapshot]);
    sim->step(target);
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
    progress.update(sim->time(), sim->step_count(), sim->next_time_step(), p.size());
  }
  progress.finish(sim->time(), sim->step_count(), sim->next_time_step(), p.size());

  // The final state: a snapshot (unless one was just written at this time) and a checkpoint, so that
  // --resume of a finished run does nothing and a longer end_time continues it.
  if (files) {
    const bool written =
        !snapshot_times.empty() && next_snapshot > 0 && snapshot_times[next_snapshot - 1] == sim->time();
    if (!written) write_snapshot_now(std::max<std::size_t>(next_snapshot, snapshot_times.size()));
    write_checkpoint_now(next_snapshot);
  }

  const auto final_state = sim->conserved();
  summary.particles = p.size();
  summary.steps = sim->step_count();
  summary.steps_this_run = sim->step_count() - first_step;
  summary.time = sim->time();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  summary.particle_updates_per_second =
      summary.wall_seconds > 0 ? static_cast<double>(summary.particles) *
                                     static_cast<double>(summary.steps_this_run) / summary.wall_seconds
                               : 0.0;
  summary.mean_neighbours = sim->mean_neighbours();
  summary.relative_energy_error = relative_energy_error(sim->initial_conserved(), final_state);
  summary.relative_momentum_error = relative_momentum_error(sim->initial_conserved(), final_state);
  summary.bytes_per_particle = sim->bytes_per_particle();
  summary.neighbour_rebuilds = sim->neighbour_rebuilds();
  summary.phase_seconds = timers.seconds_by_phase();
  summary.phase_table = timers.table();
  return summary;
}

}  // namespace craterkit::sph
