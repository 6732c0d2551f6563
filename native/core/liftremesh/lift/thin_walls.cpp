#include "liftremesh/lift/thin_walls.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace liftremesh {

namespace {

// The far side of a wall from x (see wall_thickness): the nearest triangle within `reach` that
// faces against one of `own` (the normals of the triangles x lies on) within kWallTaperDeg,
// is not one of those (`touches`), and lies across from x, along its normal.
double far_side_distance(const AabbTree& tree, const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& own,
                         double reach, const std::function<bool(int32_t)>& touches) {
    const double cos_parallel = -std::cos(kWallTaperDeg * M_PI / 180.0);
    const auto far_side = [&](int32_t f, const Eigen::Vector3d& p) {
        if (touches(f)) return false;
        return std::abs((x - p).dot(tree.triangle_normal(f))) >= -cos_parallel * (x - p).norm();
    };
    const ClosestPoint wall = tree.closest_where(x, reach, {own, cos_parallel}, far_side);
    return wall.triangle >= 0 ? std::sqrt(wall.squared_distance) : std::numeric_limits<double>::infinity();
}

bool has_vertex(const Triangles& triangles, int32_t f, int32_t v) {
    return triangles(f, 0) == v || triangles(f, 1) == v || triangles(f, 2) == v;
}

} // namespace

Eigen::VectorXd wall_thickness(const Mesh& mesh, const AabbTree& tree, double reach) {
    const Eigen::Index nv = mesh.points.rows();
    const CompressedRows around = vertex_triangles(mesh);
    Eigen::VectorXd thickness(nv);
#pragma omp parallel
    {
        std::vector<Eigen::Vector3d> own;
#pragma omp for schedule(dynamic, 256)
        for (Eigen::Index v = 0; v < nv; ++v) {
            own.clear();
            for (const int32_t* f = around.begin(v); f != around.end(v); ++f) own.push_back(tree.triangle_normal(*f));
            const int32_t vertex = static_cast<int32_t>(v);
            thickness[v] = far_side_distance(tree, mesh.points.row(v).transpose(), own, reach,
                                             [&](int32_t f) { return has_vertex(mesh.triangles, f, vertex); });
        }
    }
    return thickness;
}

namespace {

// An edge of the mesh being split and the triangles on it.
struct SplitEdge {
    int32_t a, b;
    std::vector<int32_t> triangles;
};

// The edges longer than min_edge of the triangles marked `fresh`, each with all the triangles on
// it, in order of first use.
std::vector<SplitEdge> long_edges(const Mesh& mesh, double min_edge, const std::vector<char>& fresh) {
    std::vector<SplitEdge> edges;
    std::vector<char> of_fresh;
    std::unordered_map<std::uint64_t, size_t> index;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) {
            const int32_t a = mesh.triangles(f, j), b = mesh.triangles(f, (j + 1) % 3);
            if (!((mesh.points.row(a) - mesh.points.row(b)).norm() > min_edge)) continue;
            const auto [it, added] = index.emplace(edge_key(a, b), edges.size());
            if (added) {
                edges.push_back({a, b, {}});
                of_fresh.push_back(0);
            }
            edges[it->second].triangles.push_back(static_cast<int32_t>(f));
            of_fresh[it->second] |= fresh[static_cast<size_t>(f)];
        }
    size_t kept = 0;
    for (size_t e = 0; e < edges.size(); ++e)
        if (of_fresh[e]) {
            if (kept != e) edges[kept] = std::move(edges[e]);
            ++kept;
        }
    edges.resize(kept);
    return edges;
}

// Splits `triangles` at the midpoints of the edges in `midpoint_of` (edge key -> new vertex),
// each triangle at its longest such edge first, then its halves likewise; conforming, since a
// triangle on each side of an edge splits it at the same vertex.
void split_at_midpoints(const Points& points, const std::unordered_map<std::uint64_t, int32_t>& midpoint_of,
                        Triangles& triangles, std::vector<int32_t>& parent, std::vector<char>& fresh) {
    std::vector<std::array<int32_t, 3>> out;
    std::vector<int32_t> out_parent;
    std::vector<char> out_fresh;
    std::vector<std::array<int32_t, 3>> stack;
    for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
        stack.push_back({triangles(f, 0), triangles(f, 1), triangles(f, 2)});
        bool whole = true;
        while (!stack.empty()) {
            const std::array<int32_t, 3> t = stack.back();
            stack.pop_back();
            int longest = -1;
            double length = 0.0;
            for (int j = 0; j < 3; ++j) {
                if (midpoint_of.count(edge_key(t[j], t[(j + 1) % 3])) == 0) continue;
                const double l = (points.row(t[j]) - points.row(t[(j + 1) % 3])).squaredNorm();
                if (longest < 0 || l > length) longest = j, length = l;
            }
            if (longest < 0) {
                out.push_back(t);
                out_parent.push_back(parent[static_cast<size_t>(f)]);
                out_fresh.push_back(!whole);
                continue;
            }
            whole = false;
            const int32_t a = t[longest], b = t[(longest + 1) % 3], c = t[(longest + 2) % 3];
            const int32_t m = midpoint_of.at(edge_key(a, b));
            stack.push_back({m, b, c});
            stack.push_back({a, m, c});
        }
    }
    triangles.resize(static_cast<Eigen::Index>(out.size()), 3);
    for (size_t f = 0; f < out.size(); ++f)
        for (int j = 0; j < 3; ++j) triangles(static_cast<Eigen::Index>(f), j) = out[f][static_cast<size_t>(j)];
    parent = std::move(out_parent);
    fresh = std::move(out_fresh);
}

} // namespace

WallSampling sample_wall_thickness(const Mesh& mesh, const AabbTree& tree, const WallSamplingParams& params) {
    const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!positive(params.spacing) || !positive(params.min_edge) || !(params.reach >= 0.0) || !(params.nu >= 0.0) ||
        !(params.tolerance >= 0.0) || !std::isfinite(params.tolerance) || params.max_midpoints < 0)
        throw InvalidInput("sample_wall_thickness: the spacing and the shortest edge split must be positive and "
                           "finite, the reach, nu, the tolerance and the most midpoints not negative");
    if (!(params.largest_size >= 0.0) || !std::isfinite(params.largest_size))
        throw InvalidInput("sample_wall_thickness: the largest size must be finite and not negative");
    WallSampling result;
    const double reach = std::max(params.reach, params.largest_size); // the lifting's and the size field's walls
    result.thickness = wall_thickness(mesh, tree, reach);
    Mesh split;                  // the mesh split so far, copied at the first split
    const Mesh* current = &mesh; // the mesh, then `split`
    const auto parent_of = [&](int32_t f) { return result.parent.empty() ? f : result.parent[static_cast<size_t>(f)]; };
    // Triangles not checked yet: all at first, then those the last round made. The others and
    // their vertices keep their values: their halves face as they did.
    std::vector<char> fresh(static_cast<size_t>(mesh.triangles.rows()), 1);
    const auto lifting = [&](double t) { return wall_lifting(t, params.nu, params.spacing); };
    // The far side from x, a point of the input triangles `on` (the split triangles' parents):
    // the split mesh is the same surface, so the input's own tree serves every round.
    const auto far_side = [&](const Eigen::Vector3d& x, const std::vector<int32_t>& on, double reach) {
        thread_local std::vector<Eigen::Vector3d> own;
        own.clear();
        for (int32_t f : on) own.push_back(tree.triangle_normal(f));
        return far_side_distance(tree, x, own, reach,
                                 [&](int32_t f) { return std::find(on.begin(), on.end(), f) != on.end(); });
    };
    // Whether x needs a lifting above interpolated + tolerance: only a wall nearer than
    // sqrt(spacing^2 - 4 (interpolated + tolerance)^2) can ask for it.
    const auto needs = [&](const Eigen::Vector3d& x, double interpolated, const std::vector<int32_t>& on) {
        const double enough = 2.0 * (interpolated + params.tolerance);
        if (!(enough < params.spacing)) return false;
        const double reach = std::min(params.reach, std::sqrt(params.spacing * params.spacing - enough * enough));
        return lifting(far_side(x, on, reach)) - interpolated > params.tolerance;
    };
    // Whether x lies across from a wall thinner than the size interpolated there by more than
    // kWallSizeSplit (WallSamplingParams::largest_size).
    const auto size_of = [&](int32_t v) { return std::min(result.thickness[v], params.largest_size); };
    const auto needs_size = [&](const Eigen::Vector3d& x, double interpolated, const std::vector<int32_t>& on) {
        return params.largest_size > 0.0 && std::isfinite(far_side(x, on, interpolated / kWallSizeSplit));
    };
    // The input triangles the split triangles [begin, end) lie in, each once.
    const auto parents = [&](const int32_t* begin, const int32_t* end) -> const std::vector<int32_t>& {
        thread_local std::vector<int32_t> on;
        on.clear();
        for (const int32_t* f = begin; f != end; ++f) on.push_back(parent_of(*f));
        std::sort(on.begin(), on.end());
        on.erase(std::unique(on.begin(), on.end()), on.end());
        return on;
    };
    for (;;) {
        const auto lifted = [&](int32_t v) { return lifting(result.thickness[v]); };
        // Edges whose midpoint needs more, and the longest edge of triangles whose centroid does.
        const std::vector<SplitEdge> edges = long_edges(*current, params.min_edge, fresh);
        std::vector<char> marked(edges.size(), 0);
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t e = 0; e < edges.size(); ++e) {
            const SplitEdge& edge = edges[e];
            const Eigen::Vector3d middle = 0.5 * (current->points.row(edge.a) + current->points.row(edge.b)).transpose();
            const int32_t* on = edge.triangles.data();
            const std::vector<int32_t>& parent_triangles = parents(on, on + edge.triangles.size());
            marked[e] = needs(middle, 0.5 * (lifted(edge.a) + lifted(edge.b)), parent_triangles) ||
                        needs_size(middle, 0.5 * (size_of(edge.a) + size_of(edge.b)), parent_triangles);
        }
        std::vector<size_t> longest_of(static_cast<size_t>(current->triangles.rows()), edges.size());
        const auto length = [&](size_t e) {
            return (current->points.row(edges[e].a) - current->points.row(edges[e].b)).squaredNorm();
        };
        for (size_t e = 0; e < edges.size(); ++e)
            for (int32_t f : edges[e].triangles) {
                size_t& l = longest_of[static_cast<size_t>(f)];
                if (fresh[static_cast<size_t>(f)] && (l == edges.size() || length(e) > length(l))) l = e;
            }
        std::vector<char> centroid_needs(static_cast<size_t>(current->triangles.rows()), 0);
#pragma omp parallel for schedule(dynamic, 64)
        for (Eigen::Index f = 0; f < current->triangles.rows(); ++f) {
            const size_t l = longest_of[static_cast<size_t>(f)];
            if (l == edges.size() || marked[l]) continue;
            const int32_t a = current->triangles(f, 0), b = current->triangles(f, 1), c = current->triangles(f, 2);
            const Eigen::Vector3d centroid =
                ((current->points.row(a) + current->points.row(b) + current->points.row(c)) / 3.0).transpose();
            const int32_t triangle = static_cast<int32_t>(f);
            const std::vector<int32_t>& parent_triangles = parents(&triangle, &triangle + 1);
            centroid_needs[static_cast<size_t>(f)] =
                needs(centroid, (lifted(a) + lifted(b) + lifted(c)) / 3.0, parent_triangles) ||
                needs_size(centroid, (size_of(a) + size_of(b) + size_of(c)) / 3.0, parent_triangles);
        }
        for (size_t f = 0; f < centroid_needs.size(); ++f)
            if (centroid_needs[f]) marked[longest_of[f]] = 1;

        const long wanted = static_cast<long>(std::count(marked.begin(), marked.end(), 1));
        if (wanted == 0 || static_cast<long>(result.midpoints.size()) + wanted > params.max_midpoints) break;
        if (current == &mesh) { // the first split: the copy it changes
            split = mesh;
            current = &split;
            result.parent.resize(static_cast<size_t>(mesh.triangles.rows()));
            std::iota(result.parent.begin(), result.parent.end(), 0);
        }
        std::unordered_map<std::uint64_t, int32_t> midpoint_of;
        const Eigen::Index first_new = split.points.rows();
        split.points.conservativeResize(first_new + wanted, 3); // once a round, not once a midpoint
        int32_t m = static_cast<int32_t>(first_new);
        for (size_t e = 0; e < edges.size(); ++e) {
            if (!marked[e]) continue;
            midpoint_of.emplace(edge_key(edges[e].a, edges[e].b), m);
            result.midpoints.push_back({edges[e].a, edges[e].b});
            split.points.row(m) = 0.5 * (split.points.row(edges[e].a) + split.points.row(edges[e].b));
            ++m;
        }
        split_at_midpoints(split.points, midpoint_of, split.triangles, result.parent, fresh);
        // The new vertices' thickness, as wall_thickness measures it, on the input triangles they lie on.
        const CompressedRows around = vertex_triangles(split);
        result.thickness.conservativeResize(split.points.rows());
#pragma omp parallel for schedule(dynamic, 64)
        for (Eigen::Index v = first_new; v < split.points.rows(); ++v)
            result.thickness[v] =
                far_side(split.points.row(v).transpose(), parents(around.begin(v), around.end(v)), reach);
    }
    result.triangles = std::move(split.triangles);
    return result;
}

double wall_reach(double nu, double spacing) { return std::sqrt(std::max(0.0, spacing * spacing - 4.0 * nu * nu)); }

double wall_lifting(double t, double nu, double spacing) {
    return t >= wall_reach(nu, spacing) ? nu : std::max(nu, 0.5 * std::sqrt(spacing * spacing - t * t));
}

Eigen::VectorXd thin_wall_lifting(const Eigen::VectorXd& thickness, double nu, double spacing) {
    return thin_wall_lifting(thickness, nu, Eigen::VectorXd::Constant(thickness.size(), spacing));
}

Eigen::VectorXd thin_wall_lifting(const Eigen::VectorXd& thickness, double nu, const Eigen::VectorXd& spacing) {
    Eigen::VectorXd scale(thickness.size());
    for (Eigen::Index v = 0; v < thickness.size(); ++v) scale[v] = wall_lifting(thickness[v], nu, spacing[v]);
    return scale;
}

} // namespace liftremesh
