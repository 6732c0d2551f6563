// The restricted Delaunay triangulation (Eq. 4) of the sites, dual of the restricted Voronoi
// diagram (Section 2.2.3), with a vertex per piece of a restricted cell (geogram's "multinerve").
#pragma once

#include "liftremesh/cvt/rvd.h"

namespace liftremesh {

struct RestrictedDelaunayParams {
    //! A piece of a restricted cell smaller than this fraction of the cell's area is taken as
    //! part of the cell's largest piece, not given a vertex of its own: a sliver that a bisector
    //! through a triangle's vertex leaves on a neighbouring triangle would otherwise make a
    //! vertex with a triangle or two.
    double min_piece = 0.05;
    //! Sites [0, held) are held along creases (cvt/crease_sites.h). If there are any, such a
    //! small piece that lies across a knife edge from its cell's largest (normals 90 to 160
    //! degrees apart) and whose triangles would fold shut or pile three on an edge is taken
    //! as its nearest neighbouring cell on its own side instead. Not negative.
    long held = 0;
};

struct RestrictedDelaunay {
    Mesh mesh;         //!< 3D vertices and triangles (rows of mesh.points: see restricted_delaunay)
    long split_sites = 0; //!< sites whose restricted cell came in two or more pieces
};

//! One triangle for every point of the surface where three restricted cells meet (Eq. 4): an
//! RVD polygon vertex made by two bisectors. Oriented like the input triangle the point lies in
//! (the polygon runs in that triangle's order, so its neighbours l then m come
//! counter-clockwise around k); each appears once (the same triple found from other cells, or
//! in two triangles when the point lies on an input edge, is kept once).
//!
//! A restricted cell is usually one piece of surface, and its site one vertex: row k of
//! mesh.points is site k (its first three coordinates, Algorithm 3, line 11). Where the surface
//! is thinner than the cells (two sides of a thin wall, parts that touch at a point) a cell can
//! come in pieces that do not touch, one on each side; joining them through one vertex would
//! bridge the sides and change the topology (Section 2.2 warns of it). As geogram's multinerve
//! RDT does, each piece of such a cell gets a vertex of its own, at the piece's centroid: the
//! first at row k, the others appended after the sites, and each triangle uses the pieces that
//! meet at its point. Pieces of a cell are one when they lie on two triangles sharing an input
//! edge and both reach that edge, or when both reach the input's boundary (so that cracks and
//! gaps that the diagram spans stay closed, as the connectivity-free diagram makes them).
//! `cache` (may be null): as in compute_rvd, such as the optimiser's, left at the sites' last
//! positions; the triangulation is the same with or without it (the diagram's polygons may
//! differ by rounding, as compute_rvd says, which the triangulation does not see unless a
//! point is within rounding of where four cells meet).
RestrictedDelaunay restricted_delaunay(const LiftedSurface& surface, const LiftedPoints& sites, int threads = 0,
                                       const RestrictedDelaunayParams& params = {}, RvdCache* cache = nullptr);

} // namespace liftremesh
