// Edge collapses of the repair:
// - the few very short edges the restricted Delaunay triangulation leaves where two sites crowd
//   onto the same crease junction (the feature term pulls both there, Section 6.2.2);
// - pairs folded shut: two triangles on an edge turned onto each other, their apexes close
//   together (a short edge at a corner of a solid, its triangles turning by nearly 180
//   degrees). Neither triangle is far from the input, nor do they cross, so neither the fold
//   flips of quality_polish.h nor untangle.h see them; a flip alone would leave two slivers. The
//   edge is flipped and the short new edge between the apexes collapsed, which takes both
//   triangles out and joins their apexes. Near a knife edge of the input such a pair, one apex
//   on the knife edge, stands for it and is kept.
#pragma once

#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/reference.h"

namespace liftremesh {

struct ShortEdgeStats {
    long collapsed = 0; //!< edges collapsed, each a vertex fewer
};

struct ShortEdgeParams {
    //! An interior edge shorter than this times the median edge length is collapsed (none if <= 0).
    double ratio = 0.35;
};

//! Collapses interior edges shorter than `params.ratio` times the median edge length, shortest first,
//! each onto one of its two end points (no new position: vertices stay where the optimisation
//! put them). A collapse is made only if it keeps the surface an oriented manifold with the same
//! Euler characteristic (the link condition; on an open surface, no edge joining two boundary
//! vertices through the inside), turns no triangle by more than 45 degrees, folds no more edges
//! shut (flip_rules.h: kCosFolded) than the removed end's fan had, and
//! raises the smallest kappa (Eq. 26) of the triangles around the edge. Of the two end points
//! the more corner-like one (larger angle defect) is kept when both would do. Returns the
//! number of collapses (ShortEdgeStats::collapsed); unreferenced vertices are removed.
ShortEdgeStats collapse_short_edges(Mesh& mesh, const ShortEdgeParams& params);

struct PoorTriangleParams {
    //! A triangle whose kappa (Eq. 26) is under this has its edges tried for a collapse. In [0, 1].
    double kappa_below = kKappaFloor;
    //! The vertex a collapse removes lies on a flat fan: every triangle around it within this
    //! many degrees of their mean normal, so that the triangles the collapse leaves cover the
    //! plane its fan did, and stay on the input. In (0, 90).
    double flat_angle_deg = 8.0;
};

struct PoorTriangleStats {
    long collapsed = 0; //!< edges collapsed, each a vertex fewer
    long split = 0;     //!< edges split, each a vertex more
    long flipped = 0;   //!< edges flipped with a split (below)
    //! The vertices the splits added, as numbered on return (the collapses renumber the
    //! vertices: remove_unreferenced_vertices).
    std::vector<int32_t> added;
};

//! Mends each triangle under params.kappa_below, worst first, as a remesher's last sliver
//! removal does (MMG, CGAL): the polish moves a vertex to its neighbours' centroid and flips the
//! edges of flat quads, and neither helps a vertex sitting inside a thin kite at the centroid
//! already, whose long edge would cross a crease if flipped.
//! - A collapse: each of its edges onto one end point, the other inside the surface (not on its
//!   boundary) on a flat fan (params.flat_angle_deg), under the rules of collapse_short_edges;
//!   the first allowed.
//! - Else a collapse of one of its edges whose end point that goes is not on a flat fan, where
//!   no triangle the collapse moves gets farther from the input than it was (the farthest of its
//!   centroid and edge midpoints) and that point, on the input, stays as near to the triangles
//!   left as its fan was: its fan already cut across a feature finer than the triangles (the
//!   corner of a 0.1 mm terminal, bevelled), and the collapse takes no more of it away. Taken
//!   only if every triangle round the edge ends above kappa_below: short of that, the split
//!   below may do better.
//! - Else a split of its longest edge, an interior one, at the input's point nearest to its
//!   midpoint, if none of the four triangles made turns from the one it comes from by more than
//!   45 degrees or folds onto the triangle across the quad's rim (flip_rules.h: kCosFolded)
//!   where that one did not, and their worst kappa is above that of the edge's two triangles.
//!   An edge whose two triangles turn by more than 45 degrees only if it runs along the input
//!   (that point within 2% of its length from it) and is not folded shut (flip_rules.h:
//!   kCosFolded): along a crease, its halves each stay on their faces, where the halves of a
//!   chord across a crease, or of an edge folded shut, would stay across it or folded. A new
//!   triangle no better than the two old ones is taken if flipping its edge on the quad's rim
//!   (whose two triangles turn by less than 15 degrees: no crease) lifts both triangles of that
//!   edge above them, and the flip is made with the split: a triangle across a strip narrower
//!   than its long edge, its apex near one end, leaves such a half when split alone.
//! - Else, if the triangle across that longest edge has a longer edge, that one split the same
//!   way (the next step of Rivara's longest-edge propagation): a crease's edge beside a strip
//!   narrower than it, whose split's rim flip then takes the poor triangle's edge.
//! The surface keeps its orientation, manifoldness and Euler characteristic. Unreferenced
//! vertices are removed, which renumbers the vertices; PoorTriangleStats::added gives the new
//! ones.
//! \throw InvalidInput if a parameter is out of range or an index is.
PoorTriangleStats mend_poor_triangles(Mesh& mesh, const Reference& input, const PoorTriangleParams& params = {});

struct FoldedPairStats {
    long collapsed = 0; //!< pairs removed, each two triangles and a vertex
};

struct FoldedPairParams {
    //! The two triangles of an edge turn by more than this (degrees), in (90, 180): 150 is an
    //! interior angle under 30 degrees.
    double min_turn_deg = 150.0;
    //! and their apexes lie closer together than this times the edge's length, in (0, 1). A
    //! knife edge's apexes stand apart by 2 sin(beta / 2) times their distance from it (beta its
    //! interior angle: 0.52 at 30 degrees, 0.25 at 14 degrees): below 0.25 a pair is folded
    //! shut unless it follows a knife edge sharper than that, which knife_turn_deg keeps.
    double gap_ratio = 0.25;
    //! No triangle the collapse leaves has a kappa (Eq. 26) under this or under the worst of the
    //! triangles around the four vertices before it, whichever is lower. In [0, 1].
    double kappa_floor = kKappaFloor;
    //! A pair within its edge's length of an acute crease of the input (its triangles turning by
    //! more than this, degrees, in (0, 180): acute_creases.h) is kept. The crease snap's 120.
    double knife_turn_deg = 120.0;
};

//! Removes pairs folded shut (see above): an interior, oriented edge whose two triangles turn by
//! more than params.min_turn_deg, whose apexes lie closer together than params.gap_ratio times
//! its length, one of whose triangles faces against the input's triangle nearest to its centroid
//! (a knife edge of the input, followed, has both on it) and which lies farther than its length
//! from the input's acute creases (params.knife_turn_deg) is flipped to join the apexes, and that
//! edge collapsed, under the rules of collapse_short_edges but for the kappa
//! (params.kappa_floor); where the collapse is not allowed the flip is undone. Each removal
//! takes out two triangles and a vertex and keeps the Euler characteristic; unreferenced
//! vertices are removed.
//! \throw InvalidInput if a parameter is out of range or an index is.
FoldedPairStats collapse_folded_pairs(Mesh& mesh, const Reference& input, const FoldedPairParams& params = {});

} // namespace liftremesh
