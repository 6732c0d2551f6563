// Vertices onto the input's acute creases: the repair of knife edges, where the feature term
// leaves its sites off the edge (Section 6.2.2 and docs/known-gaps.md). Where the input's
// two faces meet at an interior angle under 60 degrees, Eq. 10 has its minimum for a site in
// the wedge's middle plane at r = c cos(beta) / (cos^2(beta) + sigma^2 sin^2(beta)) from the edge
// (2 beta the interior angle, c the distance of its cell's centroid along the faces): 0.37 c at
// 30 degrees and sigma 5, where a right angle gives 0.05 c. The restricted Delaunay triangulation
// then cuts the edge off, and where a row of such sites breaks, joins the two faces across the
// wedge by triangles through its inside.
//
// The creases are the input's edges whose two triangles (a consistently oriented pair) turn by
// more than `min_turn_deg`: on a CAD tessellation a turn of over 120 degrees between neighbours
// is a feature, never a faceted smooth surface, so no tagging heuristic is involved (an input
// whose two faces do not share the crease's vertices has none, and is left as it was). First
// the output vertex nearest to each corner of the creases (an input vertex where one ends or
// several meet), if within `corner_radius`, then each output vertex within `radius` of a crease,
// nearest first, is moved onto it (its closest point there), when the crease is cut deeper than
// `min_depth` there (the vertex's triangles lie farther than that from the point). With the
// feature angle (RemeshParams::feature_angle) the same moves put every crease over it, not only
// the acute ones, on the output's vertices and edges. The edges of
// its fan that then cross the wedge are flipped (the other diagonal of their quad lies at most
// half as far from the input: crease_flip_fits, flip_rules.h), and so are those whose quality
// flip keeps the surface (quality_flip_keeps_surface) and, where the move left a pair under the
// floor, those whose quality flip keeps the new diagonal within `tolerance` of the input, as
// far as the move itself may take the surface (on the wall of a bore an edge or two across, the
// diagonal that mends a triangle up the wall spans more of the bore: a deeper chord). The move
// and its flips stand only together, and only if
// - no more of the triangles they change turn from the input's normal nearest to their
//   centroid by more than 60 degrees than before (a triangle across the wedge, or turned over);
// - the worst kappa (Eq. 26) of those triangles is at least kappa_floor (knife_kappa_floor for
//   a move onto a knife edge);
// - none of them ends farther from the input than both `tolerance` and the farthest of them
//   before;
// - no more edges of the triangles round the fan are folded shut, nor more pairs of them laid
//   through each other (flip_rules.h), than before: beside a knife edge a move and its flips
//   can do either.
// Otherwise the mesh is left as it was. Where the output follows the creases within the
// tolerance already, nothing moves.
#pragma once

#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/reference.h"

#include <limits>
#include <vector>

namespace liftremesh {

struct CreaseSnapParams {
    //! Vertices at most this far from a crease are moved onto it (the pipeline's: steps.h).
    //! Positive and finite.
    double radius = 0.0;
    //! The vertex nearest to a corner of the creases (where one ends or several meet), if it is
    //! at most this far, is moved onto it first. Not negative.
    double corner_radius = 0.0;
    //! Distance from the input (see above; the pipeline's: kInputTolerance, steps.h). Positive
    //! and finite.
    double tolerance = 0.0;
    //! A vertex moves only where the crease is cut deeper than this (its triangles lie farther
    //! from the point): the tolerance for the knife edges' repair, less for every crease over the
    //! feature angle (steps.h). Not negative; a NaN takes the tolerance.
    double min_depth = std::numeric_limits<double>::quiet_NaN();
    //! An input edge is an acute crease when its two triangles' normals turn by more than this
    //! (degrees): 120 is an interior angle under 60 degrees.
    double min_turn_deg = 120.0;
    //! Creases (chains of crease edges joined at their ends) shorter than this in all are left
    //! alone: a scan's noise, a facet's slip. Not negative.
    double min_length = 0.0;
    //! See above; the Hausdorff refinement's floor.
    double kappa_floor = kKappaFloorOnInput;
    //! The floor of a move onto a crease edge turning by more than knife_turn_deg (a knife
    //! edge), in place of kappa_floor: the faces' acute angle leaves the triangles beside such
    //! an edge poorer than elsewhere.
    double knife_kappa_floor = kKappaFloorOnInput;
    //! See knife_kappa_floor; in [0, 180].
    double knife_turn_deg = 120.0;
    //! Where a chain of creases turns by bend_turn_deg degrees or more at an input vertex (a
    //! bend: AcuteCreases::bends) and no edge of the output whose triangles turn by more than 15
    //! degrees passes within bend_distance of it, the output's crease cuts across the bend as a
    //! chord, as round a hole a few edges across: bends_off_mesh_creases lists such bends, each
    //! for a vertex of its own (pipeline.cpp). In [0, 180].
    double bend_turn_deg = 10.0;
    //! See bend_turn_deg. Not negative and finite; 0 lists none.
    double bend_distance = 0.0;
    //! Where two creases converge at a few degrees (a thread's flank and crest running out into
    //! its end face), the strip between them is narrower than an edge: the snap puts one row of
    //! vertices there, on one crease or between the two, and the other crease runs up to a third
    //! of an edge from any crease of the output. crease_gaps lists the points of the creases that
    //! no edge of the output whose triangles turn by more than 15 degrees passes within
    //! bend_distance of and that another crease passes within 2 gap_separation of, across
    //! (AcuteCreases::distance_across; a crease's own bends are bends_off_mesh_creases'), sampled
    //! every bend_distance, farthest first, each at least gap_separation from those listed
    //! before: each for a vertex of its own (pipeline.cpp), whose insertion grades the strip's
    //! triangles down to its width. Not negative and finite; 0 (or a bend_distance of 0) lists
    //! none.
    double gap_separation = 0.0;

    //! The floor beside a crease whose faces turn by `turn_deg`: knife_kappa_floor past
    //! knife_turn_deg, else kappa_floor.
    double kappa_floor_beside(double turn_deg) const { return turn_deg > knife_turn_deg ? knife_kappa_floor : kappa_floor; }
};

struct CreaseSnapStats {
    long creases = 0; //!< input edges found to be acute creases
    long moved = 0;   //!< vertices moved onto them
    long flipped = 0; //!< edges flipped with those moves
};

//! Moves vertices of `mesh` onto the acute creases of `input` (see above); `input_tree` is
//! AabbTree(input). Keeps the mesh's orientation, manifoldness and Euler characteristic (vertex
//! moves and flips only; a flip never makes an edge the mesh has). Throws InvalidInput if a
//! parameter is out of range or an index is.
CreaseSnapStats snap_to_acute_creases(Mesh& mesh, const Reference& input, const CreaseSnapParams& params);

//! The same with the creases found already: `creases` must be AcuteCreases(input.mesh,
//! params.min_turn_deg, any spacing, params.min_length), whose answers do not depend on the
//! spacing, so that the steps that follow the same creases (crease_curves.h) share them.
CreaseSnapStats snap_to_acute_creases(Mesh& mesh, const Reference& input, const AcuteCreases& creases,
                                      const CreaseSnapParams& params);

//! The points of `creases` that no crease of `mesh` passes near (see
//! CreaseSnapParams::gap_separation), farthest first (ties in the creases' order). Throws
//! InvalidInput if bend_distance or gap_separation is negative or not finite, or an index of
//! `mesh` is out of range.
std::vector<Eigen::Vector3d> crease_gaps(const Mesh& mesh, const AcuteCreases& creases, const CreaseSnapParams& params);

//! The bends of `creases` that the creases of `mesh` cut across (see
//! CreaseSnapParams::bend_turn_deg), in AcuteCreases::bends' order; none if params.bend_distance
//! is 0. Throws InvalidInput if bend_turn_deg is outside [0, 180] or bend_distance is negative
//! or not finite, or an index of `mesh` is out of range.
std::vector<AcuteCreases::Bend> bends_off_mesh_creases(const Mesh& mesh, const AcuteCreases& creases,
                                                       const CreaseSnapParams& params);

} // namespace liftremesh
