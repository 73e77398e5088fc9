// Snapshots in the Python package: reading an SPH snapshot or checkpoint (fields as NumPy arrays, the run's
// attributes) and measuring its crater as `craterkit measure` does (docs/crater_measurement.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/crater_measurement.hpp"
#include "craterkit/impact/impact_run_record.hpp"
#include "craterkit/sph/io/snapshot.hpp"

namespace py = pybind11;

namespace {

py::dict attributes_dict(const craterkit::sph::RunAttributes& a) {
  py::dict out;
  out["time"] = a.time;
  out["step"] = a.step;
  for (const auto& [key, value] : a.numbers) out[py::str(key)] = value;
  for (const auto& [key, value] : a.texts) out[py::str(key)] = value;
  return out;
}

py::tuple read_snapshot(const std::filesystem::path& path) {
  craterkit::sph::RunAttributes attributes;
  const craterkit::sph::Particles particles = craterkit::sph::read_snapshot(path, &attributes);
  py::dict fields;
  particles.for_each_field([&](std::string_view name, const auto& values) {
    using Value = typename std::decay_t<decltype(values)>::value_type;
    fields[py::str(std::string(name))] =
        py::array_t<Value>(static_cast<py::ssize_t>(values.size()), values.data());
  });
  return py::make_tuple(fields, attributes_dict(attributes));
}

double positive(std::optional<double> value, const char* name) {
  if (!value) return 0.0;
  if (!(*value > 0.0) || !std::isfinite(*value)) {
    throw craterkit::InputError(std::string(name) + " " + craterkit::format_number(*value) +
                                " is not allowed: must be a finite number > 0");
  }
  return *value;
}

py::object measure_crater(const std::filesystem::path& path, std::optional<double> rho_initial,
                          std::optional<double> spacing, std::pair<double, double> centre,
                          std::optional<bool> quarter, std::size_t azimuths,
                          std::optional<double> max_radius) {
  namespace impact = craterkit::impact;
  craterkit::sph::RunAttributes attributes;
  const craterkit::sph::Particles particles = craterkit::sph::read_snapshot(path, &attributes);
  impact::CraterMeasurementOptions m;
  if (impact::is_impact_run(attributes)) {
    m = impact::crater_measurement_options(impact::read_run_record(attributes, path.string()));
  }
  if (rho_initial) m.rho_initial = positive(rho_initial, "rho_initial");
  if (spacing) {
    m.particle_spacing = positive(spacing, "spacing");
    m.inner_spacing = m.inner_radius = m.grading = 0.0;
  }
  if (!(m.rho_initial > 0.0))
    throw craterkit::InputError(path.string() + " is not the snapshot of an impact run: give rho_initial");
  if (!(m.particle_spacing > 0.0))
    throw craterkit::InputError(path.string() + " is not the snapshot of an impact run: give spacing");
  m.centre = {centre.first, centre.second};
  if (quarter) m.quarter_symmetric = *quarter;
  if (azimuths < 4 || azimuths % 4 != 0) {
    throw craterkit::InputError("azimuths " + std::to_string(azimuths) +
                                " is not allowed: must be a multiple of 4, >= 4");
  }
  m.n_azimuths = azimuths;
  if (max_radius) m.max_radius = positive(max_radius, "max_radius");
  const auto result = impact::measure_crater(particles, m);
  // The same object as crater.json (docs/crater_measurement.md), as Python dicts and lists.
  return py::module_::import("json").attr("loads")(impact::crater_json_text(result, attributes.time));
}

}  // namespace

void add_snapshot_bindings(py::module_& m) {
  m.def("read_snapshot", &read_snapshot, py::arg("path"),
        "(fields, attributes) of an SPH snapshot or checkpoint: every particle field as a NumPy array (x, y, "
        "z, "
        "vx, ..., density, pressure, ...; docs/output.md) and the root attributes (time, step, "
        "craterkit_version, "
        "configuration, the run record).");
  m.def(
      "measure_crater", &measure_crater, py::arg("path"), py::arg("rho_initial") = py::none(),
      py::arg("spacing") = py::none(), py::arg("centre") = std::pair<double, double>{0.0, 0.0},
      py::arg("quarter") = py::none(), py::arg("azimuths") = 64, py::arg("max_radius") = py::none(),
      "The crater of an impact snapshot, measured as `craterkit measure` does: a dict with the fields of "
      "crater.json (crater_radius, depth, rim, profile, ...). The run's own settings are used unless given.");
}
