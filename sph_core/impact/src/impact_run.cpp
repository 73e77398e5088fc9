#include "craterkit/impact/impact_run.hpp"

#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "craterkit/impact/crater_growth.hpp"
#include "craterkit/sph/io/step_csv_log.hpp"
#include "craterkit/sph/run/run_observer.hpp"

namespace craterkit::impact {

using namespace sph;

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Samples the crater radius every check interval of simulated time and ends the run when growth has ended
// (crater_growth.hpp). The samples go to crater_growth.csv, from which a resumed run takes its history.
class CraterGrowthMonitor final : public RunObserver {
 public:
  CraterGrowthMonitor(const ImpactConfig& config, CraterMeasurementOptions measurement,
                      std::filesystem::path csv)
      : parameters_(config.crater),
        criteria_(growth_criteria(config.crater)),
        interval_(config.crater.check_interval > 0.0 ? config.crater.check_interval
                                                     : config.simulation.run.end_time / 200.0),
        csv_(std::move(csv)) {
    // The radius alone (the mean of the +-x and +-y rays): the four axis rays are the same sample columns as
    // in the full measurement (its azimuths are multiples of 2 pi / n_azimuths), so the same radius at a
    // sixteenth of the cost.
    axes_ = std::move(measurement);
    axes_.n_azimuths = 4;
  }

  // Over several processes process 0 measures (on the gathered particles), logs and decides; the others
  // take part in the gathers at the same times and in its decision.
  bool start(Simulation& simulation, const RunAttributes* checkpoint) override {
    if (!csv_.empty() && simulation.writes_output()) {
      const std::int64_t restart_step =
          checkpoint != nullptr ? static_cast<std::int64_t>(simulation.step_count()) : -1;
      std::optional<std::uint64_t> expected;
      if (checkpoint != nullptr && checkpoint->numbers.count("crater_growth_rows") != 0)
        expected = static_cast<std::uint64_t>(checkpoint->numbers.at("crater_growth_rows"));
      log_ = std::make_unique<StepCsvLog>(csv_, "time,step,crater_radius,kinetic_energy", 1, restart_step,
                                          expected);
      for (const auto& row : log_->kept_rows()) {
        samples_.push_back({std::stod(row[0]), std::stoull(row[1]), std::stod(row[2]), std::stod(row[3])});
      }
      if (!samples_.empty()) next_check_ = samples_.back().time + interval_;
    }
    // Process 0's history sets the next sample time of every process.
    next_check_ = simulation.least_over_processes(simulation.writes_output() ? next_check_ : infinity);
    if (checkpoint == nullptr) return sample_if_due(simulation);
    return simulation.any_process(parameters_.stop_when_grown && crater_growth_ended(samples_, criteria_));
  }

  bool after_step(Simulation& simulation) override { return sample_if_due(simulation); }

  // The number of rows of crater_growth.csv, which a resumed run must find again.
  void save(RunAttributes& checkpoint) const override {
    if (log_) checkpoint.numbers["crater_growth_rows"] = static_cast<double>(log_->rows());
  }

  [[nodiscard]] const std::vector<CraterGrowthSample>& samples() const { return samples_; }
  [[nodiscard]] const CraterGrowthCriteria& criteria() const { return criteria_; }

 private:
  bool sample_if_due(Simulation& simulation) {
    if (simulation.time() < next_check_) return false;
    auto scope = simulation.timers().measure("crater");
    next_check_ = simulation.time() + interval_;
    Particles gathered;
    const Particles& whole = simulation.whole_particles(gathered);
    if (!simulation.writes_output()) return simulation.any_process(false);
    const CraterMeasurement m = measure_crater(whole, axes_);
    const CraterGrowthSample sample{simulation.time(), simulation.step_count(), m.crater_radius,
                                    moving_kinetic_energy(whole)};
    samples_.push_back(sample);
    if (log_) {
      char row[256];
      std::snprintf(row, sizeof row, "%.17g,%llu,%.17g,%.17g", sample.time,
                    static_cast<unsigned long long>(sample.step), sample.radius, sample.kinetic_energy);
      log_->append(row);
    }
    return simulation.any_process(parameters_.stop_when_grown && crater_growth_ended(samples_, criteria_));
  }

  CraterGrowthParameters parameters_;
  CraterGrowthCriteria criteria_;
  double interval_;
  std::filesystem::path csv_;
  CraterMeasurementOptions axes_;
  std::unique_ptr<StepCsvLog> log_;
  std::vector<CraterGrowthSample> samples_;
  double next_check_ = 0.0;
};

// The crater of the final state: crater.json and crater_profile.csv.
class CraterReport final : public RunObserver {
 public:
  CraterReport(CraterMeasurementOptions measurement, std::filesystem::path directory)
      : measurement_(std::move(measurement)), directory_(std::move(directory)) {}

  void finish(Simulation& simulation) override {
    auto scope = simulation.timers().measure("crater");
    Particles gathered;
    const Particles& whole = simulation.whole_particles(gathered);
    if (!simulation.writes_output()) return;  // process 0 measures and writes
    crater = measure_crater(whole, measurement_);
    if (!directory_.empty()) {
      write_crater_files(directory_, *crater, simulation.time());
      crater_json = (directory_ / "crater.json").string();
    }
  }

  std::optional<CraterMeasurement> crater;
  std::string crater_json;

 private:
  CraterMeasurementOptions measurement_;
  std::filesystem::path directory_;
};

}  // namespace

ImpactRun build_impact_run(const ImpactConfig& config) {
  const auto& solver = config.simulation.solver;
  ImpactScenario impact =
      make_impact(config.impact, solver.smoothing.eta, solver.viscosity.alpha, solver.gravity);
  ImpactRun run{std::move(impact.problem), std::move(impact.summary), {}};
  const ImpactSummary& summary = run.summary;
  auto& plan = run.problem.late_stage;
  plan.transition_time = summary.transition_time;
  plan.A_low.assign(run.problem.materials.size(), summary.low_sound_speed_modulus);
  plan.tensile_porosity = config.impact.tensile_porosity;
  // The density-scaled stand-in (material 1) keeps the sound speed of the material it stands for only if its
  // A_low is scaled by the same k as its other stress-like parameters (docs/impact_setup.md).
  plan.A_low[1] *= summary.model_density_scale;
  run.problem.ejection = {summary.domain_radius, summary.escape_speed};
  run.record = make_run_record(summary, solver.kernel, run.problem.particles, plan.A_low[1]);
  return run;
}

ImpactRunSummary run_impact(const ImpactConfig& config, const RunOptions& options) {
  ImpactRun run = build_impact_run(config);
  if (options.log) std::fprintf(stderr, "%s", describe_impact(run.summary).c_str());
  const CraterMeasurementOptions measurement = crater_measurement_options(run.record);
  const auto& out = options.output_directory;
  CraterGrowthMonitor growth(config, measurement, out.empty() ? out : out / "crater_growth.csv");
  CraterReport report(measurement, out);
  RunObserver* observers[] = {&growth, &report};

  ImpactRunSummary summary;
  summary.setup = run.summary;
  summary.run = run_simulation(config.simulation, std::move(run.problem), run_record_attributes(run.record),
                               options, observers);
  summary.crater_growth_ended = summary.run.ended_by_observer;
  if (const auto k = first_sample_of_ended_growth(growth.samples(), growth.criteria())) {
    summary.crater_growth_end_time = growth.samples()[*k].time;
    summary.crater_growth_end_radius = growth.samples()[*k].radius;
  }
  summary.crater = report.crater;
  summary.crater_json = report.crater_json;
  if (options.log && summary.crater) {
    std::fprintf(stderr, "crater: radius %.4g +- %.2g m at t = %.6g s%s\n", summary.crater->crater_radius,
                 summary.crater->crater_radius_uncertainty, summary.run.time,
                 summary.crater_growth_ended ? " (growth ended)" : "");
  }
  return summary;
}

}  // namespace craterkit::impact
