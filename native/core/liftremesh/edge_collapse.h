// Collapsing the few very short edges the restricted Delaunay triangulation leaves where two
// sites crowd onto the same crease junction (the feature term pulls both there, Section 6.2.2).
#pragma once

#include "liftremesh/mesh.h"

namespace liftremesh {

//! Collapses interior edges shorter than `ratio` times the median edge length, shortest first,
//! each onto one of its two end points (no new position: vertices stay where the optimisation
//! put them). A collapse is made only if it keeps the surface an oriented manifold with the same
//! Euler characteristic (the link condition; on an open surface, no edge joining two boundary
//! vertices through the inside), turns no triangle by more than 45 degrees, and
//! raises the smallest kappa (Eq. 26) of the triangles around the edge. Of the two end points
//! the more corner-like one (larger angle defect) is kept when both would do. Returns the
//! number of collapses; unreferenced vertices are removed.
long collapse_short_edges(Mesh& mesh, double ratio = 0.35);

} // namespace liftremesh
