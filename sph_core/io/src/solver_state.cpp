#include "craterkit/sph/io/solver_state.hpp"

#include <array>

namespace craterkit::sph {

namespace {

constexpr const char* initial_keys[] = {"initial_mass",
                                        "initial_momentum_x",
                                        "initial_momentum_y",
                                        "initial_momentum_z",
                                        "initial_kinetic_energy",
                                        "initial_internal_energy",
                                        "initial_potential_energy",
                                        "initial_total_energy",
                                        "initial_absolute_momentum"};

template <class Quantities>
auto initial_fields(Quantities& q) {
  return std::array{&q.mass,
                    &q.momentum_x,
                    &q.momentum_y,
                    &q.momentum_z,
                    &q.kinetic_energy,
                    &q.internal_energy,
                    &q.potential_energy,
                    &q.total_energy,
                    &q.absolute_momentum};
}

}  // namespace

void write_solver_state(const SolverState& state, RunAttributes& a) {
  a.time = state.time;
  a.step = state.step;
  a.numbers["next_time_step"] = state.next_time_step;
  const auto fields = initial_fields(state.initial);
  for (std::size_t k = 0; k < fields.size(); ++k) a.numbers[initial_keys[k]] = *fields[k];
  if (state.late_stage_active) {
    a.numbers["late_stage_transition_time"] = state.transition_time;
    a.numbers["late_stage_A_low"] = state.A_low;
    a.numbers["late_stage_max_mach_at_transition"] = state.mach_at_transition;
    a.numbers["late_stage_max_mach"] = state.late_stage_max_mach;
    a.texts["late_stage"] =
        "matrix equations of state replaced by P_m = A_low (rho_m/rho_m0 - 1); shear moduli scaled by "
        "A_low/A "
        "(docs/physics.md section 3)";
  }
}

SolverState read_solver_state(const RunAttributes& a, const std::string& source) {
  SolverState state;
  state.time = a.time;
  state.step = a.step;
  state.next_time_step = a.number("next_time_step", source);
  auto fields = initial_fields(state.initial);
  for (std::size_t k = 0; k < fields.size(); ++k) *fields[k] = a.number(initial_keys[k], source);
  state.late_stage_active = a.numbers.count("late_stage_transition_time") != 0;
  if (state.late_stage_active) {
    state.transition_time = a.number("late_stage_transition_time", source);
    state.A_low = a.number("late_stage_A_low", source);
    state.mach_at_transition = a.number("late_stage_max_mach_at_transition", source);
    state.late_stage_max_mach = a.number("late_stage_max_mach", source);
  }
  return state;
}

}  // namespace craterkit::sph
