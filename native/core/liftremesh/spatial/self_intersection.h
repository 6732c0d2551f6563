// Triangles of a surface that pass through each other: what a tetrahedral mesher (TetGen,
// Netgen, Gmsh) refuses in the surface it fills, and what FreeCAD's Mesh workbench reports as
// self-intersections ("Evaluate and repair mesh").
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <array>
#include <utility>
#include <vector>

namespace liftremesh {

//! Whether the segment pq passes through the inside of triangle abc: its ends strictly on
//! either side of the triangle's plane, and the point where it crosses the plane strictly inside
//! the triangle. "Strictly" allows a relative 1e-9 (distances to the plane against |pq|,
//! barycentric coordinates), so touching, as neighbouring faces of a CAD tessellation do, is
//! not crossing. A segment in the plane, or a degenerate triangle, crosses nothing.
bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! Pairs of triangles of `mesh` that cross: a side of one passes through the inside of the
//! other (segment_crosses_triangle), or a corner of one that is not a corner of the other lies
//! on it (within a millionth of its longest side: a touch, as FreeCAD's check counts it between
//! triangles sharing no vertex, where two sheets meet). Triangles sharing an edge are never a
//! pair (a fold onto the neighbour lies in its plane); of two sharing a vertex only the sides
//! away from it are tested. Coplanar overlaps are not counted unless a corner touches. `tree` is AabbTree(mesh). Runs in parallel
//! (OpenMP's default thread count); the count does not depend on it. At most
//! kCandidatesPerTriangle #F pairs of triangles whose boxes meet are tested (a surface has 6 to
//! 8 #F: a triangle's box meets those of the dozen triangles around its corners): past that,
//! in a soup of long triangles across each other's boxes, the count is of those tested only.
//! Throws InvalidInput if an index is out of range.
constexpr long kCandidatesPerTriangle = 200;
long count_self_intersections(const Mesh& mesh, const AabbTree& tree);

//! The pairs count_self_intersections counts, each (s, t) with s < t, sorted.
std::vector<std::pair<int32_t, int32_t>> self_intersecting_pairs(const Mesh& mesh, const AabbTree& tree);

//! Whether two triangles, given by their vertex indices and corners, cross as
//! count_self_intersections counts them (shared vertices told by index).
bool triangles_cross(const std::array<int32_t, 3>& f, const std::array<Eigen::Vector3d, 3>& f_corners,
                     const std::array<int32_t, 3>& g, const std::array<Eigen::Vector3d, 3>& g_corners);

} // namespace liftremesh
