#pragma once
// What the solver simulates: the particles, their materials, the box, and the two scenario-level rules the
// solver carries out (the late-stage switch and the ejection of particles). A scenario (the standard test
// problems of run/standard_problems.hpp, the impact of impact/impact_setup.hpp) builds one.
#include <vector>

#include "craterkit/sph/particles/box.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/solver/ejecta.hpp"

namespace craterkit::sph {

// The late-stage switch planned for a run (physics/late_stage.hpp, docs/physics.md section 3): at
// transition_time every material id switches to the low-sound-speed law with its own A_low[id] (Pa). Empty
// A_low: no switch. Per material because a density-scaled stand-in projectile (impact/impact_setup.hpp) needs
// A_low scaled by its density factor k to keep the sound speed of the material it stands for.
struct LateStagePlan {
  double transition_time = 0.0;  // s
  std::vector<double> A_low;     // Pa, index = material id
  // Porous materials open their pores under tension after the switch (late_stage.hpp).
  bool tensile_porosity = false;
  [[nodiscard]] bool planned() const { return !A_low.empty(); }
};

struct ProblemSetup {
  Particles particles;
  std::vector<Material> materials;  // materials[id] for Particles::material == id
  Box box;
  LateStagePlan late_stage{};
  // Ejecta (ejecta.hpp): which moving particles above the pre-impact plane z = 0
  // leave the hydrodynamics (radius 0: none).
  EjectionRule ejection{};
};

}  // namespace craterkit::sph
