#include "craterkit/sph/rates/stress_rates.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>

#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/material_response.hpp"
#include "craterkit/sph/physics/p_alpha.hpp"

namespace craterkit::sph {

void update_material_state(Particles& p, std::span<const Material> materials, RateWorkspace& workspace,
                           std::vector<double>& shear_modulus, const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
  for (std::size_t k = 0; k < selection.size(); ++k) {  // the particles evaluated, not every particle
    const auto id = p.material[selection.at(k)];
    if (id >= materials.size()) {
      throw std::out_of_range("particle material id " + std::to_string(id) + " has no material (" +
                              std::to_string(materials.size()) + " materials)");
    }
  }
  workspace.inverse_density.resize(p.size());
  workspace.volume.resize(p.size());
  shear_modulus.resize(p.size());
  // Dynamic: the cost differs from particle to particle (a return to the crush curve, the yield), and
  // substeps often hold a few hundred active particles, which a static split would share unevenly.
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    const double rho = p.density[i];
    const Material& material = materials[p.material[i]];
    MaterialState s =
        evaluate_material(material, rho, p.specific_energy[i], p.distention[i], p.total_strain[i]);
    // Tensile porosity (late stage, PAlphaPorosity::opens_in_tension): a matrix stretched below its
    // reference density, alpha rho < rho_m0, opens pores instead of holding a tension: alpha = rho_m0 / rho
    // puts P_m = A_low (alpha rho / rho_m0 - 1) at zero, so that any compression loads the particle at once.
    // Applied again to the same density it gives the same alpha (restarts stay bitwise). Below P_e such a
    // distention may exceed alpha0; the crush curve binds above P_e only (skipped below).
    const bool opens = material.porosity && material.porosity->opens_in_tension;
    if (opens && (p.flags[i] & particle_fixed) == 0) {
      if (const auto* law = std::get_if<LowSoundSpeed>(&material.eos);
          law != nullptr && p.distention[i] * rho < law->reference_density) {
        p.distention[i] = law->reference_density / rho;
        s = evaluate_material(material, rho, p.specific_energy[i], p.distention[i], p.total_strain[i]);
      }
    }
    // Plastic compaction in algebraic form (material_response.hpp): a state left above the crush curve by
    // the last update (a shock front, or the first step past P_e) is put back on it. Skipped within a
    // relative 1e-9 of the curve: the return itself lands on it only to the tolerance of its root
    // finder, and returning again would change the last bits, so that a run resumed from a checkpoint
    // would not continue bitwise (as for the radial return below). Fixed particles do not evolve.
    if (material.porosity && (p.flags[i] & particle_fixed) == 0 &&
        !(opens && s.pressure <= material.porosity->crush_curve.elastic_pressure)) {
      const PAlphaParameters& crush = material.porosity->crush_curve;
      const double alpha = p.distention[i];
      if (alpha > crush_curve_distention(crush, s.pressure) * (1.0 + 1e-9)) {
        const double returned = return_to_crush_curve(material.eos, crush, rho, p.specific_energy[i], alpha);
        if (returned < alpha) {
          p.distention[i] = returned;
          s = evaluate_material(material, rho, p.specific_energy[i], returned, p.total_strain[i]);
        }
      }
    }
    p.pressure[i] = s.pressure;
    p.sound_speed[i] =
        std::sqrt(s.matrix_sound_speed * s.matrix_sound_speed + 4.0 / 3.0 * s.shear_modulus / rho);
    shear_modulus[i] = s.shear_modulus;
    workspace.inverse_density[i] = 1.0 / rho;
    workspace.volume[i] = p.mass[i] / rho;
    // Radial return, skipped within a relative 1e-12 of the yield surface: a returned stress lies on it
    // only to rounding, and returning it again would change its last bits, so that a run resumed from
    // a checkpoint (whose constructor evaluates this phase once more) would not continue bitwise.
    const DeviatoricStress stress{p.stress_xx[i], p.stress_xy[i], p.stress_xz[i], p.stress_yy[i],
                                  p.stress_yz[i]};
    if (std::sqrt(second_invariant(stress)) > s.yield_strength * (1.0 + 1e-12)) {
      const DeviatoricStress returned = radial_return(stress, s.yield_strength);
      p.stress_xx[i] = returned.xx;
      p.stress_xy[i] = returned.xy;
      p.stress_xz[i] = returned.xz;
      p.stress_yy[i] = returned.yy;
      p.stress_yz[i] = returned.yz;
    }
  }
}

void compute_stress_rates(Particles& p, std::span<const Material> materials,
                          const VelocityGradients& gradients, std::span<const double> shear_modulus,
                          const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    const bool moving = (p.flags[i] & (particle_fixed | particle_ejected)) == 0;
    Tensor3 L{};
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) L[a][b] = moving ? gradients.corrected[3 * a + b][i] : 0.0;
    }
    store_stress_rate(p, i, L, moving ? shear_modulus[i] : 0.0, materials[p.material[i]]);
  }
}

void limit_compaction(Particles& p, std::span<const Material> materials,
                      std::span<const double> distention_before, const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    const Material& material = materials[p.material[i]];
    const double before = distention_before[i];
    if (!material.porosity || !(p.distention[i] < before)) continue;
    const PAlphaParameters& crush = material.porosity->crush_curve;
    // Nothing to bound where the corrected state is on or above the curve (one EOS evaluation instead of
    // the root finding).
    const double alpha = p.distention[i];
    const double pressure =
        evaluate(material.eos, alpha * p.density[i], p.specific_energy[i]).pressure / alpha;
    if (alpha >= crush_curve_distention(crush, pressure)) continue;
    const double lowest =
        return_to_crush_curve(material.eos, crush, p.density[i], p.specific_energy[i], before);
    p.distention[i] = std::max(p.distention[i], lowest);
  }
}

void compute_distention_rates(Particles& p, std::span<const Material> materials,
                              const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    const Material& material = materials[p.material[i]];
    double rate = 0.0;
    if (material.porosity && (p.flags[i] & (particle_fixed | particle_ejected)) == 0) {
      const PAlphaParameters& crush = material.porosity->crush_curve;
      const double pressure = p.pressure[i];
      // Compaction only on the crush curve between P_e and P_s (distention_rate() tests the rest): the
      // matrix derivatives are evaluated only there, i.e. in the few particles that are compacting.
      if (pressure > crush.elastic_pressure && pressure < crush.solid_pressure) {
        const double alpha = p.distention[i];
        const double rho = p.density[i];
        const EosState m = evaluate(material.eos, alpha * rho, p.specific_energy[i]);
        rate = distention_rate(crush, alpha, pressure, rho, p.density_rate[i], p.energy_rate[i],
                               MatrixResponse{m.dpressure_ddensity, m.dpressure_denergy});
      }
    }
    p.distention_rate[i] = rate;
  }
}

}  // namespace craterkit::sph
