#pragma once
// Problem set-ups: the initial particle set, the materials and the box of each validation problem.
// Parameters are plain structs (defaults = the standard problem); config.hpp reads them from TOML.
#include <array>
#include <string>
#include <vector>

#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/solver/problem.hpp"

namespace craterkit::sph {

// Sedov-Taylor point blast (Sedov 1959): a cubic lattice of particles_per_side^3 particles filling
// the periodic cube [-box_size/2, box_size/2)^3 at uniform density; the blast energy is deposited
// into the specific energy of the particles within 2h of the centre, weighted by the kernel, or,
// with blast_radius > 0, spread uniformly (same specific energy) over the particles within it.
// A deposit in a handful of particles gives them an entropy so high that, with the continuity
// density, they stay overpressured and hold a sizeable part of the energy (docs/validation.md).
struct SedovSetup {
  std::string material = "ideal_gas_monatomic";
  int particles_per_side = 50;
  double box_size = 1.0;            // m
  double density = 1.0;             // kg/m^3
  double blast_energy = 1.0;        // J
  double background_energy = 1e-6;  // specific internal energy of the ambient gas, J/kg
  double blast_radius = 0.0;        // m; 0: kernel-weighted deposit within 2h
};

// Sod (1978) shock tube in a thin periodic 3D box: x in [-1, 1) (left state for x < 0, right state
// for x >= 0; the second interface at x = +-1 is far from the region |x| < 0.5 used for comparison
// up to t = 0.2), y and z in [0, cross_section) periodic. Particles have equal masses: the left
// lattice has left_particles_per_length per unit length along x, the right lattice is coarser by
// (rho_L/rho_R)^(1/3) so each has the density of its state.
struct SodSetup {
  std::string material = "ideal_gas_diatomic";
  int left_particles_per_length = 100;  // 1/m
  double cross_section = 0.08;          // m, edge of the square cross-section
  double left_density = 1.0, left_pressure = 1.0;
  double right_density = 0.125, right_pressure = 0.1;
};

// Planar impact of two plates along x: the projectile plate x in [-projectile_thickness, 0) moves at
// +impact_velocity into the target plate x in [0, target_thickness) at rest; y and z periodic with
// width cross_section, so the flow is one-dimensional (uniaxial strain). Both at their reference
// density and zero specific energy (zero pressure); a porous plate at its initial distention alpha0 and
// bulk density rho0/alpha0 (cold and unloaded). The materials' strength and porosity are as loaded.
struct PlateImpactSetup {
  std::string projectile_material = "aluminium";
  std::string target_material = "basalt";
  double impact_velocity = 2000.0;     // m/s
  double projectile_thickness = 0.02;  // m
  double target_thickness = 0.04;      // m
  double particle_spacing = 5e-4;      // m (both plates; the lattice spacing along every axis)
  int cross_section_particles = 6;     // lattice cells across y and z
};

// eta: h = eta (m/rho)^(1/3); alpha: the initial artificial-viscosity coefficient.
ProblemSetup make_sedov(const SedovSetup& setup, double eta, double alpha);
ProblemSetup make_sod(const SodSetup& setup, double eta, double alpha);
ProblemSetup make_plate_impact(const PlateImpactSetup& setup, double eta, double alpha);

}  // namespace craterkit::sph
