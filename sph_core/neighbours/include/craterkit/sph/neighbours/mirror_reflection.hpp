#pragma once
// Particles that crossed a mirror plane (Box::mirror; symmetry = "quarter") are reflected back into the
// domain. The quarter stands for the full, symmetric domain: a particle of the quarter that crosses the
// plane x_a = lower[a] is, in the full domain, a particle whose mirror partner crosses the other way, and
// the partner is the one the quarter must hold. Reflecting it (x_a -> 2 lower[a] - x_a) therefore makes the
// quarter exactly the full run again: its velocity and acceleration components along a change sign, and
// so do the tensor components with one index a (the deviatoric stress and its rate: S_xy and S_xz for
// a = x); scalars are unchanged. Without it a particle that drifted across stays on the wrong side while
// the neighbour search adds its image on the right side: a cohesionless crater floor at zero pressure,
// where nothing pushes particles back, lost 130 of 18,000 particles across the planes of sci.toml within
// 30 s, right on the rays +x and +y along which the crater is measured.
// Called at the end of a step (or block), when every particle is synchronised; the rates stored in the
// particles for the next step are flipped with the state, so the step after continues as it would have.
#include <cstddef>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

// Reflects every particle beyond a mirror plane of the box; returns how many were reflected (the caller
// rebuilds the neighbour lists when any was). Fixed and ejected particles are left alone.
std::size_t reflect_across_mirror_planes(Particles& particles, const Box& box);

}  // namespace craterkit::sph
