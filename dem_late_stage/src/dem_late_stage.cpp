#include "craterkit/dem_late_stage/dem_late_stage.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/dem/grain_contact.hpp"
#include "craterkit/dem/granular_bed.hpp"
#include "craterkit/dem/lammps_files.hpp"
#include "craterkit/dem/lammps_process.hpp"
#include "craterkit/dem/repose_calibration.hpp"
#include "craterkit/dem_late_stage/grain_crater.hpp"
#include "craterkit/impact/impact_run_record.hpp"
#include "craterkit/sph/io/snapshot.hpp"

namespace craterkit::dem_late_stage {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The grain spread: diameters uniform within +-10 % of the mean (keeps equal spheres from crystallising).
constexpr double size_spread = 0.1;
// A first guess of the settled bed's packing fraction; the grain density is corrected to the measured one.
constexpr double packing_guess = 0.58;
// The contacts' stiffness: this overlap under the bed's weight at its bottom (docs/dem.md, "Contact law").
constexpr double overlap_under_weight = 1e-3;  // of a diameter, at the bed's bottom
// ... and at most this overlap when the flow's fastest grain hits one at rest.
constexpr double collision_overlap = 0.05;

std::string late_stage_script(const DemLateStageSpec& spec, const dem::GrainContact& contact, double gravity,
                              double grain_density, double time_step, long steps, long dump_every) {
  const std::string model = dem::lammps_contact_model(contact, spec.grain_diameter, grain_density);
  const std::string mirror =
      dem::lammps_contact_model(dem::frictionless_wall(contact), spec.grain_diameter, grain_density);
  return fmt::format(
      R"(# craterkit: the late stage of an impact as a granular DEM (docs/dem.md, "Late stage")
# atom types: 1 moving bed grains, 2 the frozen shell, 3 flying ejecta (no contacts)
units si
atom_style sphere
atom_modify map array
boundary f f f
newton off
comm_modify vel yes
read_data grains.data
group bed type 1
group flying type 3
group moving type 1 3
pair_style granular
pair_coeff * * {model}
neigh_modify delay 0 exclude type 1 3 exclude type 2 3 exclude type 3 3
neighbor {skin:.17g} bin
fix mirror_x bed wall/gran granular {mirror} xplane 0.0 NULL
fix mirror_y bed wall/gran granular {mirror} yplane 0.0 NULL
fix gravity moving gravity {gravity:.17g} vector 0 0 -1
fix move moving nve/sphere
timestep {dt:.17g}
reset_timestep 0
thermo {thermo}
thermo_style custom step atoms ke
thermo_modify lost ignore norm no flush yes
dump grains all custom {dump_every} dumps/grains.*.dump {columns}
dump_modify grains sort id format float %.17g
# craterkit asks for the end at a dump once growth has ended by creating the file stop.request; every
# process must see the same answer, so the largest over the grains of all processes decides.
variable stop_request equal is_file(stop.request)
variable stop_request_atom atom v_stop_request
compute stop_request_any all reduce max v_stop_request_atom
variable stop equal c_stop_request_any
fix stop_when_grown all halt {dump_every} v_stop != 0 error continue
run {steps}
)",
      fmt::arg("model", model), fmt::arg("mirror", mirror), fmt::arg("skin", 0.25 * spec.grain_diameter),
      fmt::arg("gravity", gravity), fmt::arg("dt", time_step),
      fmt::arg("thermo", std::max(1L, dump_every / 10)), fmt::arg("dump_every", dump_every),
      fmt::arg("columns", dem::dump_columns), fmt::arg("steps", steps));
}

nlohmann::json totals_json(const MotionTotals& t) {
  return {{"count", t.count},
          {"mass_kg", t.mass},
          {"momentum_kg_m_per_s", {t.momentum[0], t.momentum[1], t.momentum[2]}},
          {"kinetic_energy_j", t.kinetic_energy}};
}

nlohmann::json balance_json(const HandoffBalance& b) {
  return {{"sph_ejected_before", totals_json(b.sph_ejected)},
          {"sph_flying", totals_json(b.sph_flying)},
          {"sph_in_bed", totals_json(b.sph_in_bed)},
          {"sph_outside_bed", totals_json(b.sph_outside_bed)},
          {"grains_moving", totals_json(b.grains_moving)},
          {"grains_frozen", totals_json(b.grains_frozen)},
          {"grains_flying", totals_json(b.grains_flying)},
          {"grains_rotational_energy_j", b.grains_rotational_energy},
          {"grains_carved", b.grains_carved},
          {"grains_without_neighbours", b.grains_without_neighbours},
          {"max_moving_speed_m_per_s", b.max_moving_speed}};
}

// The step number of a dump file "grains.<step>.dump".
long dump_step(const std::filesystem::path& path) {
  const std::string stem = path.stem().string();  // grains.<step>
  return std::stol(stem.substr(stem.find('.') + 1));
}

// One dump measured: its growth sample and its crater.
struct MeasuredDump {
  impact::CraterGrowthSample sample;
  impact::CraterMeasurement crater;
};
using DumpMeasure = std::function<MeasuredDump(const std::filesystem::path&)>;

// The dumps in folder, in step order.
std::vector<std::filesystem::path> dumps_in(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> dumps;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == ".dump") dumps.push_back(entry.path());
  std::sort(dumps.begin(), dumps.end(),
            [](const auto& a, const auto& c) { return dump_step(a) < dump_step(c); });
  return dumps;
}

// The growth samples: the impact's first, then the measured dumps' in step order.
std::vector<impact::CraterGrowthSample> growth_samples(const impact::CraterGrowthSample& impact,
                                                       const std::map<long, MeasuredDump>& measured) {
  std::vector<impact::CraterGrowthSample> samples{impact};
  for (const auto& [step, dump] : measured) samples.push_back(dump.sample);
  return samples;
}

// How LAMMPS is watched while it runs.
struct LammpsWatch {
  long steps = 0;
  double handoff_time = 0.0, time_step = 0.0;  // s
  impact::CraterGrowthSample impact;           // the first growth sample
  DumpMeasure measure;
  bool stop_when_grown = true;
  std::function<void(const std::string&)> progress;  // may be empty
};

// Runs LAMMPS and measures each dump it has finished (a dump is finished once the next one exists) as it
// appears, looking every 2 s. When stop_when_grown and the samples show the end of growth, the file
// stop.request asks LAMMPS to end the run at its next dump (the script's fix halt). Progress every 30 s from
// its log. Returns the dumps measured while it ran, by step; `stop_requested` tells whether the run was asked
// to end.
std::map<long, MeasuredDump> run_lammps_watched(const dem::LammpsRun& run, const LammpsWatch& watch,
                                                bool& stop_requested) {
  std::map<long, MeasuredDump> measured;
  stop_requested = false;
  const auto start = Clock::now();
  auto reported = start;
  dem::LammpsPoll poll;
  poll.interval = std::chrono::seconds(2);
  poll.call = [&] {
    // The finished dumps not yet measured.
    try {
      const auto dumps = dumps_in(run.folder / "dumps");
      for (std::size_t k = 0; k + 1 < dumps.size(); ++k)
        if (measured.count(dump_step(dumps[k])) == 0)
          measured.emplace(dump_step(dumps[k]), watch.measure(dumps[k]));
    } catch (const std::exception&) {
      // A dump that cannot be read now is measured again after the run, where its error is reported.
    }
    if (watch.stop_when_grown && !stop_requested &&
        impact::first_sample_of_ended_growth(growth_samples(watch.impact, measured),
                                             impact::CraterGrowthCriteria{})) {
      stop_requested = true;
      std::ofstream(run.folder / "stop.request") << "growth ended\n";
      if (watch.progress)
        watch.progress(
            fmt::format("dem: growth ended at t = {:.1f} s (R = {:.3f} m); stopping LAMMPS at its next dump",
                        measured.rbegin()->second.sample.time, measured.rbegin()->second.sample.radius));
    }
    if (watch.progress && seconds_since(reported) >= 30.0) {
      reported = Clock::now();
      const auto last = dem::last_thermo_values(run.folder / "late_stage.log", 3);  // step atoms ke
      const long step = last.empty() ? 0 : std::lround(last[0]);
      const double elapsed = seconds_since(start);
      const double left =
          step > 0 ? elapsed * static_cast<double>(watch.steps - step) / static_cast<double>(step) : 0.0;
      const std::string radius = measured.empty()
                                     ? std::string()
                                     : fmt::format(", R = {:.3f} m", measured.rbegin()->second.sample.radius);
      watch.progress(
          fmt::format("dem: t = {:.1f} s{}, step {} of {}, {:.0f} s elapsed, at most {:.0f} s left",
                      watch.handoff_time + static_cast<double>(step) * watch.time_step, radius, step,
                      watch.steps, elapsed, left));
    }
  };
  dem::run_lammps(run, poll);
  return measured;
}

}  // namespace

void check_dem_late_stage_spec(const DemLateStageSpec& spec) {
  require_positive(spec.grain_diameter, "grain_diameter");
  require_non_negative(spec.bed_length, "bed_length");
  require_positive(spec.bed_depth, "bed_depth");
  require_non_negative(spec.bed_height, "bed_height");
  require_in_range(spec.repose_angle, "repose_angle", 0.0, 90.0, true, true);
  require_in_range(spec.restitution, "restitution", 0.0, 1.0, true, false);
  require_positive(spec.end_time, "end_time");
  require_positive(spec.output_interval, "output_interval");
  require_non_negative(spec.ejecta_speed, "ejecta_speed");
  require_in_range(spec.processes, "processes", 1, 4096);
  // bed_length 0: the SPH run's domain radius, checked once it is known.
  for (const auto& [name, length] :
       {std::pair{"bed_length", spec.bed_length > 0.0 ? spec.bed_length : 10.0 * spec.grain_diameter},
        std::pair{"bed_depth", spec.bed_depth}})
    if (length < 10.0 * spec.grain_diameter)
      throw InputError(fmt::format("{}: value {:g} m is under 10 grains ({:g} m each): allowed >= {:g} m",
                                   name, length, spec.grain_diameter, 10.0 * spec.grain_diameter));
}

DemLateStageResult run_dem_late_stage(const DemLateStageSpec& requested, const std::filesystem::path& out,
                                      const std::function<void(const std::string&)>& progress) {
  DemLateStageSpec spec = requested;
  check_dem_late_stage_spec(spec);
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  DemLateStageResult result;

  // The SPH run at the hand-off.
  sph::RunAttributes attributes;
  const sph::Particles sph = sph::read_snapshot(spec.snapshot, &attributes);
  if (!impact::is_impact_run(attributes))
    throw InputError(
        fmt::format("{}: not the snapshot of an impact run (no run record)", spec.snapshot.string()));
  const impact::ImpactRunRecord record = impact::read_run_record(attributes, spec.snapshot.string());
  if (record.symmetry != impact::DomainSymmetry::quarter)
    throw InputError(
        fmt::format("{}: the DEM late stage takes quarter-domain runs (symmetry = \"quarter\"); "
                    "this run is a full domain",
                    spec.snapshot.string()));
  if (!(record.gravity > 0.0))
    throw InputError(
        fmt::format("{}: the run has no gravity; the DEM late stage needs it", spec.snapshot.string()));
  result.handoff_time = attributes.time;
  if (!(spec.end_time > result.handoff_time))
    throw InputError(fmt::format("end_time: value {:g} s is not after the hand-off time {:g} s",
                                 spec.end_time, result.handoff_time));
  if (spec.bed_length == 0.0) {
    spec.bed_length = record.domain_radius;
    check_dem_late_stage_spec(spec);
  }
  const double ejecta_speed = spec.ejecta_speed > 0.0 ? spec.ejecta_speed : record.escape_speed;
  if (!(ejecta_speed > 0.0))
    throw InputError("ejecta_speed: the run has no escape speed; give one (m/s, > 0)");

  // Contact law and the settled bed.
  const double bulk_density = record.initial_bulk_density;
  dem::BedSpec bed_spec;
  bed_spec.length_x = bed_spec.length_y = spec.bed_length;
  bed_spec.side_walls = true;
  bed_spec.depth = spec.bed_depth + spec.bed_height;
  bed_spec.grain_sizes = {(1.0 - size_spread) * spec.grain_diameter,
                          (1.0 + size_spread) * spec.grain_diameter};
  bed_spec.grain_density = bulk_density / packing_guess;
  bed_spec.gravity = record.gravity;
  bed_spec.seed = spec.seed;
  bed_spec.processes = spec.processes;
  const dem::ReposeCalibration calibration = spec.repose_table.empty()
                                                 ? dem::shipped_repose_calibration()
                                                 : dem::read_repose_calibration(spec.repose_table);
  bed_spec.contact.sliding_friction = calibration.sliding_friction;
  bed_spec.contact.rolling_friction = dem::rolling_friction_for_repose_angle(calibration, spec.repose_angle);
  bed_spec.contact.restitution = spec.restitution;
  bed_spec.contact.youngs_modulus = dem::youngs_modulus_for_overlap(
      bulk_density, bed_spec.grain_density, record.gravity, bed_spec.depth, spec.grain_diameter,
      bed_spec.contact.poisson_ratio, overlap_under_weight);
  result.sliding_friction = bed_spec.contact.sliding_friction;
  result.rolling_friction = bed_spec.contact.rolling_friction;
  dem::check_bed_spec(bed_spec);
  std::filesystem::create_directories(out);  // only once the input has been checked
  const auto settle_start = Clock::now();
  const auto cache = spec.bed_cache.empty() ? out / "beds" : spec.bed_cache;
  say(fmt::format("dem: bed {} x {} x {} m of {:g} m grains (hash {}), cached in {}", spec.bed_length,
                  spec.bed_length, bed_spec.depth, spec.grain_diameter, dem::bed_hash(bed_spec),
                  cache.string()));
  dem::SettledBed settled = dem::settled_bed_cached(bed_spec, cache, progress);
  result.settle_seconds = seconds_since(settle_start);
  // The grain density for the target's bulk density exactly; the bed in the impact's coordinates, its
  // surface bed_height above the pre-impact plane.
  const double density_scale = bulk_density / settled.bulk_density;
  result.grain_density = bed_spec.grain_density * density_scale;
  result.bulk_density = bulk_density;
  dem::Grains bed = settled.grains;
  const double shift = settled.surface_height - spec.bed_height;
  for (std::size_t g = 0; g < bed.size(); ++g) {
    bed.density[g] = result.grain_density;
    bed.z[g] -= shift;
  }

  // The hand-off.
  HandoffSpec handoff_spec;
  handoff_spec.bed_box = {0.0, spec.bed_length, 0.0, spec.bed_length, -shift, settled.surface_height - shift};
  handoff_spec.frozen_thickness = 1.5 * bed_spec.grain_sizes.max_diameter;
  handoff_spec.critical_density = 0.5 * bulk_density;
  handoff_spec.ejecta_speed = ejecta_speed;
  handoff_spec.flying_grain_density = result.grain_density;
  handoff_spec.sph_domain_radius = record.domain_radius;
  handoff_spec.kernel = record.kernel;
  handoff_spec.quarter_symmetric = true;
  Handoff handoff = hand_off(sph, bed, handoff_spec);
  result.balance = handoff.balance;
  result.grains = handoff.grains.size();
  write_atomically(out / "handoff.json", [&](const std::filesystem::path& tmp) {
    std::ofstream(tmp) << balance_json(handoff.balance).dump(2) << '\n';
  });
  const auto& b = handoff.balance;
  say(fmt::format(
      "dem: hand-off at t = {:g} s: {} moving and {} frozen grains of {:.4g} kg for {:.4g} kg of SPH "
      "material in the bed, {} flying; momentum (x, z) grains ({:.4g}, {:.4g}), SPH ({:.4g}, {:.4g}) "
      "kg m/s; kinetic energy grains {:.4g}, SPH {:.4g} J (handoff.json)",
      result.handoff_time, b.grains_moving.count, b.grains_frozen.count,
      b.grains_moving.mass + b.grains_frozen.mass, b.sph_in_bed.mass, b.grains_flying.count,
      b.grains_moving.momentum[0], b.grains_moving.momentum[2], b.sph_in_bed.momentum[0],
      b.sph_in_bed.momentum[2], b.grains_moving.kinetic_energy, b.sph_in_bed.kinetic_energy));

  // The grains' pre-impact level: their surface far from the crater, where the SPH material has not moved.
  GrainMeasurement measurement{bulk_density, 1.2, 0.0};
  {
    std::vector<std::array<double, 2>> columns;
    const double far = spec.bed_length - handoff_spec.frozen_thickness - 2.0 * spec.grain_diameter;
    for (int k = 0; k < 16; ++k) {
      const double angle = (k + 0.5) / 16.0 * 0.5 * std::numbers::pi;
      columns.push_back({far * std::cos(angle), far * std::sin(angle)});
    }
    measurement.plane_height =
        grain_surface_height(handoff.grains, handoff.roles, bulk_density, 1.2, columns);
    result.plane_height = measurement.plane_height;
  }

  // The run's stiffness: the settling stiffness, or stiffer where the flow's fastest grain hitting one at
  // rest would overlap by more than collision_overlap of the smallest diameter. Stiffening releases the
  // settled overlaps' extra elastic energy into the bed in its first contact times: reported.
  const double max_speed = std::max(b.max_moving_speed, ejecta_speed);
  dem::GrainContact run_contact = bed_spec.contact;
  run_contact.youngs_modulus =
      std::max(bed_spec.contact.youngs_modulus,
               dem::youngs_modulus_for_impact(bed_spec.grain_sizes.min_diameter, result.grain_density,
                                              max_speed, run_contact.poisson_ratio, collision_overlap));
  result.youngs_modulus = run_contact.youngs_modulus;
  {
    dem::Grains bed_grains;
    for (std::size_t g = 0; g < handoff.grains.size(); ++g) {
      if (handoff.roles[g] == static_cast<int>(GrainRole::flying)) continue;
      bed_grains.add(handoff.grains.x[g], handoff.grains.y[g], handoff.grains.z[g],
                     handoff.grains.diameter[g], handoff.grains.density[g]);
    }
    result.bed_elastic_energy_settled = dem::contact_elastic_energy(bed_grains, bed_spec.contact);
    result.bed_elastic_energy_run = dem::contact_elastic_energy(bed_grains, run_contact);
  }
  say(fmt::format(
      "dem: stiffness E = {:.4g} Pa (settled with {:.4g} Pa); the bed's contacts hold {:.3g} J at it "
      "({:.3g} J settled), against {:.4g} J of the flow's kinetic energy",
      run_contact.youngs_modulus, bed_spec.contact.youngs_modulus, result.bed_elastic_energy_run,
      result.bed_elastic_energy_settled, b.grains_moving.kinetic_energy));

  // LAMMPS.
  result.time_step = dem::hertz_contact_time(run_contact, bed_spec.grain_sizes.min_diameter,
                                             result.grain_density, max_speed) /
                     50.0;
  const auto dump_every = std::max(1L, std::lround(spec.output_interval / result.time_step));
  const long steps =
      dump_every * static_cast<long>(std::ceil((spec.end_time - result.handoff_time) /
                                               (static_cast<double>(dump_every) * result.time_step)));
  const auto folder = out / "lammps";
  const dem::Box box{0.0,
                     spec.bed_length,
                     0.0,
                     spec.bed_length,
                     handoff_spec.bed_box.z_low,
                     handoff_spec.bed_box.z_high +
                         std::max(2.0 * spec.bed_length, ejecta_speed * ejecta_speed / record.gravity)};
  // The crater on a dump, measured as on an SPH snapshot (grain_crater.hpp).
  impact::CraterMeasurementOptions options;
  options.rho_initial = bulk_density;
  options.particle_spacing = std::cbrt(result.grain_density * std::numbers::pi / 6.0 *
                                       bed_spec.grain_sizes.mean_cubed_diameter() / bulk_density);
  options.kernel = sph::KernelType::cubic_spline;
  options.quarter_symmetric = true;
  options.max_radius = spec.bed_length - handoff_spec.frozen_thickness - 2.0 * 1.2 * options.particle_spacing;
  const double initial_mass = b.grains_moving.mass + b.grains_frozen.mass + b.grains_flying.mass;
  const DumpMeasure measure_dump = [&](const std::filesystem::path& dump) {
    std::vector<long> ids;
    const dem::Grains grains = dem::read_lammps_dump(dump, &ids);
    std::vector<int> roles(grains.size());
    for (std::size_t g = 0; g < grains.size(); ++g)
      roles[g] = handoff.roles[static_cast<std::size_t>(ids[g] - 1)];
    MeasuredDump one;
    one.crater = impact::measure_crater(grains_as_particles(grains, roles, measurement), options);
    // Grains that left the box are ejected too: their mass is what the dump lacks.
    one.crater.ejected_mass =
        4.0 * (b.sph_ejected.mass + initial_mass -
               (dem::total_mass(grains) - grain_totals(grains, roles, GrainRole::flying).mass));
    const long step = dump_step(dump);
    one.sample = {result.handoff_time + static_cast<double>(step) * result.time_step,
                  static_cast<std::uint64_t>(step), one.crater.crater_radius,
                  grain_totals(grains, roles, GrainRole::moving).kinetic_energy};
    return one;
  };
  // The first sample is the impact, as in an SPH run's crater_growth.csv: the projectile's kinetic energy (in
  // the quarter), the peak the end-of-growth rule's energy criterion refers to.
  const impact::CraterGrowthSample impact_sample{
      0.0, 0, std::numeric_limits<double>::quiet_NaN(),
      0.25 * 0.5 * record.projectile_mass * record.impact_speed * record.impact_speed};

  std::map<long, MeasuredDump> measured;
  if (spec.remeasure) {
    // The earlier run must have started from this very hand-off: its data file is the same text.
    const auto data = folder / "grains.data";
    const auto again = out / "grains.data.remeasure";
    dem::write_lammps_data(again, handoff.grains, box, handoff.roles);
    std::ifstream a(data), c(again);
    const std::string before{std::istreambuf_iterator<char>(a), {}},
        now{std::istreambuf_iterator<char>(c), {}};
    std::filesystem::remove(again);
    if (before.empty() || before != now)
      throw InputError(
          fmt::format("--remeasure: {} is missing or was written for another hand-off (other "
                      "snapshot, bed or options); run without --remeasure",
                      data.string()));
    say(fmt::format("dem: measuring the dumps of the earlier run in {}", folder.string()));
    // Its LAMMPS wall time and whether it was stopped stay on record.
    result.lammps_seconds = std::numeric_limits<double>::quiet_NaN();
    try {
      const auto earlier = nlohmann::json::parse(std::ifstream(out / "late_stage.json"));
      result.lammps_seconds = earlier.at("wall_seconds").at("lammps").get<double>();
      result.stopped_when_grown = earlier.value("stopped_when_grown", false);
    } catch (const nlohmann::json::exception&) {
      // No record of the earlier run: its wall time is unknown (NaN).
    }
  } else {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder / "dumps");
    dem::write_lammps_data(folder / "grains.data", handoff.grains, box, handoff.roles);
    write_atomically(folder / "late_stage.in", [&](const std::filesystem::path& tmp) {
      std::ofstream(tmp) << late_stage_script(spec, run_contact, record.gravity, result.grain_density,
                                              result.time_step, steps, dump_every);
    });
    say(fmt::format(
        "dem: LAMMPS on {} process(es): {} grains, at most {} steps of {:.3g} s to t = {:g} s{} ({})",
        spec.processes, handoff.grains.size(), steps, result.time_step,
        result.handoff_time + static_cast<double>(steps) * result.time_step,
        spec.stop_when_grown ? ", stopping at the end of growth" : "", folder.string()));
    const auto lammps_start = Clock::now();
    measured = run_lammps_watched({folder, "late_stage.in", spec.processes},
                                  {steps, result.handoff_time, result.time_step, impact_sample, measure_dump,
                                   spec.stop_when_grown, progress},
                                  result.stopped_when_grown);
    result.lammps_seconds = seconds_since(lammps_start);
  }

  // The crater on every dump not measured while LAMMPS ran.
  const auto measure_start = Clock::now();
  for (const auto& dump : dumps_in(folder / "dumps"))
    if (measured.count(dump_step(dump)) == 0) measured.emplace(dump_step(dump), measure_dump(dump));
  if (measured.empty())
    throw std::runtime_error(fmt::format("{}: LAMMPS wrote no dump", (folder / "dumps").string()));
  result.samples = growth_samples(impact_sample, measured);
  result.growth_ended_sample =
      impact::first_sample_of_ended_growth(result.samples, impact::CraterGrowthCriteria{});
  // samples[k] is the (k - 1)-th dump.
  const std::size_t chosen =
      result.growth_ended_sample ? *result.growth_ended_sample : result.samples.size() - 1;
  const MeasuredDump& at_end = std::next(measured.begin(), static_cast<long>(chosen - 1))->second;
  result.crater = at_end.crater;
  result.crater_time = at_end.sample.time;
  result.measure_seconds = seconds_since(measure_start);

  write_atomically(out / "crater_growth.csv", [&](const std::filesystem::path& tmp) {
    std::ofstream csv(tmp);
    csv << "time,step,crater_radius,kinetic_energy\n";
    for (const auto& s : result.samples)
      csv << fmt::format("{:.17g},{},{:.17g},{:.17g}\n", s.time, s.step, s.radius, s.kinetic_energy);
  });
  impact::write_crater_files(out, result.crater, result.crater_time);
  nlohmann::json summary = {
      {"snapshot", spec.snapshot.string()},
      {"handoff_time_s", result.handoff_time},
      {"grain_diameter_m", spec.grain_diameter},
      {"grain_diameters_m", {bed_spec.grain_sizes.min_diameter, bed_spec.grain_sizes.max_diameter}},
      {"bed_m", {spec.bed_length, spec.bed_length, spec.bed_depth, spec.bed_height}},
      {"bed_hash", dem::bed_hash(bed_spec)},
      {"grain_density_kg_per_m3", result.grain_density},
      {"bulk_density_kg_per_m3", result.bulk_density},
      {"packing_fraction", settled.packing_fraction},
      {"youngs_modulus_pa", result.youngs_modulus},
      {"settling_youngs_modulus_pa", bed_spec.contact.youngs_modulus},
      {"bed_elastic_energy_j",
       {{"settled", result.bed_elastic_energy_settled}, {"run", result.bed_elastic_energy_run}}},
      {"poisson_ratio", bed_spec.contact.poisson_ratio},
      {"restitution", spec.restitution},
      {"sliding_friction", result.sliding_friction},
      {"rolling_friction", result.rolling_friction},
      {"repose_angle_degrees", spec.repose_angle},
      {"ejecta_speed_m_per_s", ejecta_speed},
      {"time_step_s", result.time_step},
      {"steps", steps},
      {"stop_when_grown", spec.stop_when_grown},
      {"stopped_when_grown", result.stopped_when_grown},
      {"last_dump_time_s", result.samples.back().time},
      {"grains", result.grains},
      {"plane_height_m", result.plane_height},
      {"crater_radius_m", result.crater.crater_radius},
      {"crater_time_s", result.crater_time},
      {"growth_ended", result.growth_ended_sample.has_value()},
      {"lammps_processes", spec.processes},
      {"wall_seconds",
       {{"settle", result.settle_seconds},
        {"lammps", result.lammps_seconds},
        {"measure", result.measure_seconds}}}};
  write_atomically(out / "late_stage.json",
                   [&](const std::filesystem::path& tmp) { std::ofstream(tmp) << summary.dump(2) << '\n'; });
  say(fmt::format("dem: crater radius {:.3f} +- {:.3f} m, depth {:.3f} m at t = {:g} s ({}); LAMMPS {:.0f} s",
                  result.crater.crater_radius, result.crater.crater_radius_uncertainty, result.crater.depth,
                  result.crater_time, result.growth_ended_sample ? "growth ended" : "growth had not ended",
                  result.lammps_seconds));
  return result;
}

}  // namespace craterkit::dem_late_stage
