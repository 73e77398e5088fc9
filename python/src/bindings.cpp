// The compiled part of the Python package `craterkit` (module craterkit._craterkit): the scaling law, its
// constant sets and fit, and the chronology (bodies, populations, crater production, relative rates,
// crater counts, model ages). Functions of one impact or one crater size take NumPy arrays (or numbers)
// and broadcast them like NumPy ufuncs. craterkit::InputError becomes ValueError with the same message.
// The Python side (craterkit/__init__.py) re-exports these names; docs/python.md shows their use.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/chronology_system.hpp"
#include "craterkit/chronology/conventions.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/law_propagation.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/chronology/production.hpp"
#include "craterkit/chronology/relative_rates.hpp"
#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/fit_json.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"
#include "craterkit/scaling/point_source.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace py = pybind11;
namespace cs = craterkit::scaling;
namespace ck = craterkit::chronology;

namespace {

using Array = py::array_t<double, py::array::forcecast>;

bool names_a_file(const std::string& name_or_path) {
  return name_or_path.find('/') != std::string::npos || name_or_path.ends_with(".toml");
}

// ---------------------------------------------------------------------------------------------------
// Scaling

std::string law_repr(const cs::ScalingLaw& law) {
  std::ostringstream out;
  out << "ScalingLaw(form='" << cs::to_string(law.form) << "', " << cs::coefficient_name(law.form, 1) << "="
      << craterkit::format_number(law.coefficient_1) << ", " << cs::coefficient_name(law.form, 2) << "="
      << craterkit::format_number(law.coefficient_2) << ", mu=" << craterkit::format_number(law.mu)
      << ", nu=" << craterkit::format_number(law.nu) << ")";
  return out.str();
}

cs::ScalingLaw make_law(const std::string& form, double c1, double c2, double mu, double nu) {
  const cs::ScalingLaw law{cs::form_from_string(form), c1, c2, mu, nu};
  cs::validate(law);
  return law;
}

cs::ConstantSet constant_set(const std::string& name_or_path) {
  return names_a_file(name_or_path) ? cs::load_constant_set_file(name_or_path)
                                    : cs::load_constant_set(name_or_path);
}

cs::RadiiTable table_from_columns(const py::dict& columns) {
  const char* required[] = {"impactor_radius", "impactor_density", "velocity",     "target_density",
                            "gravity",         "strength",         "crater_radius"};
  std::vector<std::vector<double>> values;
  std::size_t rows = 0;
  for (const char* name : required) {
    if (!columns.contains(name)) {
      throw craterkit::InputError(
          std::string("fit: the table has no column '") + name +
          "' (columns needed: impactor_radius, impactor_density, velocity, "
          "target_density, gravity, strength, crater_radius; optional crater_radius_sigma)");
    }
    values.push_back(py::cast<std::vector<double>>(Array::ensure(columns[name]).attr("ravel")()));
    if (values.size() > 1 && values.back().size() != rows) {
      throw craterkit::InputError(std::string("fit: column '") + name + "' has " +
                                  std::to_string(values.back().size()) + " values, the first column " +
                                  std::to_string(rows));
    }
    rows = values.back().size();
  }
  std::optional<std::vector<double>> sigma;
  if (columns.contains("crater_radius_sigma")) {
    sigma = py::cast<std::vector<double>>(Array::ensure(columns["crater_radius_sigma"]).attr("ravel")());
    if (sigma->size() != rows)
      throw craterkit::InputError("fit: column 'crater_radius_sigma' has the wrong length");
  }
  for (const auto& item : columns) {
    const auto key = py::cast<std::string>(item.first);
    bool known = key == "crater_radius_sigma";
    for (const char* name : required) known = known || key == name;
    if (!known) throw craterkit::InputError("fit: unknown column '" + key + "'");
  }
  cs::RadiiTable table;
  table.source = "table";
  for (std::size_t i = 0; i < rows; ++i) {
    cs::ImpactRecord r;
    r.impactor = {values[0][i], values[1][i], values[2][i]};
    r.target = {values[3][i], values[4][i], values[5][i]};
    r.crater_radius = values[6][i];
    if (sigma) r.crater_radius_sigma = (*sigma)[i];
    r.line = static_cast<int>(i) + 1;
    const auto bad = [&](const char* column, double v, const char* allowed) {
      throw craterkit::InputError("fit: row " + std::to_string(i) + ", column '" + column +
                                  "': " + craterkit::format_number(v) + " is not allowed: " + allowed);
    };
    if (!(r.impactor.radius > 0.0) || !std::isfinite(r.impactor.radius))
      bad("impactor_radius", r.impactor.radius, "> 0");
    if (!(r.impactor.density > 0.0) || !std::isfinite(r.impactor.density))
      bad("impactor_density", r.impactor.density, "> 0");
    if (!(r.impactor.velocity > 0.0) || !std::isfinite(r.impactor.velocity))
      bad("velocity", r.impactor.velocity, "> 0");
    if (!(r.target.density > 0.0) || !std::isfinite(r.target.density))
      bad("target_density", r.target.density, "> 0");
    if (!(r.target.gravity >= 0.0) || !std::isfinite(r.target.gravity))
      bad("gravity", r.target.gravity, ">= 0");
    if (!(r.target.strength >= 0.0) || !std::isfinite(r.target.strength))
      bad("strength", r.target.strength, ">= 0");
    if (!(r.crater_radius > 0.0) || !std::isfinite(r.crater_radius))
      bad("crater_radius", r.crater_radius, "> 0");
    if (sigma && (!(*r.crater_radius_sigma > 0.0) || !std::isfinite(*r.crater_radius_sigma)))
      bad("crater_radius_sigma", *r.crater_radius_sigma, "> 0");
    table.rows.push_back(r);
  }
  if (table.rows.empty()) throw craterkit::InputError("fit: the table has no rows");
  return table;
}

cs::FitResult fit(const py::object& table, const std::string& form,
                  const std::map<std::string, double>& fixed, bool shared_strength, int starts,
                  unsigned int seed) {
  cs::FitOptions options;
  options.form = cs::form_from_string(form);
  for (const auto& [name, value] : fixed) options.fixed.emplace_back(name, value);
  options.shared_strength = shared_strength;
  if (starts < 1) throw craterkit::InputError("fit: starts " + std::to_string(starts) + " must be >= 1");
  options.starts = starts;
  options.seed = seed;
  if (py::isinstance<py::dict>(table)) return cs::fit_scaling_law(table_from_columns(table), options);
  const auto path = py::cast<std::string>(py::module_::import("os").attr("fspath")(table));
  return cs::fit_scaling_law(cs::read_radii_csv(path), options);
}

// One fit per group of a sweep table's grouping columns, as `craterkit fit --group-by` (grouped_fit.hpp).
// Returns the groups and the JSON `craterkit fit --out` writes for them (readable by load_fit with group=).
py::dict fit_groups(const std::string& table_path, const std::string& form,
                    const std::map<std::string, double>& fixed,
                    std::optional<std::vector<std::string>> group_by, bool require_growth_ended, int starts,
                    unsigned int seed) {
  cs::GroupedFitOptions options;
  options.fit.form = cs::form_from_string(form);
  for (const auto& [name, value] : fixed) options.fit.fixed.emplace_back(name, value);
  if (starts < 1)
    throw craterkit::InputError("fit_groups: starts " + std::to_string(starts) + " must be >= 1");
  options.fit.starts = starts;
  options.fit.seed = seed;
  options.group_by = std::move(group_by);
  options.require_growth_ended = require_growth_ended;
  const auto result = cs::fit_groups(cs::read_radii_csv(table_path), options);
  py::list groups;
  for (const auto& group : result.groups) {
    py::dict key;
    for (const auto& [column, value] : group.key) key[py::str(column)] = value;
    py::dict g;
    g["key"] = key;
    g["label"] = cs::describe(group.key);
    g["lines"] = group.lines;
    g["cohesions"] = group.cohesions;
    g["strength_range"] = py::make_tuple(group.min_strength, group.max_strength);
    g["growth_not_ended"] = group.growth_not_ended;
    g["fit"] = group.fit ? py::cast(*group.fit) : py::none();
    g["not_fitted"] = group.not_fitted;
    py::dict regimes;
    regimes["gravity"] = group.regime_counts.gravity;
    regimes["transitional"] = group.regime_counts.transitional;
    regimes["strength"] = group.regime_counts.strength;
    g["regimes"] = regimes;
    groups.append(g);
  }
  py::dict out;
  out["group_by"] = result.group_by;
  py::dict pooled;
  for (const auto& column : result.pooled) pooled[py::str(column.name)] = column.values;
  out["pooled"] = pooled;
  out["excluded"] = result.excluded;
  out["notes"] = result.notes;
  out["groups"] = groups;
  out["json"] = cs::grouped_fit_to_json(result).dump(2) + "\n";
  return out;
}

// ---------------------------------------------------------------------------------------------------
// Chronology

ck::ImpactorPopulation population_of(const py::object& population) {
  if (py::isinstance<ck::ImpactorPopulation>(population)) return py::cast<ck::ImpactorPopulation>(population);
  return ck::load_population(py::cast<std::string>(population));
}

ck::Body body_of(const py::object& body) {
  if (py::isinstance<ck::Body>(body)) return py::cast<ck::Body>(body);
  return ck::load_body(py::cast<std::string>(body));
}

std::string population_kind(const ck::ImpactorPopulation& p) {
  if (std::holds_alternative<ck::PowerLaw>(p.shape)) return "power_law";
  if (std::holds_alternative<ck::BrokenPowerLaw>(p.shape)) return "broken_power_law";
  return "table";
}

// A crater production function bound to a body, a population, a scaling law and a cohesion.
struct Production {
  ck::Body body;
  ck::ProductionSetup setup;
  cs::ScalingLaw law;
  cs::Target target;
  double impactor_density = 0.0;
  ck::ImpactorRadiusFunction radius;

  double rate(double d) const { return ck::crater_production_rate(setup, radius, d); }
};

Production make_production(const cs::ScalingLaw& law, double cohesion, const py::object& body_arg,
                           const py::object& population_arg, const std::string& region,
                           double impactor_density, std::optional<double> target_density,
                           std::optional<double> gravity, std::optional<double> velocity,
                           double rim_to_apparent, const std::string& cross_section) {
  cs::validate(law);
  if (!(cohesion >= 0.0) || !std::isfinite(cohesion))
    throw craterkit::InputError("cohesion " + craterkit::format_number(cohesion) +
                                " is not allowed: must be a finite number >= 0 Pa");
  if (!(impactor_density > 0.0) || !std::isfinite(impactor_density))
    throw craterkit::InputError("impactor_density " + craterkit::format_number(impactor_density) +
                                " is not allowed: must be > 0 kg/m^3");
  Production p;
  p.body = body_of(body_arg);
  std::optional<ck::SpeedDistribution> speeds;
  if (velocity) {
    if (!(*velocity > 0.0)) throw craterkit::InputError("velocity must be > 0 m/s");
    speeds = ck::single_speed(*velocity);
  }
  p.setup = ck::production_setup_for_body(p.body, ck::collision_region_from_string(region),
                                          population_of(population_arg), speeds ? &*speeds : nullptr);
  p.setup.diameter.rim_to_apparent = rim_to_apparent;
  ck::validate(p.setup.diameter, "rim_to_apparent");
  if (cross_section == "target+impactor") {
    p.setup.cross_section = ck::CrossSection::target_plus_impactor;
  } else if (cross_section == "target") {
    p.setup.cross_section = ck::CrossSection::target_only;
  } else {
    throw craterkit::InputError("cross_section '" + cross_section +
                                "' is not known; allowed: target+impactor, target");
  }
  p.law = law;
  p.target.density = target_density.value_or(p.body.bulk_density);
  p.target.gravity = gravity.value_or(p.body.surface_gravity);
  p.target.strength = cohesion;
  if (!(p.target.density > 0.0)) throw craterkit::InputError("target_density must be > 0 kg/m^3");
  if (!(p.target.gravity >= 0.0)) throw craterkit::InputError("gravity must be >= 0 m/s^2");
  p.impactor_density = impactor_density;
  p.radius = ck::scaled_impactor_radius(law, p.target, impactor_density);
  return p;
}

py::array_t<double> to_numpy(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

ck::CraterCounts make_counts(double area, std::optional<Array> diameters, std::optional<Array> fractions,
                             std::optional<Array> bin_diameters, std::optional<Array> cumulative_counts,
                             const std::string& source, bool buffered) {
  ck::CraterCounts c;
  c.source = source;
  c.area = area;
  c.buffered = buffered;
  if (diameters.has_value() == bin_diameters.has_value()) {
    throw craterkit::InputError(
        "CraterCounts: give either diameters (with optional fractions) or bin_diameters with "
        "cumulative_counts");
  }
  if (diameters) {
    c.diameters = py::cast<std::vector<double>>(diameters->attr("ravel")());
    c.fractions = fractions ? py::cast<std::vector<double>>(fractions->attr("ravel")())
                            : std::vector<double>(c.diameters.size(), 1.0);
    if (c.fractions.size() != c.diameters.size()) {
      throw craterkit::InputError("CraterCounts: " + std::to_string(c.fractions.size()) + " fractions for " +
                                  std::to_string(c.diameters.size()) + " diameters");
    }
    for (double f : c.fractions) {
      if (!(f > 0.0 && (f <= 1.0 || buffered) && std::isfinite(f)))
        throw craterkit::InputError("CraterCounts: fraction " + craterkit::format_number(f) +
                                    " must be in (0, 1] (or > 0 with buffered=True)");
    }
    for (double d : c.diameters) {
      if (!(d > 0.0) || !std::isfinite(d))
        throw craterkit::InputError("CraterCounts: diameter " + craterkit::format_number(d) +
                                    " must be > 0 m");
    }
  } else {
    if (!cumulative_counts) throw craterkit::InputError("CraterCounts: bin_diameters need cumulative_counts");
    const auto d = py::cast<std::vector<double>>(bin_diameters->attr("ravel")());
    const auto n = py::cast<std::vector<double>>(cumulative_counts->attr("ravel")());
    if (d.size() != n.size())
      throw craterkit::InputError("CraterCounts: bin_diameters and cumulative_counts differ in length");
    for (std::size_t i = 0; i < d.size(); ++i) c.bins.push_back({d[i], n[i]});
  }
  ck::validate(c);
  return c;
}

ck::AgeFitOptions age_options(double min_diameter, double max_diameter,
                              std::optional<double> equilibrium_fraction, double max_age,
                              std::size_t grid_points, const std::string& fractions) {
  ck::AgeFitOptions options;
  if (fractions != "weight" && fractions != "whole")
    throw craterkit::InputError("fractions '" + fractions + "' is not known; allowed: weight, whole");
  options.weight_by_fraction = fractions == "weight";
  if (!(min_diameter >= 0.0))
    throw craterkit::InputError("min_diameter " + craterkit::format_number(min_diameter) + " must be >= 0 m");
  options.min_diameter = min_diameter;
  options.max_diameter = max_diameter;
  if (equilibrium_fraction) {
    options.cap.enabled = true;
    options.cap.fraction_of_geometric = *equilibrium_fraction;
    ck::validate(options.cap);
  }
  options.max_age = max_age;
  options.grid_points = grid_points;
  return options;
}

}  // namespace

void add_snapshot_bindings(py::module_& m);  // snapshots.cpp

PYBIND11_MODULE(_craterkit, m) {
  m.doc() = "craterkit: crater scaling and chronology for small bodies (compiled core)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const craterkit::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  add_snapshot_bindings(m);

  m.def(
      "data_directory", [] { return craterkit::data_directory(); },
      "The data directory in use (CRATERKIT_DATA_DIR, else the installation's share/craterkit).");

  // --- scaling law
  py::class_<cs::ScalingLaw>(
      m, "ScalingLaw",
      "The point-source scaling law: form 'hh2011' (H1, H2) or 'holsapple' (K1, K2), mu, nu.")
      .def(py::init(&make_law), py::arg("form"), py::arg("coefficient_1"), py::arg("coefficient_2"),
           py::arg("mu"), py::arg("nu"))
      .def_static(
          "hh2011",
          [](double h1, double h2, double mu, double nu) { return make_law("hh2011", h1, h2, mu, nu); },
          py::arg("H1"), py::arg("H2"), py::arg("mu"), py::arg("nu"))
      .def_static(
          "holsapple",
          [](double k1, double k2, double mu, double nu) { return make_law("holsapple", k1, k2, mu, nu); },
          py::arg("K1"), py::arg("K2"), py::arg("mu"), py::arg("nu"))
      .def_property_readonly("form", [](const cs::ScalingLaw& l) { return cs::to_string(l.form); })
      .def_readonly("coefficient_1", &cs::ScalingLaw::coefficient_1, "K1 or H1")
      .def_readonly("coefficient_2", &cs::ScalingLaw::coefficient_2, "K2 or H2")
      .def_readonly("mu", &cs::ScalingLaw::mu)
      .def_readonly("nu", &cs::ScalingLaw::nu)
      .def_property_readonly("coefficient_names",
                             [](const cs::ScalingLaw& l) {
                               return py::make_tuple(cs::coefficient_name(l.form, 1),
                                                     cs::coefficient_name(l.form, 2));
                             })
      .def(
          "convert",
          [](const cs::ScalingLaw& l, const std::string& form) {
            return cs::convert(l, cs::form_from_string(form));
          },
          py::arg("form"), "The same law in the other form (K1 = H1, K2 = (H1/H2)^(2/mu)).")
      .def("__repr__", &law_repr);

  py::class_<cs::ConstantSet>(m, "ConstantSet", "A published constant set shipped in data/scaling/.")
      .def_readonly("name", &cs::ConstantSet::name)
      .def_readonly("description", &cs::ConstantSet::description)
      .def_readonly("citation", &cs::ConstantSet::citation)
      .def_readonly("conventions", &cs::ConstantSet::conventions)
      .def_readonly("law", &cs::ConstantSet::law)
      .def_readonly("strength", &cs::ConstantSet::strength)
      .def_readonly("target_density", &cs::ConstantSet::target_density)
      .def_readonly("note", &cs::ConstantSet::note)
      .def_readonly("not_given", &cs::ConstantSet::not_given)
      .def("__repr__",
           [](const cs::ConstantSet& s) { return "ConstantSet('" + s.name + "', " + law_repr(s.law) + ")"; });
  m.def("constant_set_names", &cs::constant_set_names, "Names of the shipped constant sets.");
  m.def("load_constant_set", &constant_set, py::arg("name"),
        "A shipped constant set by name (e.g. 'jutzi2022_ryugu'), or any constant-set .toml file by path.");

  m.def(
      "crater_radius",
      [](const cs::ScalingLaw& law, const Array& a, const Array& delta, const Array& u, const Array& rho,
         const Array& g, const Array& y) {
        return py::vectorize([&law](double a_, double delta_, double u_, double rho_, double g_, double y_) {
          return cs::crater_radius(law, {a_, delta_, u_}, {rho_, g_, y_});
        })(a, delta, u, rho, g, y);
      },
      py::arg("law"), py::arg("impactor_radius"), py::arg("impactor_density"), py::arg("velocity"),
      py::arg("target_density"), py::arg("gravity"), py::arg("strength"));
  m.def(
      "impactor_radius",
      [](const cs::ScalingLaw& law, const Array& r, const Array& delta, const Array& u, const Array& rho,
         const Array& g, const Array& y) {
        return py::vectorize([&law](double r_, double delta_, double u_, double rho_, double g_, double y_) {
          return cs::solve_impactor_radius(law, r_, {0.0, delta_, u_}, {rho_, g_, y_});
        })(r, delta, u, rho, g, y);
      },
      py::arg("law"), py::arg("crater_radius"), py::arg("impactor_density"), py::arg("velocity"),
      py::arg("target_density"), py::arg("gravity"), py::arg("strength"));
  m.def(
      "impact_velocity",
      [](const cs::ScalingLaw& law, const Array& r, const Array& a, const Array& delta, const Array& rho,
         const Array& g, const Array& y) {
        return py::vectorize([&law](double r_, double a_, double delta_, double rho_, double g_, double y_) {
          return cs::solve_velocity(law, r_, {a_, delta_, 0.0}, {rho_, g_, y_});
        })(r, a, delta, rho, g, y);
      },
      py::arg("law"), py::arg("crater_radius"), py::arg("impactor_radius"), py::arg("impactor_density"),
      py::arg("target_density"), py::arg("gravity"), py::arg("strength"));
  m.def(
      "gravity_limit_radius",
      [](const cs::ScalingLaw& law, const Array& a, const Array& delta, const Array& u, const Array& rho,
         const Array& g) {
        return py::vectorize([&law](double a_, double delta_, double u_, double rho_, double g_) {
          return cs::gravity_limit_radius(law, {a_, delta_, u_}, {rho_, g_, 0.0});
        })(a, delta, u, rho, g);
      },
      py::arg("law"), py::arg("impactor_radius"), py::arg("impactor_density"), py::arg("velocity"),
      py::arg("target_density"), py::arg("gravity"));
  m.def(
      "strength_limit_radius",
      [](const cs::ScalingLaw& law, const Array& a, const Array& delta, const Array& u, const Array& rho,
         const Array& y) {
        return py::vectorize([&law](double a_, double delta_, double u_, double rho_, double y_) {
          return cs::strength_limit_radius(law, {a_, delta_, u_}, {rho_, 0.0, y_});
        })(a, delta, u, rho, y);
      },
      py::arg("law"), py::arg("impactor_radius"), py::arg("impactor_density"), py::arg("velocity"),
      py::arg("target_density"), py::arg("strength"));

  // --- fit
  py::class_<cs::FitResult>(m, "FitResult", "A Ceres fit of the scaling law to a table of craters.")
      .def_property_readonly("law", &cs::FitResult::law)
      .def_property_readonly("strength", &cs::FitResult::strength)
      .def_property_readonly("form", [](const cs::FitResult& f) { return cs::to_string(f.form); })
      .def_property_readonly("parameters",
                             [](const cs::FitResult& f) {
                               py::dict out;
                               for (const auto& p : f.parameters) {
                                 py::dict d;
                                 d["value"] = p.value;
                                 d["sigma"] = p.sigma;
                                 d["fixed"] = p.fixed;
                                 d["determined"] = p.determined;
                                 d["at_bound"] = p.at_bound;
                                 out[py::str(p.name)] = d;
                               }
                               return out;
                             })
      .def_readonly("chi2", &cs::FitResult::chi2)
      .def_readonly("dof", &cs::FitResult::dof)
      .def_readonly("weighted", &cs::FitResult::weighted)
      .def_readonly("correlation_names", &cs::FitResult::correlation_names)
      .def_readonly("correlation", &cs::FitResult::correlation)
      .def_readonly("covariance", &cs::FitResult::covariance)
      .def_readonly("starts", &cs::FitResult::starts)
      .def_readonly("starts_at_minimum", &cs::FitResult::starts_at_minimum)
      .def_property_readonly("residuals",
                             [](const cs::FitResult& f) {
                               std::vector<double> observed, model, log_residual;
                               for (const auto& r : f.residuals) {
                                 observed.push_back(r.observed);
                                 model.push_back(r.model);
                                 log_residual.push_back(r.log_residual);
                               }
                               py::dict out;
                               out["observed"] = to_numpy(observed);
                               out["model"] = to_numpy(model);
                               out["log_residual"] = to_numpy(log_residual);
                               return out;
                             })
      .def(
          "to_json", [](const cs::FitResult& f) { return cs::fit_to_json(f).dump(2) + "\n"; },
          "The fit as the JSON `craterkit fit --out` writes (readable by --fit and load_fit).")
      .def("__repr__", [](const cs::FitResult& f) {
        return "FitResult(" + law_repr(f.law()) + ", chi2=" + craterkit::format_number(f.chi2) +
               ", dof=" + std::to_string(f.dof) + ")";
      });
  m.def("_fit", &fit, py::arg("table"), py::arg("form"), py::arg("fixed"), py::arg("shared_strength"),
        py::arg("starts"), py::arg("seed"));
  m.def("_fit_groups", &fit_groups, py::arg("table"), py::arg("form"), py::arg("fixed"), py::arg("group_by"),
        py::arg("require_growth_ended"), py::arg("starts"), py::arg("seed"));
  m.def(
      "load_fit",
      [](const std::filesystem::path& path, std::optional<std::string> group) {
        const auto f = cs::load_fitted_law(path, group);
        return py::make_tuple(f.law, f.strength);
      },
      py::arg("path"), py::arg("group") = py::none(),
      "(law, strength) from a fit JSON (craterkit fit --out or FitResult.to_json()); group 'KEY=VALUE' for a "
      "grouped fit.");

  // --- chronology: bodies and populations
  py::class_<ck::Body>(m, "Body", "A target body (data/bodies/).")
      .def_readonly("name", &ck::Body::name)
      .def_readonly("mean_radius", &ck::Body::mean_radius)
      .def_readonly("bulk_density", &ck::Body::bulk_density)
      .def_readonly("surface_gravity", &ck::Body::surface_gravity)
      .def_readonly("surface_area", &ck::Body::surface_area)
      .def_readonly("citations", &ck::Body::citations)
      .def_property_readonly("regions",
                             [](const ck::Body& b) {
                               py::dict out;
                               for (const auto& [name, env] : {std::pair{"main_belt", &b.main_belt},
                                                               std::pair{"near_earth", &b.near_earth}}) {
                                 if (!env->has_value()) continue;
                                 py::dict d;
                                 d["intrinsic_probability_km2_yr"] = (*env)->intrinsic_probability_km2_yr;
                                 d["impact_speed"] = (*env)->impact_speed;
                                 d["citation"] = (*env)->citation;
                                 out[name] = d;
                               }
                               return out;
                             })
      .def("__repr__", [](const ck::Body& b) { return "Body('" + b.name + "')"; });
  m.def("body_names", &ck::body_names);
  m.def("load_body", &ck::load_body, py::arg("name"),
        "A shipped body ('ryugu', 'bennu') or a body .toml by path.");

  py::class_<ck::ImpactorPopulation>(m, "Population", "An impactor population N(>a) (data/populations/).")
      .def_readonly("name", &ck::ImpactorPopulation::name)
      .def_readonly("citation", &ck::ImpactorPopulation::citation)
      .def_readonly("notes", &ck::ImpactorPopulation::notes)
      .def_readonly("approximate", &ck::ImpactorPopulation::approximate)
      .def_property_readonly("kind", &population_kind)
      .def_property_readonly("minimum_radius",
                             [](const ck::ImpactorPopulation& p) { return ck::minimum_radius(p); })
      .def_property_readonly("maximum_radius",
                             [](const ck::ImpactorPopulation& p) { return ck::maximum_radius(p); })
      .def(
          "cumulative_number",
          [](const ck::ImpactorPopulation& p, const Array& a) {
            return py::vectorize([&p](double r) { return ck::cumulative_number(p, r); })(a);
          },
          py::arg("impactor_radius"), "N(>a): impactors with radius larger than a (m).")
      .def(
          "differential_number",
          [](const ck::ImpactorPopulation& p, const Array& a) {
            return py::vectorize([&p](double r) { return ck::differential_number(p, r); })(a);
          },
          py::arg("impactor_radius"), "dN/da at a (m), per m.")
      .def(
          "normalised",
          [](const ck::ImpactorPopulation& p, double a0, double n0) { return ck::normalised(p, a0, n0); },
          py::arg("impactor_radius"), py::arg("number_larger"), "The same shape with N(>a0) = n0.")
      .def("__repr__", [](const ck::ImpactorPopulation& p) { return "Population('" + p.name + "')"; });
  m.def("population_names", &ck::population_names);
  m.def("load_population", &ck::load_population, py::arg("name"),
        "A shipped population by name or a population .toml by path.");
  m.def("power_law_population", &ck::power_law_population, py::arg("slope"),
        py::arg("reference_radius") = 1.0, py::arg("number_larger") = 1.0,
        "dN/da ~ a^slope with N(>reference_radius) = number_larger.");

  // --- chronology: production
  py::class_<Production>(
      m, "Production",
      "Crater production r(D) on a body: population x collision environment x inverse scaling law "
      "at one cohesion.")
      .def(py::init(&make_production), py::arg("law"), py::arg("cohesion"), py::arg("body") = "ryugu",
           py::arg("population") = "main_belt_approx_bottke2005", py::arg("region") = "main_belt",
           py::arg("impactor_density") = 2600.0, py::arg("target_density") = py::none(),
           py::arg("gravity") = py::none(), py::arg("velocity") = py::none(),
           py::arg("rim_to_apparent") = 1.2, py::arg("cross_section") = "target+impactor")
      .def_readonly("body", &Production::body)
      .def_readonly("law", &Production::law)
      .def_property_readonly("cohesion", [](const Production& p) { return p.target.strength; })
      .def_property_readonly("target_density", [](const Production& p) { return p.target.density; })
      .def_property_readonly("gravity", [](const Production& p) { return p.target.gravity; })
      .def_readonly("impactor_density", &Production::impactor_density)
      .def_property_readonly("population", [](const Production& p) { return p.setup.population; })
      .def_property_readonly("mean_speed", [](const Production& p) { return ck::mean_speed(p.setup.speeds); })
      .def_property_readonly("rim_to_apparent",
                             [](const Production& p) { return p.setup.diameter.rim_to_apparent; })
      .def(
          "rate",
          [](const Production& p, const Array& d) {
            return py::vectorize([&p](double d_) { return p.rate(d_); })(d);
          },
          py::arg("diameter"), "r(D): craters with rim diameter > D (m) per m^2 per year.")
      .def(
          "differential_rate",
          [](const Production& p, const Array& d) {
            return py::vectorize(
                [&p](double d_) { return ck::differential_production_rate(p.setup, p.radius, d_); })(d);
          },
          py::arg("diameter"), "-dr/dD per m^2 per year per m of diameter.")
      .def(
          "impactor_radius",
          [](const Production& p, const Array& d) {
            const double speed = ck::mean_speed(p.setup.speeds);
            return py::vectorize([&p, speed](double d_) {
              return p.radius(ck::apparent_radius_from_rim_diameter(d_, p.setup.diameter), speed);
            })(d);
          },
          py::arg("diameter"),
          "a(D): the impactor radius (m) that makes a crater of rim diameter D at the mean speed.")
      .def(
          "impact_rate",
          [](const Production& p, const Array& a) {
            return py::vectorize([&p](double a_) { return ck::impact_rate(p.setup, a_); })(a);
          },
          py::arg("impactor_radius"), "Impacts per year on the body by impactors larger than a (m).")
      .def("__repr__", [](const Production& p) {
        return "Production(" + law_repr(p.law) + ", cohesion=" + craterkit::format_number(p.target.strength) +
               ", body='" + p.body.name + "', population='" + p.setup.population.name + "')";
      });

  m.def(
      "relative_rate",
      [](const Production& a, const Production& b, const Array& d) {
        const Array flat = Array::ensure(d.attr("ravel")());
        const auto n = static_cast<std::size_t>(flat.size());
        std::vector<double> ratio(n), rate_a(n), rate_b(n), radius_a(n), radius_b(n);
        for (std::size_t i = 0; i < n; ++i) {
          const auto r = ck::relative_rate(a.setup, a.radius, b.radius, flat.at(static_cast<py::ssize_t>(i)));
          ratio[i] = r.ratio;
          rate_a[i] = r.rate_a;
          rate_b[i] = r.rate_b;
          radius_a[i] = r.impactor_radius_a;
          radius_b[i] = r.impactor_radius_b;
        }
        // Each column in the shape of `diameter` (a number gives 0-d arrays).
        const auto shaped = [&](const std::vector<double>& v) {
          return to_numpy(v).attr("reshape")(d.attr("shape"));
        };
        py::dict out;
        out["ratio"] = shaped(ratio);
        out["rate_a"] = shaped(rate_a);
        out["rate_b"] = shaped(rate_b);
        out["impactor_radius_a"] = shaped(radius_a);
        out["impactor_radius_b"] = shaped(radius_b);
        return out;
      },
      py::arg("a"), py::arg("b"), py::arg("diameter"),
      "r_B(D)/r_A(D) with A's body, population and conventions and each one's law and target.");

  // --- chronology: counts and ages
  py::class_<ck::CraterCounts>(
      m, "CraterCounts",
      "Crater counts of a unit: rim diameters (m) with fractions, or binned cumulative counts; "
      "area in m^2.")
      .def(py::init(&make_counts), py::arg("area"), py::arg("diameters") = py::none(),
           py::arg("fractions") = py::none(), py::arg("bin_diameters") = py::none(),
           py::arg("cumulative_counts") = py::none(), py::arg("source") = "", py::arg("buffered") = false)
      .def_readonly("buffered", &ck::CraterCounts::buffered)
      .def_readonly("source", &ck::CraterCounts::source)
      .def_readonly("area", &ck::CraterCounts::area)
      .def_property_readonly("binned", &ck::CraterCounts::binned)
      .def_property_readonly("diameters", [](const ck::CraterCounts& c) { return to_numpy(c.diameters); })
      .def_property_readonly("fractions", [](const ck::CraterCounts& c) { return to_numpy(c.fractions); })
      .def_property_readonly("bin_diameters",
                             [](const ck::CraterCounts& c) {
                               std::vector<double> v;
                               for (const auto& b : c.bins) v.push_back(b.diameter);
                               return to_numpy(v);
                             })
      .def_property_readonly("cumulative_counts",
                             [](const ck::CraterCounts& c) {
                               std::vector<double> v;
                               for (const auto& b : c.bins) v.push_back(b.cumulative_count);
                               return to_numpy(v);
                             })
      .def("__len__",
           [](const ck::CraterCounts& c) { return c.binned() ? c.bins.size() : c.diameters.size(); })
      .def("__repr__", [](const ck::CraterCounts& c) {
        return "CraterCounts(" + std::to_string(c.binned() ? c.bins.size() : c.diameters.size()) +
               (c.binned() ? " bins" : " craters") + ", area=" + craterkit::format_number(c.area) + " m^2)";
      });
  m.def(
      "read_counts", [](const std::filesystem::path& p) { return ck::read_crater_counts(p.string()); },
      py::arg("path"),
      "Reads .csv (craterkit), .diam (craterstats) or .scc (CraterTools/craterstats) counts.");
  m.def(
      "write_counts",
      [](const ck::CraterCounts& c, const std::filesystem::path& p) {
        ck::write_crater_counts(c, p.string());
      },
      py::arg("counts"), py::arg("path"),
      "Writes the counts by the extension: .csv (craterkit), .diam, .scc or .binned (craterstats); read back "
      "by read_counts.");

  py::class_<ck::AgeEstimate>(m, "AgeEstimate",
                              "A model age (years) from the Poisson likelihood of the counts.")
      .def_readonly("min_diameter", &ck::AgeEstimate::min_diameter)
      .def_readonly("max_diameter", &ck::AgeEstimate::max_diameter)
      .def_readonly("craters_in_range", &ck::AgeEstimate::craters_in_range)
      .def_readonly("production_in_range", &ck::AgeEstimate::production_in_range)
      .def_readonly("median", &ck::AgeEstimate::median)
      .def_readonly("mode", &ck::AgeEstimate::mode)
      .def_property_readonly(
          "sigma1", [](const ck::AgeEstimate& e) { return py::make_tuple(e.sigma1_low, e.sigma1_high); })
      .def_property_readonly(
          "sigma2", [](const ck::AgeEstimate& e) { return py::make_tuple(e.sigma2_low, e.sigma2_high); })
      .def_readonly("reaches_max_age", &ck::AgeEstimate::reaches_max_age)
      .def_property_readonly("age_grid", [](const ck::AgeEstimate& e) { return to_numpy(e.age_grid); })
      .def_property_readonly("density", [](const ck::AgeEstimate& e) { return to_numpy(e.density); })
      .def_readonly("cumulative_fit_age", &ck::AgeEstimate::cumulative_fit_age)
      .def_readonly("cumulative_fit_sigma", &ck::AgeEstimate::cumulative_fit_sigma)
      .def("__repr__", [](const ck::AgeEstimate& e) {
        return "AgeEstimate(median=" + craterkit::format_number(e.median) + " yr, 1 sigma [" +
               craterkit::format_number(e.sigma1_low) + ", " + craterkit::format_number(e.sigma1_high) +
               "] yr)";
      });
  const char* model_age_doc =
      "The model age (years) of the counts under a Production (scaling law) or a ChronologySystem (published "
      "production polynomial and N(1)(t)): Poisson likelihood, uniform prior on [0, max_age].";
  m.def(
      "model_age",
      [](const ck::CraterCounts& counts, const Production& production, double min_diameter,
         double max_diameter, std::optional<double> equilibrium_fraction, double max_age,
         std::size_t grid_points, const std::string& fractions) {
        const auto options =
            age_options(min_diameter, max_diameter, equilibrium_fraction, max_age, grid_points, fractions);
        return ck::fit_model_age(counts, ck::production_function(production.setup, production.radius),
                                 options);
      },
      py::arg("counts"), py::arg("production"), py::arg("min_diameter") = 0.0,
      py::arg("max_diameter") = std::numeric_limits<double>::infinity(),
      py::arg("equilibrium_fraction") = py::none(), py::arg("max_age") = 4.567e9,
      py::arg("grid_points") = 2001, py::arg("fractions") = "weight", model_age_doc);
  m.def(
      "model_age",
      [](const ck::CraterCounts& counts, const ck::ChronologySystem& system, double min_diameter,
         double max_diameter, std::optional<double> equilibrium_fraction, double max_age,
         std::size_t grid_points, const std::string& fractions, const std::string& prior) {
        auto options =
            age_options(min_diameter, max_diameter, equilibrium_fraction, max_age, grid_points, fractions);
        if (prior != "age" && prior != "density")
          throw craterkit::InputError("prior '" + prior + "' is not known; allowed: age, density");
        options.clock = ck::chronology_clock(system);
        options.prior_uniform_in_density = prior == "density";
        return ck::fit_model_age(counts, ck::chronology_production(system), options);
      },
      py::arg("counts"), py::arg("production"), py::arg("min_diameter") = 0.0,
      py::arg("max_diameter") = std::numeric_limits<double>::infinity(),
      py::arg("equilibrium_fraction") = py::none(), py::arg("max_age") = 4.567e9,
      py::arg("grid_points") = 2001, py::arg("fractions") = "weight", py::arg("prior") = "age",
      model_age_doc);

  m.def(
      "sample_laws",
      [](const std::filesystem::path& path, int samples, std::uint64_t seed,
         std::optional<std::string> group) {
        const auto fitted = cs::load_fitted_law(path, group);
        if (!fitted.covariance.has_covariance()) {
          throw craterkit::InputError(path.string() +
                                      " gives no covariance of the constants: nothing to sample");
        }
        auto covariance = fitted.covariance;
        covariance.law = fitted.law;
        return cs::sample_laws(covariance, samples, seed).laws;
      },
      py::arg("fit"), py::arg("samples") = 1000, py::arg("seed") = 1, py::arg("group") = py::none(),
      "Laws drawn from the covariance of a fit JSON (as `--samples N --seed S` of rates and age): seeded, "
      "truncated to the fit's ranges.");
  m.def(
      "relative_rate_spread",
      [](const Production& a, const Production& b, const std::vector<cs::ScalingLaw>& laws, const Array& d) {
        if (laws.empty())
          throw craterkit::InputError("relative_rate_spread needs at least one law (sample_laws)");
        if (a.impactor_density != b.impactor_density) {
          throw craterkit::InputError("relative_rate_spread: the productions' impactor densities differ (" +
                                      craterkit::format_number(a.impactor_density) + " and " +
                                      craterkit::format_number(b.impactor_density) +
                                      " kg/m^3); the draws are one law for both");
        }
        const Array flat = Array::ensure(d.attr("ravel")());
        const auto n = static_cast<std::size_t>(flat.size());
        std::vector<double> columns[9];
        for (auto& c : columns) c.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
          const auto spread = ck::rate_spread(a.setup, laws, b.target, a.target, a.impactor_density,
                                              flat.at(static_cast<py::ssize_t>(i)));
          const cs::Percentiles* ps[3] = {&spread.relative_rate, &spread.rate, &spread.impactor_radius};
          for (int k = 0; k < 3; ++k) {
            columns[3 * k][i] = ps[k]->p16;
            columns[3 * k + 1][i] = ps[k]->p50;
            columns[3 * k + 2][i] = ps[k]->p84;
          }
        }
        const auto shaped = [&](const std::vector<double>& v) {
          return to_numpy(v).attr("reshape")(d.attr("shape"));
        };
        py::dict out;
        const char* names[3] = {"ratio", "rate_b", "impactor_radius_b"};
        for (int k = 0; k < 3; ++k)
          out[names[k]] =
              py::make_tuple(shaped(columns[3 * k]), shaped(columns[3 * k + 1]), shaped(columns[3 * k + 2]));
        return out;
      },
      py::arg("a"), py::arg("b"), py::arg("laws"), py::arg("diameter"),
      "The scaling law's uncertainty in r_B(D)/r_A(D) (as `craterkit rates --fit F --samples N`): each law "
      "of "
      "`laws` (sample_laws) in place of both productions' law, A's set-up and B's cohesion against A's; "
      "ratio, rate_b (per m^2 per year) and impactor_radius_b (m) as (p16, p50, p84) arrays of D's shape.");
  m.def(
      "model_age_spread",
      [](const ck::CraterCounts& counts, const Production& production,
         const std::vector<cs::ScalingLaw>& laws, double min_diameter, double max_diameter,
         std::optional<double> equilibrium_fraction, double max_age, std::size_t grid_points,
         const std::string& fractions) {
        if (laws.empty())
          throw craterkit::InputError("model_age_spread needs at least one law (sample_laws)");
        auto options =
            age_options(min_diameter, max_diameter, equilibrium_fraction, max_age, grid_points, fractions);
        options.cumulative_fit = false;
        const auto spread = ck::model_age_spread(counts, production.setup, laws, production.target,
                                                 production.impactor_density, options);
        py::dict out;
        out["law_median"] = py::make_tuple(spread.median.p16, spread.median.p50, spread.median.p84);
        out["total_median"] = spread.total_median;
        out["total_sigma1"] = py::make_tuple(spread.total_sigma1_low, spread.total_sigma1_high);
        out["total_sigma2"] = py::make_tuple(spread.total_sigma2_low, spread.total_sigma2_high);
        return out;
      },
      py::arg("counts"), py::arg("production"), py::arg("laws"), py::arg("min_diameter") = 0.0,
      py::arg("max_diameter") = std::numeric_limits<double>::infinity(),
      py::arg("equilibrium_fraction") = py::none(), py::arg("max_age") = 4.567e9,
      py::arg("grid_points") = 2001, py::arg("fractions") = "weight",
      "The scaling law's uncertainty in the model age: each law of `laws` (sample_laws) in the production's "
      "place. law_median: 15.87/50/84.13 percentiles of the draws' median ages; total_*: the age density "
      "averaged over the draws (years).");

  py::class_<ck::ChronologySystem>(
      m, "ChronologySystem",
      "A published chronology system: production function (a polynomial, or Hartmann's table of incremental "
      "densities in root-2 diameter bins) and N(1)(t) (data/chronology/).")
      .def_readonly("name", &ck::ChronologySystem::name)
      .def_readonly("title", &ck::ChronologySystem::title)
      .def_readonly("body", &ck::ChronologySystem::body)
      .def_readonly("citation", &ck::ChronologySystem::citation)
      .def_property_readonly(
          "production_form", [](const ck::ChronologySystem& s) { return ck::to_string(s.production_form); },
          "'polynomial' or 'tabular_incremental_root2'.")
      .def_readonly("production_coefficients", &ck::ChronologySystem::production,
                    "Polynomial form: a0 .. an (empty for the tabular form).")
      .def_readonly("incremental_density", &ck::ChronologySystem::incremental_density,
                    "Tabular form: craters per km^2 in [2^((i - index_1km)/2), 2^((i - index_1km + 1)/2)) km "
                    "(empty for the polynomial form).")
      .def_readonly("index_1km", &ck::ChronologySystem::index_1km,
                    "Tabular form: the bin of incremental_density that starts at 1 km.")
      .def_readonly("chronology_coefficients", &ck::ChronologySystem::chronology)
      .def_property_readonly(
          "diameter_range",
          [](const ck::ChronologySystem& s) { return py::make_tuple(s.min_diameter, s.max_diameter); })
      .def(
          "n1",
          [](const ck::ChronologySystem& s, const Array& t) {
            return py::vectorize([&s](double t_) { return ck::n1(s, t_); })(t);
          },
          py::arg("age"), "N(1): craters >= 1 km per km^2 after `age` years.")
      .def(
          "cumulative_density",
          [](const ck::ChronologySystem& s, const Array& d, const Array& t) {
            return py::vectorize([&s](double d_, double t_) { return ck::cumulative_density(s, d_, t_); })(d,
                                                                                                           t);
          },
          py::arg("diameter"), py::arg("age"), "N(>=D) per km^2 (D in m) after `age` years.")
      .def("__repr__", [](const ck::ChronologySystem& s) { return "ChronologySystem('" + s.name + "')"; });
  m.def("chronology_system_names", &ck::chronology_system_names);
  m.def(
      "load_chronology_system", &ck::load_chronology_system, py::arg("name"),
      "A shipped chronology system (chronology_system_names(): 'moon_neukum2001', 'mars_neukum_ivanov2001', "
      "'moon_hartmann2010', 'mars_hartmann2005', 'mars_hartmann_daubar2016') or a system .toml by path.");
}
