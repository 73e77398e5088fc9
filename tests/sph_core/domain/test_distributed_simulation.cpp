// The solver spread over 1, 2 and 3 ranks (solver/decomposition.hpp, domain/mpi_decomposition.hpp) against
// the serial solver on the same problem, which every rank also runs whole, 20 steps with re-splits every 5:
//  - the Sedov blast (gas, periodic cube, summed density): measured equal bit for bit;
//  - an elastic block under gravity with mirror planes and a fixed floor (the solid path): equal to round-off
//    (3e-15 of the largest velocity): the pair sums add the same terms, in the order of each rank's own
//    octree;
//  - a planar impact into the porous, cohesive SCI target material (P-alpha, Lundborg, periodic
//  cross-section):
//    as close as the serial run is to itself after a change of 1e-15 (serial_sensitivity());
//  - the tiny impact of the study tests, also through ejection and the late-stage switch: to round-off.
// A missing or stale halo differs by far more (measured on 2 ranks: without the refresh of the summed density
// the Sedov velocities by 3e-2, without the periodic halos the Sedov densities by 0.18, with the halos'
// stress_xx zeroed the elastic block's velocities by 0.19 and the tiny impact's by 3.4e-3, with the halos'
// densities 0.1 % high the tiny impact's by 3.2e-2).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "craterkit/impact/impact_config.hpp"
#include "craterkit/impact/impact_run.hpp"
#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/domain/mpi_decomposition.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "craterkit/sph/solver/simulation.hpp"
#include "sph_core/solid_test_setups.hpp"
#include "study/study_test_helpers.hpp"

namespace craterkit::sph {
namespace {

StandardProblemConfig sedov_config() {
  StandardProblemConfig config;
  SedovSetup setup;
  setup.particles_per_side = 14;
  setup.blast_radius = 0.15;
  config.problem = setup;
  config.simulation.solver.smoothing.max_smoothing_length = 0.2;
  config.simulation.solver.density = DensityMethod::summation;
  config.simulation.solver.time_step.block_levels = 0;
  config.simulation.solver.neighbours.sort_interval = 5;  // re-split and migrate during the run
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  return config;
}

StandardProblemConfig porous_plates_config() {
  StandardProblemConfig config;
  PlateImpactSetup setup;
  setup.projectile_material = "aluminium_projectile";
  setup.target_material = "basalt_matrix_ryugu";
  setup.impact_velocity = 300.0;
  setup.projectile_thickness = 0.004;
  setup.target_thickness = 0.01;
  setup.particle_spacing = 5e-4;
  setup.cross_section_particles = 6;
  config.problem = setup;
  config.simulation.solver.time_step.block_levels = 0;
  config.simulation.solver.neighbours.sort_interval = 5;
  return config;
}

// An elastic block swaying under gravity in a quarter domain: mirror planes at x = 0 and y = 0, a fixed floor
// two layers thick, a smooth initial velocity field, strength far above the stresses (no yield, no
// threshold anywhere: well conditioned), corrected stress force. Everything of the solid path except
// porosity.
struct ElasticBlock {
  SolverParameters solver;
  ProblemSetup problem;
};

ElasticBlock elastic_block() {
  ElasticBlock out;
  out.solver.time_step.block_levels = 0;
  out.solver.neighbours.sort_interval = 5;
  out.solver.gravity = {0.0, 0.0, -1.0};
  auto& problem = out.problem;
  problem.materials = {solid_test::elastic_material(2000.0, 1e7, 0.25)};
  problem.box.lower = {0.0, 0.0, 0.0};
  problem.box.mirror = {true, true, false};
  const double dx = 0.1, eta = 1.2;
  const int across = 9, high = 12;
  for (int i = 0; i < across; ++i)
    for (int j = 0; j < across; ++j)
      for (int k = 0; k < high; ++k) {
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx, z = (k + 0.5) * dx;
        const std::size_t n =
            solid_test::add_particle(problem.particles, x, y, z, dx, 2000.0, eta, 1.0, k < 2);
        if (k < 2) continue;
        problem.particles.vx[n] = 0.5 * std::sin(1.3 * z) * std::cos(0.7 * y);
        problem.particles.vy[n] = 0.3 * std::sin(0.9 * z + x);
        problem.particles.vz[n] = -0.2 * std::sin(2.0 * x) * std::sin(1.1 * y);
      }
  return out;
}

// Largest |a - b| over the particles (matched by id), each relative to the largest serial value.
struct Differences {
  double position = 0, velocity = 0, density = 0, energy = 0;
};

Differences differences(const Particles& serial, const Particles& other) {
  std::map<std::uint64_t, std::size_t> index;
  for (std::size_t i = 0; i < serial.size(); ++i) index[serial.id[i]] = i;
  const Particles& s = serial;
  double length = 0, speed = 0, density = 0, energy = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    length = std::max(length, s.smoothing_length[i]);
    speed = std::max(speed, std::hypot(s.vx[i], s.vy[i], s.vz[i]));
    density = std::max(density, s.density[i]);
    energy = std::max(energy, std::abs(s.specific_energy[i]));
  }
  Differences out;
  for (std::size_t k = 0; k < other.size(); ++k) {
    const Particles& o = other;
    const std::size_t i = index.at(o.id[k]);
    out.position =
        std::max(out.position, std::hypot(o.x[k] - s.x[i], o.y[k] - s.y[i], o.z[k] - s.z[i]) / length);
    out.velocity =
        std::max(out.velocity, std::hypot(o.vx[k] - s.vx[i], o.vy[k] - s.vy[i], o.vz[k] - s.vz[i]) / speed);
    out.density = std::max(out.density, std::abs(o.density[k] - s.density[i]) / density);
    out.energy = std::max(out.energy, std::abs(o.specific_energy[k] - s.specific_energy[i]) / energy);
  }
  return out;
}

// What "to round-off" means for a problem: the serial run again with every velocity changed by one part in
// 1e15. Well-conditioned flows (Sedov) keep such a change at round-off; the first steps of a planar impact
// into a porous target at rest do not (particles at the edge of the neighbour-count band, of the crush curve
// and of the yield surface take one branch or the other): there 1e-15 grows to 1e-5 in the velocity in three
// steps (measured), and a distributed run can be no closer than that.
Differences serial_sensitivity(const SolverParameters& solver, ProblemSetup nudged, const Simulation& serial,
                               int steps) {
  for (auto* component : {&nudged.particles.vx, &nudged.particles.vy, &nudged.particles.vz})
    for (auto& v : *component) v *= 1.0 + 1e-15;
  Simulation other(solver, std::move(nudged));
  for (int s = 0; s < steps; ++s) other.step(1.0);
  return differences(serial.particles(), other.particles());
}

// The floor of the tolerance (round-off grown over 20 steps), and how much more than the serial run's own
// sensitivity a distributed run may differ.
constexpr double round_off = 1e-12;
constexpr double sensitivity_factor = 10.0;

// Runs `steps` steps serially and over the ranks (each rank also runs the serial problem whole) and compares
// every particle by id, the conserved energy and the clock.
// largest_tolerance: a cap on the tolerance, for problems whose nudged serial run takes another branch of a
// discrete decision (e.g. an ejection a step earlier), which the compared runs must not take (checked).
// Returns how often the distributed run found its halos anew within a block (block time steps).
std::uint64_t expect_serial(const SolverParameters& solver, const ProblemSetup& problem, int steps,
                            double largest_tolerance = 1.0) {
  const auto comm = Communicator::world();
  Simulation serial(solver, problem);
  for (int s = 0; s < steps; ++s) serial.step(1.0);
  const Differences sensitivity = serial_sensitivity(solver, problem, serial, steps);

  MpiDecomposition decomposition(comm);
  Simulation distributed(solver, problem, &decomposition);
  std::vector<EjectaRecord> serial_ejecta, distributed_ejecta;
  for (int s = 0; s < steps; ++s) {
    distributed.step(1.0);
    for (const auto& r : distributed.take_new_ejecta()) distributed_ejecta.push_back(r);
  }
  for (const auto& r : serial.take_new_ejecta()) serial_ejecta.push_back(r);
  std::set<std::uint64_t> ejection_steps;
  for (const auto& r : serial_ejecta) ejection_steps.insert(r.step);
  const ConservedQuantities total = distributed.conserved();  // collective
  const std::size_t count = distributed.total_particles();    // collective
  Particles gathered;
  const Particles& whole = distributed.whole_particles(gathered);  // collective; ejecta included

  // Rank 0 compares the whole particle set (ejected ones included), the others their own particles.
  const Differences d = differences(serial.particles(), comm.rank() == 0 ? whole : distributed.particles());
  const auto tolerance = [largest_tolerance](double serial_change) {
    return std::min(largest_tolerance, std::max(round_off, sensitivity_factor * serial_change));
  };
  EXPECT_EQ(count, serial.particles().size());
  if (comm.rank() == 0) {
    EXPECT_EQ(whole.size(), serial.particles().size());
    // Every ejection recorded once, on rank 0, at the serial run's step.
    std::map<std::uint64_t, std::uint64_t> serial_steps, distributed_steps;
    for (const auto& r : serial_ejecta) serial_steps[r.id] = r.step;
    for (const auto& r : distributed_ejecta) distributed_steps[r.id] = r.step;
    EXPECT_EQ(distributed_steps, serial_steps);
    EXPECT_EQ(distributed_ejecta.size(), serial_ejecta.size());
    EXPECT_EQ(distributed.ejected_totals().particles, serial.ejected_totals().particles);
  } else {
    EXPECT_TRUE(distributed_ejecta.empty()) << "ejections are recorded on rank 0 alone";
    EXPECT_EQ(distributed.ejected_totals().particles, 0u);
  }
  EXPECT_EQ(distributed.late_stage_active(), serial.late_stage_active());
  if (serial.late_stage_active()) {
    EXPECT_LT(std::abs(distributed.mach_at_transition() - serial.mach_at_transition()) /
                  serial.mach_at_transition(),
              tolerance(sensitivity.velocity));
  }
  EXPECT_EQ(distributed.step_count(), serial.step_count());
  EXPECT_LT(std::abs(distributed.time() - serial.time()) / serial.time(), tolerance(sensitivity.velocity));
  EXPECT_LT(std::abs(total.total_energy - serial.conserved().total_energy) /
                std::abs(serial.conserved().total_energy),
            tolerance(sensitivity.energy));
  EXPECT_LT(d.position, tolerance(sensitivity.position));
  EXPECT_LT(d.velocity, tolerance(sensitivity.velocity));
  EXPECT_LT(d.density, tolerance(sensitivity.density));
  EXPECT_LT(d.energy, tolerance(sensitivity.energy));
  std::printf(
      "[rank %d] largest relative differences from the serial run: position %.2g, velocity %.2g, density "
      "%.2g, energy %.2g (the serial run's own sensitivity: %.2g, %.2g, %.2g, %.2g); %zu ejected at %zu "
      "steps, late "
      "stage %s\n",
      comm.rank(), d.position, d.velocity, d.density, d.energy, sensitivity.position, sensitivity.velocity,
      sensitivity.density, sensitivity.energy, serial.ejected_totals().particles, ejection_steps.size(),
      serial.late_stage_active() ? "switched" : "not planned or not reached");
  return distributed.halos_found_anew();
}

std::uint64_t expect_serial(const StandardProblemConfig& config, int steps) {
  return expect_serial(config.simulation.solver, build_standard_problem(config), steps);
}

TEST(DistributedSimulation, SedovFollowsTheSerialRun) {
  expect_serial(sedov_config(), 20);
}

// Block time steps: the blast's hot centre takes steps up to 2^3 shorter than the cold gas (and finer within
// a block); the levels, the neighbour rule and the waking cross the processes. Both runs keep their lists
// through a block, sorted by entry: the distributed run over its owned particles and halos in curve order
// (measured: equal bit for bit on 2 and 3 ranks; tolerance round-off).
TEST(DistributedSimulation, SedovWithBlockTimeStepsFollowsTheSerialRun) {
  StandardProblemConfig config = sedov_config();
  config.simulation.solver.density = DensityMethod::continuity;  // block steps integrate the density
  config.simulation.solver.time_step.block_levels = 3;
  expect_serial(config, 6);  // blocks of up to 2^3 substeps and more; one re-split
}

// The halos of a block are found once, each particle with a margin for its motion, and found anew when a
// particle has moved beyond it. With no skin the margin is the motion over the block alone, which the blast's
// particles outgrow (their h grows): the halos are found anew in the middle of blocks (the rates of the
// step's start, kept for the correction, move with the particles) and the run still follows the serial one.
TEST(DistributedSimulation, SedovWithBlockTimeStepsFindsItsHalosAnewWhenOutgrown) {
  StandardProblemConfig config = sedov_config();
  config.simulation.solver.density = DensityMethod::continuity;
  config.simulation.solver.time_step.block_levels = 3;
  config.simulation.solver.neighbours.halo_skin = 0.0;
  const std::uint64_t found_anew = expect_serial(config, 6);
  std::printf("[rank %d] halos found anew %llu times in 6 blocks\n", Communicator::world().rank(),
              static_cast<unsigned long long>(found_anew));
  if (Communicator::world().size() > 1) {
    EXPECT_GT(found_anew, 0u);
  }
}

TEST(DistributedSimulation, ElasticBlockWithMirrorsAndGravityFollowsTheSerialRun) {
  const ElasticBlock block = elastic_block();
  expect_serial(block.solver, block.problem, 20);
}

TEST(DistributedSimulation, PorousCohesivePlateImpactFollowsTheSerialRun) {
  expect_serial(porous_plates_config(), 20);
}

// The tiny impact of the study tests (study_test_helpers.hpp; a quarter domain: mirror planes, graded porous
// target held by its fixed shell, resolved projectile, gravity) with the global time step, its first 20
// steps. Like the plate impact, the first steps of an impact are ill-conditioned: compared within the serial
// run's own sensitivity.
impact::ImpactConfig tiny_impact_config() {
  return impact::parse_impact_config(
      std::string(study::test::tiny_base()) + "[time_step]\nblock_levels = 0\n", "tiny impact");
}

TEST(DistributedSimulation, TinyImpactFollowsTheSerialRun) {
  const impact::ImpactConfig config = tiny_impact_config();
  impact::ImpactRun run = impact::build_impact_run(config);
  run.problem.late_stage = {};
  run.problem.ejection = {};
  ASSERT_TRUE(run.problem.box.any_mirror());
  expect_serial(config.simulation.solver, run.problem, 20);
}

// The tiny impact with particles ejected above the surface beyond 1 m from the impact point and the
// late-stage switch at the end of step `switch_after` (found by a run without the switch, which also must
// eject some).
ProblemSetup ejecting_and_switching(const impact::ImpactConfig& config, int switch_after) {
  impact::ImpactRun run = impact::build_impact_run(config);
  EXPECT_TRUE(run.problem.late_stage.planned());
  run.problem.ejection = {1.0, 0.0};
  ProblemSetup probe_problem = run.problem;
  probe_problem.late_stage.transition_time = 1e9;  // planned, never reached
  Simulation probe(config.simulation.solver, probe_problem);
  for (int s = 0; s < switch_after; ++s) probe.step(1.0);
  EXPECT_GT(probe.ejected_totals().particles, 0u);
  run.problem.late_stage.transition_time = probe.time();
  return run.problem;
}

// The same impact through ejection and the late-stage switch, 60 steps: particles above the surface beyond
// 1 m from the impact point are ejected (the projectile's upper part as it flattens; the set-up's own rule,
// at the domain radius, ejects nothing this early), and the medium switches at the end of step 30. The
// nudged serial run takes another branch of some discrete decision (an ejection, the crush curve, the yield
// surface) and differs by percents, which says nothing of the distributed run: that one must eject the same
// particles at the same steps, and stays at round-off (measured 1e-14 on 2 and 3 ranks; tolerance 1e-12).
TEST(DistributedSimulation, TinyImpactEjectsAndSwitchesToTheLateStageAsTheSerialRunDoes) {
  const impact::ImpactConfig config = tiny_impact_config();
  expect_serial(config.simulation.solver, ejecting_and_switching(config, 30), 60, round_off);
}

// The impact's own block time steps (tiny_base(): the default block_levels). Its first five blocks are well
// conditioned (the serial run's own sensitivity 1e-14): to round-off. Then 30 blocks with the ejection and
// the late-stage switch of the test above: there the serial run itself turns a 1e-15 change into 5e-7 by the
// eighth block (a level or a return decided the other way; measured), and the distributed run is compared
// within ten times that, with the same ejections.
TEST(DistributedSimulation, TinyImpactWithBlockTimeStepsFollowsTheSerialRun) {
  const impact::ImpactConfig config =
      impact::parse_impact_config(std::string(study::test::tiny_base()), "tiny impact");
  ASSERT_GT(config.simulation.solver.time_step.block_levels, 0);
  impact::ImpactRun run = impact::build_impact_run(config);
  ProblemSetup first_blocks = run.problem;
  first_blocks.late_stage = {};
  first_blocks.ejection = {};
  expect_serial(config.simulation.solver, first_blocks, 5, round_off);

  expect_serial(config.simulation.solver, ejecting_and_switching(config, 15), 30);
}

// A checkpoint holding ejected particles, written by the serial run just after the late-stage switch (step 30
// of the test above), continued over the ranks to step 60: process 0 keeps the ejecta, the others their
// shares, and the whole set ends where the uninterrupted serial run ends, to round-off (a resumed run builds
// its neighbour lists afresh, so the pair sums add in another order).
TEST(DistributedSimulation, ImpactCheckpointWithEjectaResumesOverTheRanks) {
  const auto comm = Communicator::world();
  const impact::ImpactConfig config = tiny_impact_config();
  const ProblemSetup problem = ejecting_and_switching(config, 30);
  Simulation serial(config.simulation.solver, problem);
  for (int s = 0; s < 30; ++s) serial.step(1.0);
  ASSERT_TRUE(serial.late_stage_active());
  ASSERT_GT(serial.ejected_totals().particles, 0u);
  const Particles checkpoint = serial.particles();
  const SolverState state = serial.state();
  for (int s = 0; s < 30; ++s) serial.step(1.0);

  MpiDecomposition decomposition(comm);
  Simulation resumed(config.simulation.solver, problem, checkpoint, state, &decomposition);
  for (int s = 0; s < 30; ++s) resumed.step(1.0);
  EXPECT_EQ(resumed.total_particles(), serial.particles().size());
  Particles gathered;
  const Particles& whole = resumed.whole_particles(gathered);
  if (comm.rank() != 0) return;
  EXPECT_EQ(resumed.ejected_totals().particles, serial.ejected_totals().particles);
  ASSERT_EQ(whole.size(), serial.particles().size());
  const Differences d = differences(serial.particles(), whole);
  EXPECT_LT(d.position, round_off);
  EXPECT_LT(d.velocity, round_off);
  EXPECT_LT(d.density, round_off);
  EXPECT_LT(d.energy, round_off);
  std::printf("resumed over %d ranks: position %.2g, velocity %.2g, density %.2g, energy %.2g\n", comm.size(),
              d.position, d.velocity, d.density, d.energy);
}

// Runs over several processes write the files a serial run writes, and their checkpoints resume on any number
// of processes: run A goes 10 steps over the ranks, then rank 0 alone continues it to 20; run B goes 10 steps
// on rank 0 alone, then all ranks continue it. Both end where the uninterrupted serial run ends, bit for bit
// (the Sedov blast is bitwise equal over ranks, and the checkpoints are written before a curve sort).
class Scratch {
 public:
  explicit Scratch(const Communicator& comm) {
    std::array<double, 1> pid{comm.rank() == 0 ? double(::getpid()) : 0.0};
    comm.sum(pid);  // rank 0's process id names the folder on every rank
    path_ = std::filesystem::temp_directory_path() /
            ("craterkit-test-distributed-" + std::to_string(static_cast<long>(pid[0])));
    comm_ = &comm;
    if (comm.rank() == 0) std::filesystem::remove_all(path_);
    wait();
  }
  ~Scratch() {
    wait();
    if (comm_->rank() == 0) std::filesystem::remove_all(path_);
  }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  void wait() const {
    std::array<double, 1> nothing{0.0};
    comm_->sum(nothing);
  }

 private:
  std::filesystem::path path_;
  const Communicator* comm_ = nullptr;
};

RunSummary run_steps(StandardProblemConfig config, std::uint64_t steps, const std::filesystem::path& out,
                     bool resume, Decomposition* decomposition) {
  config.simulation.run.max_steps = steps;
  RunOptions options;
  options.output_directory = out;
  options.resume = resume;
  options.progress = false;
  options.log = false;
  options.decomposition = decomposition;
  return run_standard_problem(config, options);
}

// Every field of every particle equal, matched by id (a distributed run's snapshot holds its particles in the
// order of its own curve sort).
std::size_t differing_particles(const Particles& a, const Particles& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::map<std::uint64_t, std::size_t> index;
  for (std::size_t i = 0; i < b.size(); ++i) index[b.id[i]] = i;
  std::vector<char> differs(a.size(), 0);
  a.for_each_field([&](std::string_view name, const auto& field) {
    b.for_each_field([&](std::string_view other, const auto& other_field) {
      if constexpr (std::is_same_v<decltype(field), decltype(other_field)>) {
        if (name != other) return;
        for (std::size_t i = 0; i < a.size(); ++i) differs[i] |= field[i] != other_field[index.at(a.id[i])];
      }
    });
  });
  return std::size_t(std::count(differs.begin(), differs.end(), 1));
}

TEST(DistributedRun, CheckpointsResumeOnAnotherNumberOfProcesses) {
  const auto comm = Communicator::world();
  const Scratch scratch(comm);
  StandardProblemConfig config = sedov_config();
  // Bit for bit across process counts with lists rebuilt at every step, in the search's curve order: with a
  // skin the serial run keeps its lists (sorted by entry, in its own numbering) while a distributed run
  // rebuilds them at every evaluation, and the two add the same terms in another order (round-off,
  // DistributedSimulation.SedovFollowsTheSerialRun).
  config.simulation.solver.neighbours.search.skin = 0.0;
  config.simulation.run.end_time = 1.0;  // the runs end by their step counts
  config.simulation.output.snapshot_times = {0.0};
  if (comm.rank() == 0) (void)run_steps(config, 20, scratch / "uninterrupted", false, nullptr);

  MpiDecomposition decomposition(comm);
  const RunSummary first = run_steps(config, 10, scratch / "A", false, &decomposition);
  if (comm.rank() == 0) (void)run_steps(config, 20, scratch / "A", true, nullptr);
  if (comm.rank() == 0) (void)run_steps(config, 10, scratch / "B", false, nullptr);
  scratch.wait();
  const RunSummary second = run_steps(config, 20, scratch / "B", true, &decomposition);

  EXPECT_EQ(first.particles, std::size_t(14 * 14 * 14));
  EXPECT_EQ(first.steps, 10u);
  EXPECT_TRUE(second.resumed);
  EXPECT_EQ(second.steps, 20u);
  if (comm.rank() != 0) {
    EXPECT_TRUE(first.snapshots.empty()) << "only rank 0 writes";
    return;
  }
  EXPECT_EQ(first.snapshots.size(), 2u);  // t = 0 and the final state
  const Particles uninterrupted = read_checkpoint(scratch / "uninterrupted" / "checkpoint.h5");
  EXPECT_EQ(differing_particles(read_checkpoint(scratch / "A" / "checkpoint.h5"), uninterrupted), 0u)
      << "checkpointed over " << comm.size() << " ranks, resumed on 1";
  EXPECT_EQ(differing_particles(read_checkpoint(scratch / "B" / "checkpoint.h5"), uninterrupted), 0u)
      << "checkpointed on 1 rank, resumed over " << comm.size();
}

}  // namespace
}  // namespace craterkit::sph
