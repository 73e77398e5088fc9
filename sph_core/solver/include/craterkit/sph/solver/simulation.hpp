#pragma once
// The simulation driver: one step is a short sequence of phases, each a free function over the
// particle set and each timed (docs/architecture.md):
//
//   sort along the space-filling curve (every sort_interval steps)
//   -> predict (kick, drift, predicted state; integrator.hpp)
//   -> neighbours (rebuilt when the skin no longer covers the motion, after a sort or checkpoint)
//   -> equation of state per particle -> rates (pair pass) [-> stress rates] -> correct
//   -> equation of state -> next time step
//
// Solid mechanics is on when any material has a [strength] block: the equation-of-state phase then
// evaluates the full material (floor, longitudinal signal speed, shear modulus, radial return) and the
// stress rates come out of the pair pass itself (compute_rates_and_stress_rates: no velocity gradient is
// held). With a [porosity] material (with or without strength) the same per-particle phase evaluates the
// porous pressure and returns states to the crush curve, and the distention rate follows the pair pass.
// Fluid-only runs take the fluid path unchanged.
//
// Late-stage transition (physics/late_stage.hpp, docs/physics.md section 3): when the problem plans one, the
// step that would pass t_transition is shortened to end on it; after that step every material switches to the
// low-sound-speed law, the equation of state and the rates are evaluated again with the new laws (so the
// integrator's stored rates belong to the switched medium), and the time step follows the new sound speeds.
// Each particle carries across the switch (carry_stress_across_switch()) its velocity, its lithostatic
// pressure P_s = clamp(P, 0, rho g d) (d the depth below z = 0), and the elastic energy of the rest of its
// stress:
//  - P_s is kept by re-referencing the density so that the new law returns it,
//    rho = rho_m0 (1 + alpha P / A_low) / alpha: otherwise a target at rest would carry its load with a
//    medium A/A_low times softer and sag (the continuity density is a state variable, so this moves no
//    particle and changes no mass or energy);
//  - the dynamic rest P - P_s and the deviatoric stress S, the stresses of the shock stage's waves, are
//    scaled by sqrt(A_low/A), which keeps their elastic energy P^2/(2K) and S:S/(4G) (K and G both scale by
//    A_low/A); unscaled, that energy would grow by A/A_low (1e6 for the SCI target) and heave the target
//    (docs/validation.md, "Impact craters");
//  - the matrix strain alpha P / A_low stays within +-late_stage_max_reference_strain, and so does the
//    elastic shear strain sqrt(J2)/(2 G) under the new G (cap_elastic_shear_strain()).
// The largest Mach number |v|/c just after the switch and over the late stage are part of the solver's
// state (SolverState), and a run resumed from a checkpoint written after the switch starts switched.
//
// Ejecta (ejecta.hpp): after every step, moving particles beyond the problem's ejection radius are
// flagged particle_ejected and moved behind the others; the neighbour search and the pair loops only see
// the first active_particles() particles, the other phases skip the flag.
//
// Spread over processes (decomposition.hpp, docs/parallel.md): with a Decomposition the particles are those
// this process owns along the space-filling curve. The curve sort becomes a re-split by work with migration
// (Decomposition::distribute), every rate evaluation runs on the owned particles plus copies of the other
// processes' particles within reach (halos, taken after the predictor, so that they carry the predicted
// state; the summed density is sent again before the equation of state), and the time step and the conserved
// quantities are reduced over the processes. The per-particle phases (predict, equation of state, correct)
// run on the owned particles, so a distributed run follows the serial one to round-off (the pair sums add the
// same terms, but the lists order them by each process's own octree). With block time steps every process
// schedules its own particles and reads its halos' levels (advance_block_over_processes(): the finest level
// and the next tick agreed between the processes, halos at every substep's evaluation and new levels, the
// neighbours of active particles on other processes refreshed as the serial run refreshes them). Ejected
// particles leave the processes' pieces: process 0
// collects them (Decomposition::collect_flagged) and holds them from then on, for the ejecta log, the
// conserved quantities and the whole particle set of the output. The late-stage switch happens at the same
// time on every process, and its Mach numbers are maxima over the processes.
//
// The solver knows no files, configurations or scenarios: run/run_simulation.hpp drives it with outputs
// around the steps, and a scenario (run/standard_problems.hpp, the impact library) builds its ProblemSetup.
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "craterkit/sph/integration/block_time_steps.hpp"
#include "craterkit/sph/integration/integrator.hpp"
#include "craterkit/sph/integration/time_step.hpp"
#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/rates/rates.hpp"
#include "craterkit/sph/rates/stress_rates.hpp"
#include "craterkit/sph/solver/conserved_quantities.hpp"
#include "craterkit/sph/solver/decomposition.hpp"
#include "craterkit/sph/solver/ejecta.hpp"
#include "craterkit/sph/solver/memory_use.hpp"
#include "craterkit/sph/solver/phase_timers.hpp"
#include "craterkit/sph/solver/problem.hpp"
#include "craterkit/sph/solver/solver_parameters.hpp"

namespace craterkit::sph {

constexpr double late_stage_max_reference_strain = 0.1;

// What a resumed run needs besides the particles: the clock, the next step, the conserved quantities at
// t = 0 (relative errors of a resumed run refer to the start of the run) and the late stage's state.
struct SolverState {
  double time = 0.0;            // s
  std::uint64_t step = 0;       // completed steps
  double next_time_step = 0.0;  // s
  ConservedQuantities initial{};
  bool late_stage_active = false;
  double transition_time = 0.0;      // s (late stage active)
  double A_low = 0.0;                // Pa, of material 0 (late stage active)
  double mach_at_transition = 0.0;   // max |v|/c just after the switch
  double late_stage_max_mach = 0.0;  // max |v|/c since
};

// Particles ejected so far and their mass, kg.
struct EjectedTotals {
  std::size_t particles = 0;
  double mass = 0.0;
};

class Simulation {
 public:
  // A fresh run at t = 0: evaluates the rates and the first time step. With a decomposition (which must
  // outlive the Simulation) every process passes the whole problem, keeps its share of it and takes its
  // piece of the curve; throws InputError for what a distributed run cannot do yet (see above).
  Simulation(SolverParameters parameters, ProblemSetup problem, Decomposition* decomposition = nullptr);
  // Continues from a checkpoint: `problem` supplies the materials and the box, `particles` and `state`
  // (time, step, next time step, initial conserved quantities, late stage) the state.
  // With a decomposition every process passes the whole checkpoint: a run resumes on any number of
  // processes.
  Simulation(SolverParameters parameters, ProblemSetup problem, Particles particles, const SolverState& state,
             Decomposition* decomposition = nullptr);

  // Advances one step, shortened so as not to pass target_time (the step then ends exactly on it).
  // Throws std::runtime_error if the time step collapses (not positive or not finite).
  void step(double target_time);

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::uint64_t step_count() const { return step_; }
  [[nodiscard]] double next_time_step() const { return dt_next_; }
  [[nodiscard]] const TimeStepLimits& time_step_limits() const { return limits_; }
  [[nodiscard]] Particles& particles() { return problem_.particles; }
  [[nodiscard]] const Particles& particles() const { return problem_.particles; }
  [[nodiscard]] const std::vector<Material>& materials() const { return problem_.materials; }
  [[nodiscard]] const Box& box() const { return problem_.box; }
  [[nodiscard]] const SolverParameters& parameters() const { return parameters_; }
  [[nodiscard]] PhaseTimers& timers() { return timers_; }
  // Interacting pairs (r < h_i + h_j) per particle in the last rate evaluation.
  // (Distributed: over all processes; collective.)
  [[nodiscard]] double mean_neighbours() const;
  [[nodiscard]] const ConservedQuantities& initial_conserved() const { return initial_; }
  // Of all particles (distributed: summed over the processes; collective).
  [[nodiscard]] ConservedQuantities conserved() const;
  // Memory held per particle (capacities over the particle count of this process): fields, neighbour lists
  // and search buffers, integrator and rate scratch, the block schedule, and in distributed runs the
  // exchanges' scratch and the halos' anchors. bytes_per_particle() is memory_use().total().
  [[nodiscard]] MemoryUse memory_use() const;
  [[nodiscard]] double bytes_per_particle() const { return memory_use().total(); }
  [[nodiscard]] std::uint64_t neighbour_rebuilds() const { return rebuilds_; }
  // Distributed block time steps: how often the halos were found anew within a block because a particle had
  // moved beyond its margin (they are found once per block otherwise; docs/parallel.md).
  [[nodiscard]] std::uint64_t halos_found_anew() const { return halos_found_anew_; }
  // Particle updates (one per particle and rate evaluation of its own step) since construction: particles
  // x steps with a global step, the sum over substeps of the particles whose step ended with block steps.
  [[nodiscard]] std::uint64_t particle_updates() const { return particle_updates_; }
  // Block time steps: the schedule of the last block (levels, finest level).
  [[nodiscard]] const BlockSchedule& block_schedule() const { return schedule_; }
  // Particles not ejected (they come first in the arrays).
  [[nodiscard]] std::size_t active_particles() const { return active_; }
  [[nodiscard]] const ProblemSetup& problem() const { return problem_; }

  // Runs over several processes (all collective when distributed). The whole particle set for output: the
  // particles themselves in a serial run; gathered into `gathered` on process 0 (empty elsewhere) in a
  // distributed one.
  [[nodiscard]] const Particles& whole_particles(Particles& gathered);
  // Whether this process writes the run's files (serial, or process 0).
  [[nodiscard]] bool writes_output() const {
    return decomposition_ == nullptr || decomposition_->rank() == 0;
  }
  // True when `value` is true on some process: decisions that every process must take alike.
  [[nodiscard]] bool any_process(bool value) const;
  // The smallest `value` over the processes (e.g. process 0's, with infinity elsewhere).
  [[nodiscard]] double least_over_processes(double value) const;
  // Particles over all processes.
  [[nodiscard]] std::size_t total_particles() const;

  // Late stage: whether the switch has happened, the largest Mach number just after it and since.
  [[nodiscard]] bool late_stage_active() const { return late_stage_active_; }
  [[nodiscard]] double mach_at_transition() const { return mach_at_transition_; }
  [[nodiscard]] double late_stage_max_mach() const { return late_stage_max_mach_; }
  // Ejected so far (distributed: process 0 holds them all; elsewhere none).
  [[nodiscard]] EjectedTotals ejected_totals() const;
  // Ejections since the last call (in order), for the ejecta log (distributed: on process 0).
  [[nodiscard]] std::vector<EjectaRecord> take_new_ejecta() { return std::exchange(new_ejecta_, {}); }

  // Everything a checkpoint needs besides the particles.
  [[nodiscard]] SolverState state() const;
  // True when the next step() begins with a space-filling-curve sort (every sort_interval steps), which
  // rebuilds the neighbour search from the particles alone: nothing of the search's history then reaches the
  // next step, so a run resumed from a checkpoint written now (which builds its search afresh) follows the
  // same states, and the checkpoint needs no extra rebuild (run_simulation.hpp writes checkpoints only then).
  [[nodiscard]] bool next_step_sorts() const {
    const auto interval = parameters_.neighbours.sort_interval;
    return interval > 0 && step_ % interval == 0;
  }
  // Rebuild the neighbour lists at the next step (after a checkpoint when next_step_sorts() is false, i.e.
  // without sorting, so that a restarted run, which must build them afresh, follows the same sequence of
  // lists).
  void force_neighbour_rebuild() { force_rebuild_ = true; }
  // Called between the substeps of a block (block time steps), from the thread that called step() and
  // outside any parallel region: for what should not wait for the end of a block that may take seconds,
  // such as lowering the thread count while other programs compete for the processors (run/thread_share.hpp).
  // It must not change the particles.
  void set_between_substeps(std::function<void()> hook) { between_substeps_ = std::move(hook); }

 private:
  void configure();  // shared by both constructors: laws, rate options, particle storage
  // The positions and h of the particles in the search: the active ones (ejecta are behind them, and never
  // enter the search or the pair loops).
  [[nodiscard]] NeighbourInput searched_input() const;
  // The lists for an evaluation of every particle: kept (keep_neighbours) with one global step and a skin;
  // otherwise rebuilt when the skin no longer covers the motion (skin 0, distributed global steps, and the
  // first and switch evaluations of block time steps).
  void update_neighbours();
  // The lists of every particle kept with the skin (NeighbourSearch::update): block time steps, and one
  // global step with a skin.
  void keep_neighbours();
  // The same within a serial block, checking against its anchor only a particle whose bound has run out: a
  // particle drifts along its step's parabola, so until within_skin_until_ it cannot have left its skin.
  // The same lists as keep_neighbours(). With a summed density, whose values change between a particle's own
  // steps, every particle is checked (no bound is kept).
  void keep_neighbours_within_bounds();
  void renew_skin_bounds(const ParticleSelection& selection);  // from their state and anchors (room())
  void evaluate_rates();  // neighbours, then the state and the rates of every particle
  // The state (equation of state, returns to the yield surface and the crush curve) of `state_for` and
  // the rates of `rates_for`; the lists must be current.
  void evaluate_rates(const ParticleSelection& rates_for, const ParticleSelection& state_for);
  void update_equation_of_state();
  void update_equation_of_state(const ParticleSelection& selection);
  void advance_block(double block);  // block time steps (block_time_steps.hpp) over one block
  // Block time steps, after the rates of the active particles: their correction, state and own next step.
  // step_of_particle: per particle index, the step of an active particle that ends here.
  void end_substep(const ParticleSelection& active, std::span<const double> step_of_particle,
                   const TimeStepParameters& parameters);
  // The same over several processes: the schedule of the owned particles, with the halos' levels, the finest
  // level and the next tick agreed between the processes (docs/parallel.md).
  void advance_block_over_processes(double block);
  // Halos held: exchange_values_ (a level per owned particle, -1 for none) given to the halos by their
  // owners, into held_level_ and held_present_.
  void exchange_levels();
  // Halos held: the levels of the owned particles and their halos' (exchanged), for the neighbour rule.
  NeighbourLevels levels_with_halos();
  // Halos held: the particles whose step ends at this tick, owned or halo (list indices), with `level`
  // (per owned particle) exchanged into held_level_ for them.
  std::span<const std::uint32_t> active_with_halos(std::span<const std::uint8_t> level);
  [[nodiscard]] int largest_over_processes(int value) const;
  // The given particles and all their neighbours (block time steps: whose state an active particle reads).
  ParticleSelection neighbourhood_of(std::span<const std::uint32_t> particles);
  [[nodiscard]] TimeStepParameters time_step_parameters() const;
  // The next step (global) or block: the longest particle step, at most 2^block_levels times the shortest
  // and at most max_step (block_levels = 0: the shortest, the global step); after the late-stage switch, the
  // length within a factor 2 below that with the least work per unit time (cheapest_block_length).
  [[nodiscard]] double next_block_length() const;
  // The materials and the fluid laws (no logging, no rate evaluation); returns each material's stress
  // factor sqrt(A_low/A).
  std::vector<double> switch_to_late_stage();
  void eject();  // flags, records and moves ejecta behind the active particles
  void carry_stress_across_switch(const std::vector<double>& stress_factor);
  void cap_elastic_shear_strain();
  // Distributed runs: the halos around the owned particles, and their removal (the per-particle values kept
  // between evaluations follow the owned particles). Found with the reach r_i + r_j, r = h + m, where the
  // margin m = skin h + (|v| + |a| lookahead / 2) lookahead is the motion each particle may make before they
  // are found anew (halos_outgrown). exact_halo_skin: for lists built afresh at once (it only keeps pairs at
  // the edge of the support, equal to round-off, from being missed).
  static constexpr double exact_halo_skin = 1e-6;
  void add_halos(double skin, double lookahead);
  void drop_halos();
  // Halos held: whether a particle on any process has moved beyond its margin since the halos were found, so
  // that a pair within the support may be missing. Collective.
  [[nodiscard]] bool halos_outgrown() const;
  // Halos held: they take their owners' values of the fields that changed, or are found anew when outgrown.
  void keep_halos(std::span<const std::string_view> changed_fields);
  void take_share_of_the_particles();  // distributed: this process's piece of the whole set

  SolverParameters parameters_;
  ProblemSetup problem_;
  std::vector<EquationOfState> equations_of_state_;
  RateOptions rate_options_;
  NeighbourSearch search_;
  NeighbourLists lists_;
  RateWorkspace rate_workspace_;
  std::vector<double> shear_modulus_;  // solid runs only: G per particle, Pa
  IntegratorWorkspace integrator_workspace_;
  std::vector<std::uint32_t> order_;
  BlockSchedule schedule_;
  std::vector<std::uint8_t> needed_mark_;   // block steps: scratch of neighbourhood_of()
  std::vector<std::uint32_t> needed_list_;  // block steps: the particles whose state is read
  // Serial block steps: per particle, the time into the block (s) until which it surely stays within its
  // anchor's skin; the particles whose bound has run out (scratch).
  std::vector<double> within_skin_until_;
  std::vector<std::uint32_t> expired_;
  std::uint64_t particle_updates_ = 0;
  PhaseTimers timers_;
  RateSummary rate_summary_{};
  TimeStepLimits limits_{};
  ConservedQuantities initial_{};
  double time_ = 0.0;
  double dt_next_ = 0.0;
  std::uint64_t step_ = 0;
  std::uint64_t rebuilds_ = 0;
  bool force_rebuild_ = true;
  std::function<void()> between_substeps_;
  bool porous_ = false;  // a material has [porosity]: the distention evolves (P-alpha)
  std::size_t active_ = 0;
  bool late_stage_active_ = false;
  double mach_at_transition_ = 0.0;
  double late_stage_max_mach_ = 0.0;
  std::vector<EjectaRecord> new_ejecta_;
  Particles ejected_;  // distributed runs, process 0: every ejected particle (elsewhere empty)
  Decomposition* decomposition_ = nullptr;  // distributed runs only (not owned)
  OwnedRange owned_{};                      // while halos are held
  std::vector<std::uint32_t> owned_list_;   // owned_ as a selection
  // Distributed block steps: scratch of the exchanges of levels and of the active particles.
  std::vector<double> exchange_values_;
  std::vector<std::uint8_t> held_level_, held_present_;
  std::vector<std::uint32_t> active_anywhere_, shifted_active_;
  std::vector<double> held_steps_;  // per held particle: the step of an active owned one
  std::vector<std::string_view> every_field_;
  // How the halos were found (add_halos), each owned particle's margin and reach then, and its position and
  // h then (halos_outgrown).
  double halo_skin_ = 0.0, halo_lookahead_ = 0.0;
  std::vector<double> halo_margin_, halo_reach_;
  std::vector<double> halo_anchor_x_, halo_anchor_y_, halo_anchor_z_, halo_anchor_h_;
  std::uint64_t halos_found_anew_ = 0;  // halos found anew within a block (outgrown)
};

}  // namespace craterkit::sph
