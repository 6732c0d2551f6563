// The remesher's entry point: Algorithm 3 from an input mesh to a clean output mesh and report.
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/params.h"
#include "liftremesh/progress.h"
#include "liftremesh/report.h"

namespace liftremesh {

struct RemeshResult {
    Mesh mesh;           //!< the remeshed surface, in the input's units
    RemeshReport report; //!< quality of input and output, distance, timings
};

//! Remeshes `input` (any triangle soup: welded, checked, never modified):
//!  1. weld exactly equal vertices; centre and scale into the unit ball (Section 5.1); each closed
//!     component apart from the rest (solid_parts.h), steps 2 to 5 running on each piece alone
//!     with its share of the sites, and a small closed piece that does not come out as the
//!     surface it is, with triangles as good as its own, again with more sites or as it was;
//!  2. vertex normals on geometric neighbourhoods of radius eta (5.2.1), densities (Eqs. 22-24),
//!     lifting x + nu n (Eq. 12); with local_sizing, a size per vertex from walls and bends
//!     (size_field.h) in the weights, and with an edge length the vertex count it gives;
//!  3. random sites, L-BFGS on the objective of Eq. 25 in two phases (6.2.2); with hold_creases,
//!     sites held on the creases, and a piece whose surface they break (a defect its input has
//!     not after step 5) remeshed again with its creases snapped to (report.parts_unheld); a
//!     piece whose surface is still broken lifted again with normals over balls a quarter of
//!     the spacing wide and remeshed (report.parts_eta_reduced), the sounder run kept;
//!  4. restricted Delaunay triangulation (Eq. 4) projected to R^3 (Algorithm 3, line 11);
//!  5. a clean oriented manifold (repair.h), holes the input does not have filled (5.2.2);
//!     on an open input, the output's boundary vertices put onto the input's boundary (boundary_snap.h);
//!     the pieces together: small closed pieces standing for no part of the input removed
//!     (stray_components.h), triangles passing through each other untangled (untangle.h);
//!  6. quality report (Eq. 26, Hausdorff distance to the input).
//! Throws InvalidInput (bad mesh or parameters), NumericalFailure, TopologyFailure, Cancelled.
RemeshResult remesh(const Mesh& input, const RemeshParams& params, const ProgressCallback& progress = {});

//! Number of sites the parameters ask for on a mesh of the given area (input units).
long target_site_count(const RemeshParams& params, double area);

} // namespace liftremesh
