#pragma once
// The solver's state (solver/simulation.hpp, SolverState) as attributes of snapshots and checkpoints: the
// one mapping between the typed state and the file's named attributes (docs/output.md).
//   numbers: next_time_step (s), initial_mass, initial_momentum_{x,y,z}, initial_kinetic_energy,
//            initial_internal_energy, initial_potential_energy, initial_total_energy,
//            initial_absolute_momentum; after the late-stage switch also late_stage_transition_time (s),
//            late_stage_A_low (Pa), late_stage_max_mach_at_transition, late_stage_max_mach
//   texts:   late_stage (what the switch did; after the switch only)
// time and step are the attributes' own members.
#include <string>

#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/solver/simulation.hpp"

namespace craterkit::sph {

void write_solver_state(const SolverState& state, RunAttributes& attributes);

// Throws craterkit::InputError naming `source` and the attribute when one is missing.
SolverState read_solver_state(const RunAttributes& attributes, const std::string& source);

}  // namespace craterkit::sph
