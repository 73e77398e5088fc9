#pragma once
// The numerical parameters of the solver (docs/simulate.md lists the configuration keys that set them):
// kernel, density method, smoothing length, artificial viscosity and stress, time step, neighbour search,
// and the constant gravity. Plain data with the defaults of a generic problem; a scenario may change
// defaults (run/standard_problems.hpp, impact/impact_config.hpp).
#include <array>
#include <cstdint>

#include "craterkit/sph/integration/integrator.hpp"
#include "craterkit/sph/integration/time_step.hpp"
#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/rates/rates.hpp"
#include "craterkit/sph/rates/summation_density.hpp"

namespace craterkit::sph {

struct NeighbourParameters {
  // Lists with a skin of 0.1 h, kept from step to step and searched again only for the particles that left
  // it (NeighbourSearch::update): the Sedov bench takes half the time of lists rebuilt at every step
  // (bench/RESULTS.md, "Kept lists for one global step").
  NeighbourSearchOptions search{.skin = 0.1};
  std::uint64_t sort_interval = 20;  // steps between space-filling-curve sorts (0: never)
  // Distributed block time steps: each particle's margin for the halos a block keeps is halo_skin h plus its
  // motion over the block (Simulation::add_halos); they are found again within the block only when a particle
  // moved beyond its margin. Changes no result. docs/parallel.md, "Halos kept through a block".
  double halo_skin = 0.5;
};

struct SolverParameters {
  KernelType kernel = KernelType::cubic_spline;
  DensityMethod density = DensityMethod::continuity;
  SmoothingLengthParameters smoothing{};
  ArtificialViscosity viscosity{};
  double artificial_stress = 0.0;  // epsilon of rates/artificial_stress.hpp; 0: off
  TimeStepParameters time_step{};
  NeighbourParameters neighbours{};
  std::array<double, 3> gravity{0.0, 0.0, 0.0};  // m/s^2, constant
};

}  // namespace craterkit::sph
