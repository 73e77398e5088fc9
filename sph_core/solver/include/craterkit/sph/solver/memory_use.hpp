#pragma once
// Memory a simulation holds per particle, by part (Simulation::memory_use; `craterkit simulate --json`
// reports it as bytes_per_particle_by_part; bench/RESULTS.md "Memory of an impact run, by part").

namespace craterkit::sph {

// Capacities over the particle count of the process, in bytes per particle.
struct MemoryUse {
  double particle_fields = 0.0;   // every field of Particles
  double neighbour_lists = 0.0;   // offsets, ends and entries of the kept or packed lists
  double neighbour_search = 0.0;  // the search's anchors, tree and scratch
  double integrator = 0.0;        // the rates and distention at the start of each particle's step
  double rate_pass = 0.0;    // stress force B, 1/rho, m/rho, shear modulus G, signal time, counts, Balsara
  double schedule = 0.0;     // block levels and ticks, active and needed lists, skin bounds, curve order
  double distributed = 0.0;  // exchanges' scratch and halos' anchors (0 in a serial run)
  [[nodiscard]] double total() const {
    return particle_fields + neighbour_lists + neighbour_search + integrator + rate_pass + schedule +
           distributed;
  }
};

}  // namespace craterkit::sph
