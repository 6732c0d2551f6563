// Triangle-mesh arrays and the whole-mesh facts every stage needs (area, Euler characteristic,
// normalisation into the unit ball of Section 5.1).
#pragma once

#include "liftremesh/mesh/compressed_rows.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace liftremesh {

//! #V by 3 vertex positions, row-major so that numpy arrays map without a copy.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
//! #F by 3 vertex indices (0-based), counter-clockwise seen from outside.
using Triangles = Eigen::Matrix<int32_t, Eigen::Dynamic, 3, Eigen::RowMajor>;
//! #V by d lifted vertex positions (d = 3 or 6), row-major.
using LiftedPoints = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

//! A triangle soup with shared vertices.
struct Mesh {
    Points points;       //!< #V by 3
    Triangles triangles; //!< #F by 3
};

//! A mesh with these points and triangles (as the stages that build one in vectors keep them).
Mesh make_mesh(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int32_t, 3>>& triangles);

//! Position of corner j (0, 1, 2) of triangle f.
inline Eigen::Vector3d corner(const Mesh& mesh, Eigen::Index f, int j) {
    return mesh.points.row(mesh.triangles(f, j)).transpose();
}

//! The three vertices of triangle f, in its order.
inline std::array<int32_t, 3> triangle_vertices(const Mesh& mesh, Eigen::Index f) {
    return {mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)};
}

//! Similarity that maps a mesh into the unit ball (Section 5.1): x' = (x - center) / scale.
struct UnitBallTransform {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    double scale = 1.0;
    Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return (x - center) / scale; }
    Eigen::Vector3d undo(const Eigen::Vector3d& x) const { return x * scale + center; }
};

//! Area-weighted centroid as center, largest vertex distance from it as scale.
//! Throws InvalidInput if the mesh has no triangle of positive area.
UnitBallTransform unit_ball_transform(const Mesh& mesh);

//! Applies `t` (or its inverse) to every point of `points` in place.
void apply_transform(const UnitBallTransform& t, Points& points);
void undo_transform(const UnitBallTransform& t, Points& points);

//! Sum of triangle areas.
double surface_area(const Mesh& mesh);

//! Axis-aligned bounding-box diagonal length of the referenced vertices.
double bounding_box_diagonal(const Points& points);

//! The undirected edges of a list of triangles and the triangles' uses of each. Edge e joins
//! a[e] <= b[e]; the edges come in increasing (a, b) order. Its uses are uses.begin(e) ..
//! uses.end(e), in increasing order, each 3 f + j for the side of triangle f from its corner j
//! to its corner j + 1 (mod 3). Made in linear time (a counting sort on a, then each vertex's
//! few edges sorted by b), where a comparison sort of the 3 #F uses would take O(#F log #F) and
//! fall back to heap sort on triangles listed in order, as the restricted Delaunay
//! triangulation lists them. For a mesh
//! under flips and splits, EditableMesh keeps its edges' uses in a hash map instead.
struct EdgeUses {
    std::vector<int32_t> a, b;
    CompressedRows uses;
    long size() const { return static_cast<long>(a.size()); }
    long count(long e) const { return uses.end(e) - uses.begin(e); }
    //! Per side 3 f + j of the `triangles` triangles they were made from, its edge; -1 for the
    //! sides of triangles left out (not live).
    std::vector<int32_t> edge_of_sides(long triangles) const;
};

//! Whether the side `use` (3 f + j, as EdgeUses numbers it) runs from its edge's lower vertex
//! to its higher one. The two triangles on an edge agree in orientation when their sides run
//! opposite ways.
inline bool runs_forward(const Triangles& triangles, int32_t use) {
    const Eigen::Index f = use / 3;
    const int j = use % 3;
    return triangles(f, j) <= triangles(f, j == 2 ? 0 : j + 1);
}

//! The edges of `count` triangles given as 3 count corner indices, of those with live[f] only
//! unless `live` is empty (else it has a flag per triangle). Throws InvalidInput on a negative
//! index or on a `live` of another size.
EdgeUses edge_uses(const int32_t* corners, long count, const std::vector<char>& live = {});
EdgeUses edge_uses(const Triangles& triangles, const std::vector<char>& live = {});

//! Undirected edges (i < j) with the number of triangles using each, sorted by (i, j).
struct EdgeCount {
    int32_t a, b;
    int count;
};
std::vector<EdgeCount> edge_counts(const Triangles& triangles);

//! A 64-bit key of the undirected edge {a, b} (the same for (a, b) and (b, a)), for hash maps.
inline std::uint64_t edge_key(int32_t a, int32_t b) {
    const auto lo = static_cast<std::uint32_t>(a < b ? a : b), hi = static_cast<std::uint32_t>(a < b ? b : a);
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

//! Connected components of the graph on nodes 0 .. n-1 with the given links: writes each node's
//! component into `label` (0 .. count-1, numbered in order of first appearance), returns count.
int connected_components(int n, const std::vector<std::pair<int, int>>& links, std::vector<int>& label);

//! Groups the triangles around vertex v into fans: two triangles are in one fan when a chain of
//! edges (v, w) shared by triangles joins them. `around` lists the corners of the triangles that
//! use v. Writes each triangle's fan into `fan` (0 .. count-1, numbered in order of first
//! appearance) and returns the count: 1 at a manifold vertex, 0 if `around` is empty.
int vertex_fans(int32_t v, const std::vector<std::array<int32_t, 3>>& around, std::vector<int>& fan);

//! #V flags, 1 for the vertices some triangle refers to.
std::vector<char> referenced_vertices(const Mesh& mesh);

//! Row v: the triangles that have vertex v as a corner, in increasing order.
CompressedRows vertex_triangles(const Mesh& mesh);

//! Hash of a vertex triple (FNV-1a over the three indices), for sets of triangles keyed by
//! their vertices (sorted, or rotated to start at the smallest, as the set needs).
struct TriangleKeyHash {
    size_t operator()(const std::array<int32_t, 3>& t) const {
        uint64_t h = 1469598103934665603ull;
        for (int32_t i : t) h = (h ^ static_cast<uint32_t>(i)) * 1099511628211ull;
        return static_cast<size_t>(h);
    }
};

//! V - E + F counting only vertices referenced by a triangle.
int euler_characteristic(const Mesh& mesh);

//! Throws InvalidInput if a triangle refers to a vertex that does not exist. `what` names the
//! mesh or the caller in the message ("input mesh", "make_manifold", ...).
void check_indices(const Mesh& mesh, const std::string& what);

//! Throws InvalidInput naming the problem if indices are out of range, a coordinate is not
//! finite, or the mesh is empty. `what` names the mesh in the message ("input", "output").
void check_mesh(const Mesh& mesh, const char* what);

//! Largest bounding-box diagonal over median edge length that check_extent accepts: about a
//! thousand kilometres of 1 mm triangles. Beyond it a vertex lies far from the rest, as a corrupt
//! file puts one, and the surface itself is a speck in its own bounding box.
constexpr double kMaxExtentRatio = 1e9;

//! Throws InvalidInput when the bounding box of the mesh's vertices is more than kMaxExtentRatio
//! times its median triangle side, giving the coordinates of the vertex farthest from the per-axis
//! median point (indices change with the welding of duplicates).
//! Every vertex counts: call it once the unreferenced ones are removed. `what` names the mesh.
void check_extent(const Mesh& mesh, const char* what);

//! Drops vertices no triangle references and renumbers the triangles (vertices in order of
//! first use). Returns each old vertex's new index, -1 for the dropped.
std::vector<int32_t> remove_unreferenced_vertices(Mesh& mesh);

//! Drops the triangles f with drop[f] set (#F entries), keeping the others in their order; the
//! vertices stay (remove_unreferenced_vertices).
void drop_triangles(Mesh& mesh, const std::vector<char>& drop);

//! The triangles `ids` of `mesh` (rows in that order) with the vertices they use, in order of
//! first use.
Mesh submesh(const Mesh& mesh, const std::vector<int32_t>& ids);

//! Appends the vertices and triangles of `part` to `mesh`.
void append(Mesh& mesh, const Mesh& part);

} // namespace liftremesh
