#include "craterkit/sph/io/snapshot.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/xdmf.hpp"
#include "snapshot_hdf5.hpp"

namespace craterkit::sph {

double RunAttributes::number(const std::string& key, const std::string& source) const {
  const auto it = numbers.find(key);
  if (it == numbers.end()) throw InputError(source + ": attribute " + key + " missing");
  return it->second;
}

const std::string& RunAttributes::text(const std::string& key, const std::string& source) const {
  const auto it = texts.find(key);
  if (it == texts.end()) throw InputError(source + ": attribute " + key + " missing");
  return it->second;
}

void write_snapshot(const std::filesystem::path& h5, const Particles& particles,
                    const RunAttributes& attributes, int compression) {
  if (compression < 0 || compression > 9) {
    throw std::invalid_argument("snapshot compression " + std::to_string(compression) + ": allowed 0 .. 9");
  }
  const detail::ParticleFileOptions options{detail::kind_snapshot, /*visualisation_vectors=*/true,
                                            compression};
  write_atomically(h5, [&](const std::filesystem::path& tmp) {
    detail::write_particle_file(tmp, particles, attributes, options);
  });
  // The sidecar refers to the snapshot by file name, so it is valid wherever the directory goes.
  write_text_atomically(xdmf_sidecar_path(h5), snapshot_xdmf(h5.filename().string(), particles.size(),
                                                             attributes.time, particles.solid_fields));
}

Particles read_snapshot(const std::filesystem::path& h5, RunAttributes* attributes) {
  return detail::read_particle_file(h5, attributes);
}

void reseal_particle_file(const std::filesystem::path& h5) {
  detail::seal_particle_file(h5);
}

std::filesystem::path xdmf_sidecar_path(const std::filesystem::path& h5) {
  auto sidecar = h5;
  sidecar.replace_extension(".xdmf");
  return sidecar;
}

std::string field_unit(std::string_view field_name) {
  // One line per field of Particles::for_each_field that has a physical unit.
  static constexpr std::pair<std::string_view, std::string_view> units[] = {
      {"x", "m"},
      {"y", "m"},
      {"z", "m"},
      {"vx", "m/s"},
      {"vy", "m/s"},
      {"vz", "m/s"},
      {"mass", "kg"},
      {"density", "kg/m^3"},
      {"specific_energy", "J/kg"},
      {"smoothing_length", "m"},
      {"pressure", "Pa"},
      {"sound_speed", "m/s"},
      {"stress_xx", "Pa"},
      {"stress_xy", "Pa"},
      {"stress_xz", "Pa"},
      {"stress_yy", "Pa"},
      {"stress_yz", "Pa"},
      {"total_strain", "1"},
      {"distention", "1"},
      {"viscosity_alpha", "1"},
      {"balsara", "1"},
      {"acceleration_x", "m/s^2"},
      {"acceleration_y", "m/s^2"},
      {"acceleration_z", "m/s^2"},
      {"density_rate", "kg/m^3/s"},
      {"energy_rate", "W/kg"},
      {"viscosity_alpha_rate", "1/s"},
      {"time_step", "s"},
      {"stress_rate_xx", "Pa/s"},
      {"stress_rate_xy", "Pa/s"},
      {"stress_rate_xz", "Pa/s"},
      {"stress_rate_yy", "Pa/s"},
      {"stress_rate_yz", "Pa/s"},
      {"total_strain_rate", "1/s"},
      {"distention_rate", "1/s"},
      {"correction_xx", "1"},
      {"correction_xy", "1"},
      {"correction_xz", "1"},
      {"correction_yy", "1"},
      {"correction_yz", "1"},
      {"correction_zz", "1"},
      {"peak_pressure", "Pa"},
  };
  for (const auto& [name, unit] : units) {
    if (name == field_name) return std::string(unit);
  }
  return {};
}

}  // namespace craterkit::sph
