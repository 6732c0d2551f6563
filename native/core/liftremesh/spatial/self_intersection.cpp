#include "liftremesh/spatial/self_intersection.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <functional>
#include <utility>
#include <vector>

namespace liftremesh {

bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    constexpr double kStrict = 1e-9;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double n2 = n.squaredNorm();
    if (!(n2 > 0.0)) return false;
    // Signed distances times |n|: of opposite signs, each beyond the tolerance.
    const double dp = n.dot(p - a), dq = n.dot(q - a);
    const double tol = kStrict * std::sqrt(n2) * (q - p).norm();
    if (!((dp > tol && dq < -tol) || (dp < -tol && dq > tol))) return false;
    const Eigen::Vector3d x = p + (dp / (dp - dq)) * (q - p);
    // Barycentric coordinates of x, each n.((next - from) x (x - from)) / |n|^2.
    const std::array<const Eigen::Vector3d*, 3> v = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& from = *v[i];
        const Eigen::Vector3d& next = *v[(i + 1) % 3];
        if (!(n.dot((next - from).cross(x - from)) > kStrict * n2)) return false;
    }
    return true;
}

namespace {

// Whether a corner of `from` that is not one of `onto`'s lies on triangle `onto`: no farther
// than kTouch times its longest side from its plane and inside each of its sides. Two triangles
// of a surface that share at most a vertex meet nowhere else; where one's corner lies on the
// other, as where two sheets meet along a crease each holds a vertex on, FreeCAD's check counts
// the touch and a mesher sees the sheets fused. (Of two sharing a vertex, a corner on the other is a fold
// within the fan: counted too, so that no flip takes a touch off the count by giving the two
// triangles a common vertex.)
bool vertex_touches(const std::array<int32_t, 3>& from_ids, const std::array<Eigen::Vector3d, 3>& from,
                    const std::array<int32_t, 3>& onto_ids, const std::array<Eigen::Vector3d, 3>& onto) {
    constexpr double kTouch = 1e-6;
    const Eigen::Vector3d n = (onto[1] - onto[0]).cross(onto[2] - onto[0]);
    const double n2 = n.squaredNorm();
    if (!(n2 > 0.0)) return false;
    const double longest = std::sqrt(std::max({(onto[1] - onto[0]).squaredNorm(), (onto[2] - onto[1]).squaredNorm(),
                                               (onto[0] - onto[2]).squaredNorm()}));
    const double tol = kTouch * longest, area2 = std::sqrt(n2);
    for (int k = 0; k < 3; ++k) {
        if (from_ids[k] == onto_ids[0] || from_ids[k] == onto_ids[1] || from_ids[k] == onto_ids[2]) continue;
        const Eigen::Vector3d& x = from[k];
        if (!(std::abs(n.dot(x - onto[0])) <= tol * area2)) continue;
        bool inside = true;
        for (int i = 0; i < 3 && inside; ++i) {
            const Eigen::Vector3d& a = onto[i];
            const Eigen::Vector3d& b = onto[(i + 1) % 3];
            // Signed distance of x from side ab, inward positive: n.((b - a) x (x - a)) / (|n| |b - a|).
            inside = n.dot((b - a).cross(x - a)) >= -tol * area2 * (b - a).norm();
        }
        if (inside) return true;
    }
    return false;
}

} // namespace

bool triangles_cross(const std::array<int32_t, 3>& tf, const std::array<Eigen::Vector3d, 3>& pf,
                     const std::array<int32_t, 3>& tg, const std::array<Eigen::Vector3d, 3>& pg) {
    int shared = 0;
    for (int32_t u : tf)
        for (int32_t w : tg) shared += u == w;
    if (shared >= 2) return false;
    if (vertex_touches(tf, pf, tg, pg) || vertex_touches(tg, pg, tf, pf)) return true;
    // Quick rejection: the vertices of one not on the other strictly on one side of its plane (no
    // tolerance: a vertex near or on the plane goes on to the exact tests below).
    auto one_side = [](const std::array<int32_t, 3>& of, const std::array<Eigen::Vector3d, 3>& of_p,
                       const std::array<int32_t, 3>& plane, const std::array<Eigen::Vector3d, 3>& plane_p) {
        const Eigen::Vector3d& a = plane_p[0];
        const Eigen::Vector3d n = (plane_p[1] - a).cross(plane_p[2] - a);
        int above = 0, below = 0, off = 0;
        for (int i = 0; i < 3; ++i) {
            const int32_t v = of[i];
            if (v == plane[0] || v == plane[1] || v == plane[2]) continue;
            const double d = n.dot(of_p[i] - a);
            above += d > 0.0;
            below += d < 0.0;
            ++off;
        }
        return above == off || below == off;
    };
    if (one_side(tg, pg, tf, pf) || one_side(tf, pf, tg, pg)) return false;
    // The sides of `from` that do not end at a vertex of `into`, against `into`.
    auto sides_through = [](const std::array<int32_t, 3>& from, const std::array<Eigen::Vector3d, 3>& from_p,
                            const std::array<int32_t, 3>& into, const std::array<Eigen::Vector3d, 3>& into_p) {
        auto is_shared = [&](int32_t v) { return v == into[0] || v == into[1] || v == into[2]; };
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            if (!is_shared(from[i]) && !is_shared(from[j]) &&
                segment_crosses_triangle(from_p[i], from_p[j], into_p[0], into_p[1], into_p[2]))
                return true;
        }
        return false;
    };
    return sides_through(tf, pf, tg, pg) || sides_through(tg, pg, tf, pf);
}

namespace {

// Whether triangles f and g of `mesh`, g != f, cross (see count_self_intersections).
bool cross(const Mesh& mesh, Eigen::Index f, Eigen::Index g) {
    std::array<int32_t, 3> tf, tg;
    std::array<Eigen::Vector3d, 3> pf, pg;
    for (int i = 0; i < 3; ++i) {
        tf[i] = mesh.triangles(f, i);
        tg[i] = mesh.triangles(g, i);
        pf[i] = mesh.points.row(tf[i]).transpose();
        pg[i] = mesh.points.row(tg[i]).transpose();
    }
    return triangles_cross(tf, pf, tg, pg);
}

//! Calls found(s, t) for each crossing pair (see count_self_intersections), batch by batch.
void for_each_crossing(const Mesh& mesh, const AabbTree& tree, const std::function<void(int32_t, int32_t)>& found) {
    check_indices(mesh, "self-intersection test");
    // Candidates (triangles whose boxes meet) tested in parallel a batch at a time: memory stays
    // bounded, and a soup of long triangles all over each other's boxes stops at the budget.
    constexpr size_t kBatch = size_t{1} << 16;
    const long budget = kCandidatesPerTriangle * static_cast<long>(mesh.triangles.rows());
    std::vector<std::pair<int32_t, int32_t>> batch;
    std::vector<char> crossing;
    long seen = 0;
    auto test_batch = [&]() {
        const auto n = static_cast<long>(batch.size());
        crossing.assign(batch.size(), 0);
#pragma omp parallel for schedule(static)
        for (long i = 0; i < n; ++i) crossing[i] = cross(mesh, batch[i].first, batch[i].second) ? 1 : 0;
        for (long i = 0; i < n; ++i)
            if (crossing[i]) found(batch[i].first, batch[i].second);
        batch.clear();
    };
    tree.overlapping_pairs([&](int32_t s, int32_t t) {
        batch.emplace_back(s, t);
        if (batch.size() == kBatch) test_batch();
        return ++seen < budget;
    });
    test_batch();
}

} // namespace

long count_self_intersections(const Mesh& mesh, const AabbTree& tree) {
    long pairs = 0;
    for_each_crossing(mesh, tree, [&](int32_t, int32_t) { ++pairs; });
    return pairs;
}

std::vector<std::pair<int32_t, int32_t>> self_intersecting_pairs(const Mesh& mesh, const AabbTree& tree) {
    std::vector<std::pair<int32_t, int32_t>> pairs;
    for_each_crossing(mesh, tree, [&](int32_t s, int32_t t) { pairs.emplace_back(std::min(s, t), std::max(s, t)); });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

} // namespace liftremesh
