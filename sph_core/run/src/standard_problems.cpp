#include "craterkit/sph/run/standard_problems.hpp"
#include "craterkit/sph/io/material_file.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/particles/kernel.hpp"

namespace craterkit::sph {

namespace {

double ideal_gas_gamma(const Material& material, const char* key) {
  const auto* gas = std::get_if<IdealGas>(&material.eos);
  if (gas == nullptr) {
    throw InputError(std::string(key) + " = \"" + material.name +
                     "\": this set-up needs an ideal-gas material (e.g. ideal_gas_monatomic)");
  }
  return gas->gamma;
}

void add_particle(Particles& p, double x, double y, double z, double mass, double density, double energy,
                  double h, double alpha, std::uint16_t material) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  p.id[i] = i;
  p.material[i] = material;
  p.x[i] = x;
  p.y[i] = y;
  p.z[i] = z;
  p.mass[i] = mass;
  p.density[i] = density;
  p.specific_energy[i] = energy;
  p.smoothing_length[i] = h;
  p.viscosity_alpha[i] = alpha;
}

}  // namespace

ProblemSetup make_sedov(const SedovSetup& s, double eta, double alpha) {
  ProblemSetup out;
  out.materials.push_back(load_material(s.material));
  (void)ideal_gas_gamma(out.materials[0], "sedov.material");
  const int n = s.particles_per_side;
  const double dx = s.box_size / n;
  const double mass = s.density * dx * dx * dx;
  const double h = eta * dx;
  const double half = 0.5 * s.box_size;
  out.particles.reserve(static_cast<std::size_t>(n) * n * n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        add_particle(out.particles, -half + (i + 0.5) * dx, -half + (j + 0.5) * dx, -half + (k + 0.5) * dx,
                     mass, s.density, s.background_energy, h, alpha, 0);
      }
    }
  }
  // Kernel-weighted deposit: u_i += E W(r_i, h) / sum_j m_j W(r_j, h), so sum m_i du_i = E exactly.
  // With blast_radius > 0 the weight is 1 inside the radius (uniform specific energy).
  auto& p = out.particles;
  auto weight_of = [&](std::size_t i) {
    const double r = std::sqrt(p.x[i] * p.x[i] + p.y[i] * p.y[i] + p.z[i] * p.z[i]);
    if (s.blast_radius > 0.0) return r < s.blast_radius ? 1.0 : 0.0;
    return CubicSpline::value(r, h);
  };
  double weight = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) weight += p.mass[i] * weight_of(i);
  if (!(weight > 0.0)) {
    throw InputError("sedov.blast_radius = " + std::to_string(s.blast_radius) +
                     ": no particle inside; use at least one particle spacing (" + std::to_string(dx) +
                     " m)");
  }
  for (std::size_t i = 0; i < p.size(); ++i) p.specific_energy[i] += s.blast_energy * weight_of(i) / weight;
  out.box.lower = {-half, -half, -half};
  out.box.upper = {half, half, half};
  out.box.periodic = {true, true, true};
  return out;
}

ProblemSetup make_sod(const SodSetup& s, double eta, double alpha) {
  ProblemSetup out;
  out.materials.push_back(load_material(s.material));
  const double gamma = ideal_gas_gamma(out.materials[0], "sod.material");
  const double dx_left = 1.0 / s.left_particles_per_length;
  const double mass = s.left_density * dx_left * dx_left * dx_left;
  auto fill = [&](double x0, double x1, double density, double pressure) {
    // Cross-section lattice: as close to cubic cells of the state's density as the width allows.
    const double ideal = std::cbrt(mass / density);
    const int across = std::max(1, static_cast<int>(std::lround(s.cross_section / ideal)));
    const double dy = s.cross_section / across;
    const double dx = mass / (density * dy * dy);
    const auto along = static_cast<int>(std::lround((x1 - x0) / dx));
    const double sx = (x1 - x0) / along;  // exact fill of [x0, x1); density corrected accordingly
    const double rho = mass / (sx * dy * dy);
    const double u = pressure / ((gamma - 1.0) * rho);
    const double h = eta * std::cbrt(mass / rho);
    for (int i = 0; i < along; ++i) {
      for (int j = 0; j < across; ++j) {
        for (int k = 0; k < across; ++k) {
          add_particle(out.particles, x0 + (i + 0.5) * sx, (j + 0.5) * dy, (k + 0.5) * dy, mass, rho, u, h,
                       alpha, 0);
        }
      }
    }
  };
  fill(-1.0, 0.0, s.left_density, s.left_pressure);
  fill(0.0, 1.0, s.right_density, s.right_pressure);
  out.box.lower = {-1.0, 0.0, 0.0};
  out.box.upper = {1.0, s.cross_section, s.cross_section};
  out.box.periodic = {true, true, true};
  return out;
}

ProblemSetup make_plate_impact(const PlateImpactSetup& s, double eta, double alpha) {
  ProblemSetup out;
  out.materials.push_back(load_material(s.projectile_material));
  out.materials.push_back(load_material(s.target_material));
  auto reference_density = [](const Material& m, const char* key) {
    const auto* law = std::get_if<Tillotson>(&m.eos);
    if (law == nullptr) {
      throw InputError(std::string(key) + " = \"" + m.name +
                       "\": the plate impact needs a Tillotson material");
    }
    return law->reference_density;
  };
  const double dx = s.particle_spacing;
  const double width = dx * s.cross_section_particles;
  const double h = eta * dx;
  // A porous plate starts cold and unloaded at its initial distention: bulk density rho0 / alpha0.
  auto distention_of = [](const Material& m) {
    return m.porosity ? m.porosity->crush_curve.initial_distention : 1.0;
  };
  auto fill = [&](double x0, double thickness, double velocity, std::uint16_t id, double matrix_density) {
    const auto layers = static_cast<int>(std::lround(thickness / dx));
    const double distention = distention_of(out.materials[id]);
    const double density = matrix_density / distention;
    const double mass = density * dx * dx * dx;
    for (int i = 0; i < layers; ++i) {
      for (int j = 0; j < s.cross_section_particles; ++j) {
        for (int k = 0; k < s.cross_section_particles; ++k) {
          add_particle(out.particles, x0 + (i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx, mass, density, 0.0,
                       h, alpha, id);
          out.particles.vx.back() = velocity;
          out.particles.distention.back() = distention;
        }
      }
    }
  };
  fill(-s.projectile_thickness, s.projectile_thickness, s.impact_velocity, 0,
       reference_density(out.materials[0], "plates.projectile_material"));
  fill(0.0, s.target_thickness, 0.0, 1, reference_density(out.materials[1], "plates.target_material"));
  out.box.lower = {-s.projectile_thickness, 0.0, 0.0};
  out.box.upper = {s.target_thickness, width, width};
  out.box.periodic = {false, true, true};
  return out;
}

}  // namespace craterkit::sph
