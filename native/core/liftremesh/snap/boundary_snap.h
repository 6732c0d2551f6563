// Putting the output's boundary onto the input's boundary on open surfaces. The restricted
// Delaunay triangulation places every vertex at a site, i.e. at (near) the centroid of its
// restricted Voronoi cell; a cell that touches the input's boundary has its centroid inside it,
// so without this step the output's boundary runs about a third of an edge length inside the
// input's and cuts its corners off. Acute corners, which no output vertex is near enough to, get
// a vertex of their own; triangles hanging beyond the boundary go. Closed inputs are left
// untouched.
#pragma once

#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/reference.h"

#include <cstdint>
#include <vector>

namespace liftremesh {

struct BoundarySnapParams {
    //! A boundary vertex of the input is a corner where its boundary turns by more than this
    //! (degrees, in (0, 180)): the angle between the directions of its two boundary edges.
    //! 30 by default: a polyline approximating a smooth curve turns by its edge length over the
    //! curvature radius, under 30 degrees from 12 segments per full circle on, while the corners
    //! a CAD or FEM shell boundary has by design (rectangles, slots, hexagons) turn 60 degrees
    //! or more.
    double corner_angle_deg = 30.0;
    //! How far an output boundary vertex may move, in units of its local edge length (the mean
    //! length of its boundary edges in the output); > 0, default 1. A vertex farther than this
    //! from the input's boundary belongs to a boundary the input does not have, and stays.
    double reach = 1.0;
    //! A move is refused if it leaves a triangle around the vertex with less than this fraction
    //! of its area before the step (in [0, 1), default 0.25), or turns its normal by 90 degrees
    //! or more (a flip).
    double min_area_ratio = 0.25;
    //! A move is also refused if it leaves a triangle around the vertex with a kappa (Eq. 26)
    //! below this floor and below its kappa before the step (in [0, 1), default kKappaFloor):
    //! a corner left slightly cut is a smaller error than a sliver element.
    double min_kappa = kKappaFloor;
};

struct BoundarySnapStats {
    long input_corners = 0;    //!< corners of the input's boundary (boundary_corners())
    long corners_matched = 0;  //!< of them, those an output vertex was moved onto
    long corners_inserted = 0; //!< of them, those given a vertex of their own (step 3 of
                               //!< snap_boundary()), appended to output.points with a triangle each
    long vertices_snapped = 0; //!< other output boundary vertices moved onto the input's boundary
    long moves_refused = 0;    //!< other output boundary vertices in reach left where they were
                               //!< because their move would spoil a triangle (see snap_boundary())
    long flaps_removed = 0;    //!< triangles removed beyond the input's boundary (step 2b of
                               //!< snap_boundary()), each with its apex
    long moved() const { return corners_matched + vertices_snapped; }
};

//! Corners of the boundary of `mesh` (boundary edge: an edge used by exactly one triangle):
//! boundary vertices where the boundary turns by more than `angle_deg` degrees, plus those with
//! other than two boundary edges (where boundary curves end or meet, a non-manifold boundary).
//! Vertex indices, increasing. Empty for a closed mesh. Throws InvalidInput if an index is out
//! of range or angle_deg is not in [0, 180).
std::vector<int32_t> boundary_corners(const Mesh& mesh, double angle_deg = 30.0);

//! Moves the boundary vertices of `output` onto the boundary of `input` (both in the same
//! coordinates; `output` an oriented manifold, as make_manifold() leaves it). Reach of an output
//! boundary vertex: params.reach times the mean length of its boundary edges.
//!  1. each corner of the input's boundary (boundary_corners()), sharpest turn first, takes the
//!     nearest output boundary vertex within reach that no corner has taken yet and whose move
//!     is allowed (below), and that vertex goes exactly onto the corner;
//!  2. every other output boundary vertex goes to its nearest point on the input's boundary
//!     edges (exact, closest_point_on_segment()), if that point is within reach;
//!  2b. a flap is removed: a triangle whose apex lies beyond the input's boundary (its nearest
//!     point there within reach but back inside the output) and in no other triangle, whose
//!     other two vertices lie on that boundary (within 1e-9 of the mean output boundary edge)
//!     after step 2, and whose edge between them has a triangle on its other side. Its site sat
//!     outside the surface with a cell too small to pull it in; the triangle covers no input,
//!     and the edge opposite the apex becomes boundary;
//!  3. a corner step 1 left with no output boundary vertex within reach (an acute one: the
//!     centroids of the cells near a 20-degree corner lie about 3 edge lengths from it) gets a
//!     vertex of its own, exactly on it, and one triangle joining it to the output boundary edge
//!     that makes the best such triangle (kappa, Eq. 26) among those within 6 reaches of it,
//!     with the corner beyond them (out of the output, in their triangle's plane), the new
//!     triangle not turned over against theirs, and lying on the input: within 0.15 of the
//!     edge's reach of it at the points of a barycentric grid of step 1/4, so that it bridges
//!     no gap to another part. None is made if the best has a kappa below
//!     params.min_kappa / 2, as for a corner sharper than about 4.5 degrees at the default
//!     floor (kappa 0.15).
//! A move (steps 1 and 2) is allowed only if it goes out of the output (along the sum of the
//! outward normals of the vertex's boundary edges, in their triangles' planes: a centroid lies
//! inside its cell, so the input's boundary lies beyond the output's) and leaves every triangle
//! around the vertex unflipped, with at least options.min_area_ratio of its area and a kappa of
//! at least min(params.min_kappa, its kappa before). Moves are made one at a time, corners
//! first then by vertex index, each checked against the triangles as the moves before it left
//! them.
//! Steps 1 and 2 change positions only: the triangles, the topology and every interior vertex
//! stay. Step 2b removes a triangle and its apex per flap (stats.flaps_removed; the vertices are
//! then renumbered, remove_unreferenced_vertices()), step 3 appends a vertex and a triangle per
//! corner (stats.corners_inserted): both keep the Euler characteristic and the boundary loops
//! (one vertex, two edges and one triangle fewer or more).
//! A closed `input` or `output` leaves `output` unchanged, bit for bit. Cost: two edge counts
//! (O(#F)), one pass over the triangles and O(B log B) for the B boundary vertices and edges;
//! step 3, for each corner left, 12 distance queries per candidate triangle.
//! Step 3 queries input.tree.
//! \throw InvalidInput if an index is out of range or a parameter outside its range.
BoundarySnapStats snap_boundary(Mesh& output, const Reference& input, const BoundarySnapParams& params = {});

} // namespace liftremesh
