// The restricted Delaunay triangulation (Eq. 4) of the sites, dual of the restricted Voronoi
// diagram (Section 2.2.3).
#pragma once

#include "liftremesh/rvd.h"

namespace liftremesh {

//! One triangle (k, l, m) for every point of the surface where the restricted cells of sites k,
//! l and m meet (Eq. 4): an RVD polygon vertex made by two bisectors. Oriented like the input
//! triangle the point lies in (the polygon runs in that triangle's order, so its neighbours l
//! then m come counter-clockwise around k); each appears once (the same triple found from
//! other cells, or in two triangles when the point lies on an input edge, is kept once).
//! Indices refer to rows of `sites`.
Triangles restricted_delaunay(const LiftedSurface& surface, const LiftedPoints& sites, int threads = 0);

} // namespace liftremesh
