// Random initial sites on the lifted surface (Algorithm 3, line 5).
#pragma once

#include "liftremesh/cvt/rvd.h"

#include <cstdint>

namespace liftremesh {

//! `count` points (#count by d) on the valid triangles of `surface`, reproducible for a seed.
//! A triangle is drawn with probability proportional to |T_p| sqrt(w_p), w_p = rho_p^delta:
//! the point density a CVT of weight w reaches in 2D, so the optimiser starts near its goal
//! (with w = 1 this is the uniform sampling of the paper). The point is uniform inside it.
//! Rows come sorted along a Morton curve (near in space, near in memory) for cache locality.
LiftedPoints random_sites(const LiftedSurface& surface, long count, std::uint64_t seed);

//! The sum of |T_p| sqrt(w_p) over the valid triangles: what random_sites draws from. Pieces
//! remeshed on their own share the sites as it would spread them over all of them.
double sampling_mass(const LiftedSurface& surface);

} // namespace liftremesh
