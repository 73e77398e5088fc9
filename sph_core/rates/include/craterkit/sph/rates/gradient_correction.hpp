#pragma once
// Kernel-gradient correction of Randles & Libersky (1996, CMAME 139, 375, eq. 24; Bonet & Lok 1999,
// CMAME 180, 97, eq. 41):
//   L_i = [ sum_j V_j (x_j - x_i) (x) grad_i W_ij ]^-1,   V_j = m_j / rho_j,
// so that sum_j V_j (f_j - f_i) (L_i grad_i W_ij) is exact for every linear field f, at free surfaces and
// on disordered particles too. The matrix in brackets is symmetric (grad_i W_ij is parallel to x_ij), so
// L_i is, and it is stored as six components per particle (Particles::correction_*).
//
// Solid runs use L_i (rates.hpp) in the velocity gradient that drives the stress rate and in the stress
// divergence of the momentum equation with its matching work term. The bulk of a regular lattice has
// L = c I with c within 2 % of 1; where it matters is within 2h of a free surface, where the uncorrected
// kernel moments are short by 20 % (tangential) to 50 % (normal) (docs/validation.md, "Elastic plate").
//
// Where L comes from: the momentum equation of particle i reads L_j of its neighbours, and the pair force
// m_i m_j (sigma_i L_i / rho_i^2 + sigma_j L_j / rho_j^2) grad_i W_ij stays antisymmetric in (i, j) only
// if both L are the same in the sums of i and of j, so every L must be known before the pair pass. The
// rate pass (rates.hpp) therefore uses in the force the L of every particle's previous rate evaluation
// (Particles::correction_*), and accumulates M_i itself to give the velocity gradient of the stress rate
// the current L_i and to store it for the next evaluation. compute_correction_matrices() below, a separate
// pass over the pairs, gives the current L where there is no previous one (the first evaluation of a run).
// Why not that pass at every evaluation: it cost 30 % of the solid pair pass (callgrind, 249e6 against
// 832e6 instructions, bench/RESULTS.md) for a change of L over one step of order dt |grad v| (dt the
// Courant step, so at most ~0.3 |v_rel|/c of the particle's neighbourhood).
#include <array>

#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"
#include "craterkit/sph/particles/particle_selection.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/rates/rates.hpp"

namespace craterkit::sph {

// Smallest eigenvalue of M below which it is lifted (M + (lambda - lambda_min) I) before inversion, so that
// L has no eigenvalue above 2.5. Measured on a cubic lattice at h = 1.2 dx (cubic spline): M = 0.98 I in the
// bulk; 0.49 normal and 0.78 tangential half a spacing below a flat free surface (corrected in full); 0.29
// at an edge and 0.23 at a corner (lifted to 0.4); a particle with a few neighbours, in a splash or the
// front of a granular flow, has eigenvalues near zero. Without the lift such particles got L of 10 and more,
// multiplied their stress force by as much, and a collapsing granular column blew up (time step 1e-8 s,
// then non-finite positions) within three free-fall times.
inline constexpr double min_correction_eigenvalue = 0.4;

// The smallest eigenvalue of the symmetric 3x3 matrix m = (xx, xy, xz, yy, yz, zz).
[[nodiscard]] double smallest_eigenvalue(const std::array<double, 6>& m) noexcept;

// L from M = sum_j V_j (x_j - x_i) (x) grad_i W_ij (symmetric, xx, xy, xz, yy, yz, zz): M lifted to the
// smallest eigenvalue min_correction_eigenvalue where it is below, then inverted.
[[nodiscard]] std::array<double, 6> correction_matrix(std::array<double, 6> M) noexcept;

// Inverts the symmetric 3x3 matrix m = (xx, xy, xz, yy, yz, zz) into inverse (same order). Returns false,
// leaving inverse untouched, when m is ill-conditioned: |det m| below 1e-3 of the product of its row norms
// (the matrix of a particle with too few neighbours, or all of them in a plane or on a line).
bool invert_symmetric(const std::array<double, 6>& m, std::array<double, 6>& inverse) noexcept;

// Fills Particles::correction_* of the selected particles that are not ejected (fixed ones too: their
// neighbours read their L) from their neighbour lists, with M lifted to min_correction_eigenvalue.
// Reads positions, smoothing lengths and workspace.volume (m/rho, current for every neighbour: after
// update_material_state). period and mirror as in RateOptions. Requires the solid group.
void compute_correction_matrices(Particles& particles, const PairList& pairs, const RateOptions& options,
                                 const RateWorkspace& workspace, const ParticleSelection& selection);

}  // namespace craterkit::sph
