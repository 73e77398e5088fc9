#include "craterkit/sph/rates/rates_pressure.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace craterkit::sph {

void update_pressure(Particles& p, std::span<const EquationOfState> equations_of_state,
                     RateWorkspace& workspace, const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
  for (const auto id : p.material) {
    if (id >= equations_of_state.size()) {
      throw std::out_of_range("particle material id " + std::to_string(id) + " has no equation of state (" +
                              std::to_string(equations_of_state.size()) + " materials)");
    }
  }
  workspace.inverse_density.resize(p.size());
  workspace.volume.resize(p.size());
  double* inverse_density = workspace.inverse_density.data();
  double* volume = workspace.volume.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    const EosState state = evaluate(equations_of_state[p.material[i]], p.density[i], p.specific_energy[i]);
    p.pressure[i] = state.pressure;
    p.sound_speed[i] = state.sound_speed;
    inverse_density[i] = 1.0 / p.density[i];
    volume[i] = p.mass[i] / p.density[i];
  }
}

}  // namespace craterkit::sph
