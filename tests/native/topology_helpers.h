// Topology facts of a triangle mesh, computed here from scratch (directed edge counts and vertex
// fans) so that the repair and hole-filling tests do not check the code with itself.
#pragma once

#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace liftremesh::test {

struct Topology {
    long boundary_edges = 0;       //!< undirected edges used by one triangle
    long nonmanifold_edges = 0;    //!< undirected edges used by 3+ triangles
    long misoriented_edges = 0;    //!< edges whose two triangles run the same direction
    long nonmanifold_vertices = 0; //!< vertices whose triangles form 2+ edge-connected fans
    long degenerate = 0;           //!< triangles with a repeated vertex index
    long duplicates = 0;           //!< triangles with the vertex set of an earlier one
    int chi = 0;                   //!< V - E + F over referenced vertices

    //! Every edge used exactly once in each direction, every vertex one fan.
    bool closed_oriented_manifold() const {
        return boundary_edges == 0 && oriented_manifold();
    }
    //! Every edge used at most once in each direction (boundary allowed), every vertex one fan.
    bool oriented_manifold() const {
        return nonmanifold_edges == 0 && misoriented_edges == 0 && nonmanifold_vertices == 0 && degenerate == 0 &&
               duplicates == 0;
    }
};

inline Topology topology(const Mesh& mesh) {
    Topology t;
    const auto& T = mesh.triangles;
    std::map<std::pair<int32_t, int32_t>, int> directed;
    std::set<std::array<int32_t, 3>> sets;
    for (Eigen::Index f = 0; f < T.rows(); ++f) {
        std::array<int32_t, 3> key = {T(f, 0), T(f, 1), T(f, 2)};
        if (key[0] == key[1] || key[1] == key[2] || key[2] == key[0]) ++t.degenerate;
        std::sort(key.begin(), key.end());
        if (!sets.insert(key).second) ++t.duplicates;
        for (int j = 0; j < 3; ++j) ++directed[{T(f, j), T(f, (j + 1) % 3)}];
    }
    std::set<std::pair<int32_t, int32_t>> undirected;
    for (const auto& [e, n] : directed) undirected.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
    for (const auto& [a, b] : undirected) {
        const auto ab = directed.count({a, b}) ? directed.at({a, b}) : 0;
        const auto ba = directed.count({b, a}) ? directed.at({b, a}) : 0;
        if (ab + ba == 1) ++t.boundary_edges;
        if (ab + ba > 2) ++t.nonmanifold_edges;
        if (ab + ba == 2 && (ab == 2 || ba == 2)) ++t.misoriented_edges;
    }
    // Fans: triangles around v joined when they share an edge (v, w).
    std::vector<std::vector<Eigen::Index>> around(static_cast<size_t>(mesh.points.rows()));
    for (Eigen::Index f = 0; f < T.rows(); ++f)
        for (int j = 0; j < 3; ++j) around[T(f, j)].push_back(f);
    long referenced = 0;
    for (size_t v = 0; v < around.size(); ++v) {
        const auto& fs = around[v];
        if (fs.empty()) continue;
        ++referenced;
        std::vector<size_t> parent(fs.size());
        std::iota(parent.begin(), parent.end(), 0);
        auto find = [&](size_t i) {
            while (parent[i] != i) i = parent[i];
            return i;
        };
        std::map<int32_t, size_t> seen;
        for (size_t i = 0; i < fs.size(); ++i)
            for (int j = 0; j < 3; ++j) {
                const int32_t w = T(fs[i], j);
                if (w == static_cast<int32_t>(v)) continue;
                auto it = seen.find(w);
                if (it == seen.end())
                    seen[w] = i;
                else
                    parent[find(i)] = find(it->second);
            }
        std::set<size_t> roots;
        for (size_t i = 0; i < fs.size(); ++i) roots.insert(find(i));
        if (roots.size() > 1) ++t.nonmanifold_vertices;
    }
    t.chi = static_cast<int>(referenced - static_cast<long>(undirected.size()) + T.rows());
    return t;
}

//! Smallest kappa (Eq. 26) of triangles [first, #F).
inline double min_kappa(const Mesh& m, Eigen::Index first = 0) {
    double k = 1.0;
    for (Eigen::Index f = first; f < m.triangles.rows(); ++f)
        k = std::min(k, triangle_kappa(corner(m, f, 0), corner(m, f, 1), corner(m, f, 2)));
    return k;
}

//! Largest angle, in degrees, between the normals of two triangles sharing an edge in opposite
//! directions (0 where the surface is flat, 180 where it folds back onto itself).
inline double largest_dihedral_deg(const Mesh& m) {
    std::map<std::pair<int32_t, int32_t>, Eigen::Index> by_edge; // directed edge -> its triangle
    auto normal = [&](Eigen::Index f) { return triangle_normal(corner(m, f, 0), corner(m, f, 1), corner(m, f, 2)); };
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) by_edge[{m.triangles(f, j), m.triangles(f, (j + 1) % 3)}] = f;
    double largest = 0.0;
    for (const auto& [e, f] : by_edge) {
        const auto twin = by_edge.find({e.second, e.first});
        if (twin == by_edge.end() || e.first > e.second) continue;
        const double c = std::clamp(normal(f).dot(normal(twin->second)), -1.0, 1.0);
        largest = std::max(largest, std::acos(c) * 180.0 / M_PI);
    }
    return largest;
}

//! Number of triangles [first, #F) whose normal points towards `center` (inward on a sphere).
inline long facing_inward(const Mesh& m, const Eigen::Vector3d& center, Eigen::Index first = 0) {
    long n = 0;
    for (Eigen::Index f = first; f < m.triangles.rows(); ++f) {
        const Eigen::Vector3d a = corner(m, f, 0), b = corner(m, f, 1), c = corner(m, f, 2);
        if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - center) <= 0.0) ++n;
    }
    return n;
}

//! A triangle soup: nv random points in [-1, 1]^3, nf triangles of random indices (repeats allowed).
inline Mesh random_soup(std::mt19937& rng, int nv, int nf) {
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    std::uniform_int_distribution<int32_t> index(0, nv - 1);
    Mesh m;
    m.points.resize(nv, 3);
    for (int i = 0; i < nv; ++i) m.points.row(i) << coord(rng), coord(rng), coord(rng);
    m.triangles.resize(nf, 3);
    for (int f = 0; f < nf; ++f) m.triangles.row(f) << index(rng), index(rng), index(rng);
    return m;
}

//! `mesh` without the triangles whose index is in `drop`.
inline Mesh without_triangles(const Mesh& mesh, const std::set<Eigen::Index>& drop) {
    Mesh out;
    out.points = mesh.points;
    out.triangles.resize(mesh.triangles.rows() - static_cast<Eigen::Index>(drop.size()), 3);
    Eigen::Index row = 0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        if (!drop.count(f)) out.triangles.row(row++) = mesh.triangles.row(f);
    return out;
}

//! Indices of the triangles using vertex v.
inline std::set<Eigen::Index> triangles_at(const Mesh& mesh, int32_t v) {
    std::set<Eigen::Index> out;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            if (mesh.triangles(f, j) == v) out.insert(f);
    return out;
}

//! Boundary edges (used by one triangle), counted here from scratch.
inline std::vector<std::pair<int32_t, int32_t>> boundary_edges_of(const Mesh& m) {
    std::map<std::pair<int32_t, int32_t>, int> count;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) {
            const int32_t a = m.triangles(f, j), b = m.triangles(f, (j + 1) % 3);
            ++count[{std::min(a, b), std::max(a, b)}];
        }
    std::vector<std::pair<int32_t, int32_t>> out;
    for (const auto& [e, n] : count)
        if (n == 1) out.push_back(e);
    return out;
}

//! Vertices on boundary edges.
inline std::set<int32_t> boundary_vertices_of(const Mesh& m) {
    std::set<int32_t> out;
    for (const auto& [a, b] : boundary_edges_of(m)) out.insert({a, b});
    return out;
}

//! Largest distance from a boundary vertex of `output` to the boundary edges of `input`.
inline double boundary_gap(const Mesh& output, const Mesh& input) {
    const auto edges = boundary_edges_of(input);
    double worst = 0.0;
    for (int32_t v : boundary_vertices_of(output)) {
        const Eigen::Vector3d p = output.points.row(v).transpose();
        double best = std::numeric_limits<double>::infinity();
        for (const auto& [a, b] : edges)
            best = std::min(best, (closest_point_on_segment(p, input.points.row(a).transpose(),
                                                            input.points.row(b).transpose()) - p).norm());
        worst = std::max(worst, best);
    }
    return worst;
}

//! Distance from x to the nearest vertex of m.
inline double distance_to_nearest_vertex(const Mesh& m, const Eigen::Vector3d& x) {
    return (m.points.rowwise() - x.transpose()).rowwise().norm().minCoeff();
}

//! The unit triangle with an angle of `degrees` at the origin, between the x axis and the
//! direction at `degrees` from it; its other corners are (1, 0) and that direction's unit point.
inline Mesh acute_triangle(double degrees) {
    const double a = degrees * M_PI / 180.0;
    return make_mesh({{0, 0, 0}, {1, 0, 0}, {std::cos(a), std::sin(a), 0}}, {{0, 1, 2}});
}

} // namespace liftremesh::test
