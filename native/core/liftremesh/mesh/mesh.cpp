#include "liftremesh/mesh/mesh.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <sstream>
#include <string>

namespace liftremesh {

Mesh make_mesh(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int32_t, 3>>& triangles) {
    Mesh mesh;
    mesh.points.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (size_t i = 0; i < points.size(); ++i) mesh.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
    mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t i = 0; i < triangles.size(); ++i)
        for (int j = 0; j < 3; ++j) mesh.triangles(static_cast<Eigen::Index>(i), j) = triangles[i][j];
    return mesh;
}

UnitBallTransform unit_ball_transform(const Mesh& mesh) {
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
        const auto a = corner(mesh, f, 0);
        const auto b = corner(mesh, f, 1);
        const auto c = corner(mesh, f, 2);
        const double area = triangle_area(a, b, c);
        weighted += area * (a + b + c) / 3.0;
        total += area;
    }
    if (!(total > 0.0)) throw InvalidInput("the mesh has no triangle of positive area (expected a surface)");
    UnitBallTransform t;
    t.center = weighted / total;
    double radius = 0.0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            radius = std::max(radius, (corner(mesh, f, j) - t.center).norm());
    t.scale = radius;
    return t;
}

void apply_transform(const UnitBallTransform& t, Points& points) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) = t.apply(points.row(i).transpose()).transpose();
}

void undo_transform(const UnitBallTransform& t, Points& points) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) = t.undo(points.row(i).transpose()).transpose();
}

double surface_area(const Mesh& mesh) {
    double total = 0.0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        total += triangle_area(corner(mesh, f, 0), corner(mesh, f, 1),
                               corner(mesh, f, 2));
    return total;
}

double bounding_box_diagonal(const Points& points) {
    if (points.rows() == 0) return 0.0;
    return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

EdgeUses edge_uses(const int32_t* corners, long count, const std::vector<char>& live) {
    auto ends = [corners](int32_t use) {
        const int32_t* t = corners + 3 * (use / 3);
        const int j = use % 3;
        return std::minmax(t[j], t[j == 2 ? 0 : j + 1]);
    };
    if (!live.empty() && static_cast<long>(live.size()) != count)
        throw InvalidInput("edge_uses: " + std::to_string(live.size()) + " live flags for " + std::to_string(count) +
                           " triangles");
    // The uses by their edge's lower end, each vertex's in increasing order.
    std::vector<std::pair<int32_t, int32_t>> by_low;
    by_low.reserve(3 * static_cast<size_t>(count));
    long vertices = 0; // the largest index + 1
    for (long f = 0; f < count; ++f) {
        if (!live.empty() && !live[f]) continue;
        for (int j = 0; j < 3; ++j) {
            const auto use = static_cast<int32_t>(3 * f + j);
            const auto [lo, hi] = ends(use);
            if (lo < 0) throw InvalidInput("a triangle refers to vertex " + std::to_string(lo));
            by_low.emplace_back(lo, use);
            vertices = std::max(vertices, static_cast<long>(hi) + 1);
        }
    }
    // Grouped by lower end, uses in increasing order: a counting sort, or where the indices
    // are far more than the uses (a few triangles of a large mesh) a comparison sort.
    if (static_cast<size_t>(vertices) <= 4 * by_low.size() + 1024) {
        const CompressedRows low = compress_rows(vertices, by_low);
        size_t i = 0;
        for (int32_t lo = 0; lo < vertices; ++lo)
            for (const int32_t* use = low.begin(lo); use != low.end(lo); ++use) by_low[i++] = {lo, *use};
    } else {
        std::sort(by_low.begin(), by_low.end());
    }
    EdgeUses out;
    out.uses.values.reserve(by_low.size());
    out.uses.offsets.push_back(0);
    std::vector<std::pair<int32_t, int32_t>> around; // (upper end, use) of one vertex
    for (size_t group = 0; group < by_low.size();) {
        const int32_t lo = by_low[group].first;
        around.clear();
        for (; group < by_low.size() && by_low[group].first == lo; ++group)
            around.emplace_back(ends(by_low[group].second).second, by_low[group].second);
        std::sort(around.begin(), around.end());
        for (size_t i = 0; i < around.size(); ++i) {
            if (i == 0 || around[i].first != around[i - 1].first) { // a new edge: close the last one
                if (i > 0) out.uses.offsets.push_back(static_cast<int32_t>(out.uses.values.size()));
                out.a.push_back(lo);
                out.b.push_back(around[i].first);
            }
            out.uses.values.push_back(around[i].second);
        }
        out.uses.offsets.push_back(static_cast<int32_t>(out.uses.values.size()));
    }
    return out;
}

std::vector<int32_t> EdgeUses::edge_of_sides(long triangles) const {
    std::vector<int32_t> edge(3 * static_cast<size_t>(std::max(0L, triangles)), -1);
    for (long e = 0; e < size(); ++e)
        for (const int32_t* use = uses.begin(e); use != uses.end(e); ++use) edge[*use] = static_cast<int32_t>(e);
    return edge;
}

EdgeUses edge_uses(const Triangles& triangles, const std::vector<char>& live) {
    return edge_uses(triangles.data(), static_cast<long>(triangles.rows()), live);
}

std::vector<EdgeCount> edge_counts(const Triangles& triangles) {
    const EdgeUses edges = edge_uses(triangles);
    std::vector<EdgeCount> out(static_cast<size_t>(edges.size()));
    for (long e = 0; e < edges.size(); ++e) out[e] = {edges.a[e], edges.b[e], static_cast<int>(edges.count(e))};
    return out;
}

int connected_components(int n, const std::vector<std::pair<int, int>>& links, std::vector<int>& label) {
    // Scratch kept per thread: the manifold repair and the quality measure call this (through
    // vertex_fans) for every vertex, and allocating here cost more than the work.
    thread_local std::vector<int> parent, label_of_root;
    parent.resize(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) parent[i] = i;
    auto find = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const auto& [a, b] : links) parent[find(a)] = find(b);
    label.assign(static_cast<size_t>(n), -1);
    label_of_root.assign(static_cast<size_t>(n), -1);
    int count = 0;
    for (int i = 0; i < n; ++i) {
        int& root_label = label_of_root[find(i)];
        if (root_label < 0) root_label = count++;
        label[i] = root_label;
    }
    return count;
}

int vertex_fans(int32_t v, const std::vector<std::array<int32_t, 3>>& around, std::vector<int>& fan) {
    const int n = static_cast<int>(around.size());
    // Spokes (w, i): triangle i has the edge (v, w). Triangles with a common spoke share that edge.
    thread_local std::vector<std::pair<int32_t, int>> spokes; // scratch, as in connected_components
    thread_local std::vector<std::pair<int, int>> shared;
    spokes.clear();
    shared.clear();
    for (int i = 0; i < n; ++i)
        for (int32_t w : around[i])
            if (w != v) spokes.emplace_back(w, i);
    std::sort(spokes.begin(), spokes.end());
    for (size_t k = 1; k < spokes.size(); ++k)
        if (spokes[k].first == spokes[k - 1].first) shared.emplace_back(spokes[k].second, spokes[k - 1].second);
    return connected_components(n, shared, fan);
}

CompressedRows vertex_triangles(const Mesh& mesh) {
    std::vector<std::pair<int32_t, int32_t>> pairs;
    pairs.reserve(3 * static_cast<size_t>(mesh.triangles.rows()));
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) pairs.emplace_back(mesh.triangles(f, j), static_cast<int32_t>(f));
    return compress_rows(static_cast<long>(mesh.points.rows()), pairs);
}

std::vector<char> referenced_vertices(const Mesh& mesh) {
    std::vector<char> used(static_cast<size_t>(mesh.points.rows()), 0);
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) used[mesh.triangles(f, j)] = 1;
    return used;
}

int euler_characteristic(const Mesh& mesh) {
    const std::vector<char> used = referenced_vertices(mesh);
    const long v = std::count(used.begin(), used.end(), 1);
    const long e = static_cast<long>(edge_counts(mesh.triangles).size());
    return static_cast<int>(v - e + mesh.triangles.rows());
}

void check_mesh(const Mesh& mesh, const char* what) {
    const std::string name(what);
    if (mesh.points.rows() == 0 || mesh.triangles.rows() == 0)
        throw InvalidInput(name + " mesh is empty: expected at least one triangle");
    if (!mesh.points.allFinite())
        throw InvalidInput(name + " mesh has a non-finite vertex coordinate (NaN or infinity)");
    check_indices(mesh, name + " mesh");
}

void check_indices(const Mesh& mesh, const std::string& what) {
    const auto n = mesh.points.rows();
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) {
            const auto i = mesh.triangles(f, j);
            if (i < 0 || i >= n)
                throw InvalidInput(what + ": triangle " + std::to_string(f) + " refers to vertex " + std::to_string(i) +
                                   ", expected an index in [0, " + std::to_string(n) + ")");
        }
}

void check_extent(const Mesh& mesh, const char* what) {
    const Eigen::Index m = mesh.triangles.rows(), n = mesh.points.rows();
    if (m == 0 || n == 0) return;
    std::vector<double> sides(3 * static_cast<size_t>(m));
    for (Eigen::Index f = 0; f < m; ++f)
        for (int j = 0; j < 3; ++j)
            sides[3 * f + j] =
                (mesh.points.row(mesh.triangles(f, j)) - mesh.points.row(mesh.triangles(f, (j + 1) % 3))).norm();
    auto middle = sides.begin() + static_cast<std::ptrdiff_t>(sides.size() / 2);
    std::nth_element(sides.begin(), middle, sides.end());
    const double median_side = *middle, diagonal = bounding_box_diagonal(mesh.points);
    if (!(median_side > 0.0) || diagonal <= kMaxExtentRatio * median_side) return;
    Eigen::RowVector3d centre;
    std::vector<double> axis(static_cast<size_t>(n));
    for (int k = 0; k < 3; ++k) {
        for (Eigen::Index i = 0; i < n; ++i) axis[i] = mesh.points(i, k);
        std::nth_element(axis.begin(), axis.begin() + n / 2, axis.end());
        centre[k] = axis[n / 2];
    }
    Eigen::Index far = 0;
    (mesh.points.rowwise() - centre).rowwise().squaredNorm().maxCoeff(&far);
    std::ostringstream message;
    message.precision(3);
    message << what << " mesh spans " << diagonal << " (bounding-box diagonal), more than " << kMaxExtentRatio
            << " times its median edge length " << median_side << ": the vertex at ("
            << mesh.points(far, 0) << ", " << mesh.points(far, 1) << ", " << mesh.points(far, 2)
            << ") is far from the rest (a corrupt file?)";
    throw InvalidInput(message.str());
}

namespace {

// Triangles row(0) .. row(count - 1) of `mesh`, with the vertices they use renumbered in order
// of first use; remap[v] is old vertex v's new index, -1 if unused.
template <class Row>
Mesh compacted(const Mesh& mesh, Eigen::Index count, const Row& row, std::vector<int32_t>& remap) {
    remap.assign(static_cast<size_t>(mesh.points.rows()), -1);
    std::vector<int32_t> used;
    Mesh part;
    part.triangles.resize(count, 3);
    for (Eigen::Index k = 0; k < count; ++k)
        for (int j = 0; j < 3; ++j) {
            const int32_t v = mesh.triangles(row(k), j);
            if (remap[v] < 0) {
                remap[v] = static_cast<int32_t>(used.size());
                used.push_back(v);
            }
            part.triangles(k, j) = remap[v];
        }
    part.points.resize(static_cast<Eigen::Index>(used.size()), 3);
    for (size_t i = 0; i < used.size(); ++i) part.points.row(static_cast<Eigen::Index>(i)) = mesh.points.row(used[i]);
    return part;
}

} // namespace

std::vector<int32_t> remove_unreferenced_vertices(Mesh& mesh) {
    std::vector<int32_t> remap;
    mesh = compacted(mesh, mesh.triangles.rows(), [](Eigen::Index f) { return f; }, remap);
    return remap;
}

void drop_triangles(Mesh& mesh, const std::vector<char>& drop) {
    Eigen::Index kept = 0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        if (!drop[static_cast<size_t>(f)]) mesh.triangles.row(kept++) = mesh.triangles.row(f);
    mesh.triangles.conservativeResize(kept, Eigen::NoChange);
}

Mesh submesh(const Mesh& mesh, const std::vector<int32_t>& ids) {
    std::vector<int32_t> remap;
    return compacted(mesh, static_cast<Eigen::Index>(ids.size()), [&ids](Eigen::Index k) { return ids[k]; }, remap);
}

void append(Mesh& mesh, const Mesh& part) {
    const Eigen::Index nv = mesh.points.rows(), nf = mesh.triangles.rows();
    mesh.points.conservativeResize(nv + part.points.rows(), 3);
    mesh.points.bottomRows(part.points.rows()) = part.points;
    mesh.triangles.conservativeResize(nf + part.triangles.rows(), 3);
    mesh.triangles.bottomRows(part.triangles.rows()) = part.triangles.array() + static_cast<int32_t>(nv);
}

} // namespace liftremesh
