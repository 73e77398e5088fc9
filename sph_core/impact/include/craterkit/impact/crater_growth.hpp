#pragma once
// End of crater growth: an impact run stops when, over the last window_fraction (default 20 %)
// of the elapsed simulated time, the measured crater radius stayed within a band of radius_tolerance (1 %)
// of its latest value and the kinetic energy of the moving particles stayed below kinetic_energy_fraction
// (1e-3) of its peak. The crater is measured (crater_measurement.hpp) every check interval of simulated time;
// each measurement is one sample. Documented in docs/crater_measurement.md ("End of crater growth").
#include <cstdint>
#include <optional>
#include <span>

#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::impact {

// The [crater] table of an impact configuration.
struct CraterGrowthParameters {
  double check_interval = 0.0;  // s, simulated time between samples; 0: end_time / 200
  double radius_tolerance = 0.01;
  double kinetic_energy_fraction = 1e-3;
  double window_fraction = 0.2;
  bool stop_when_grown = true;  // false: run to the end time, still reporting when growth ended
};

struct CraterGrowthSample {
  double time = 0.0;            // s
  std::uint64_t step = 0;       // completed steps
  double radius = 0.0;          // m (NaN: no crater found)
  double kinetic_energy = 0.0;  // J, moving particles only (moving_kinetic_energy)
};

struct CraterGrowthCriteria {
  double radius_tolerance = 0.01;
  double kinetic_energy_fraction = 1e-3;
  double window_fraction = 0.2;
  std::size_t min_window_samples = 3;  // samples the window must hold before growth may be declared over
};

[[nodiscard]] CraterGrowthCriteria growth_criteria(const CraterGrowthParameters& parameters);

// True when the samples (in time order) show that growth has ended: with t the time of the last sample,
// every sample with time >= (1 - window_fraction) t (at least min_window_samples of them, t > 0) has a
// finite radius, the largest and the smallest of them differ by at most radius_tolerance x R_last (the
// last radius, > 0), and every one has a kinetic energy at most kinetic_energy_fraction x the largest
// kinetic energy of all samples (which must be > 0).
bool crater_growth_ended(std::span<const CraterGrowthSample> samples, const CraterGrowthCriteria& criteria);

// The first sample k at which crater_growth_ended() holds for samples[0..k], or nullopt: when growth
// ended, also for a run that went on to its end time (stop_when_grown = false).
std::optional<std::size_t> first_sample_of_ended_growth(std::span<const CraterGrowthSample> samples,
                                                        const CraterGrowthCriteria& criteria);

// sum m |v|^2 / 2 over the particles that are neither fixed nor ejected, J (ejecta keep their launch
// energy forever: they must not hold the run open).
double moving_kinetic_energy(const sph::Particles& particles);

}  // namespace craterkit::impact
