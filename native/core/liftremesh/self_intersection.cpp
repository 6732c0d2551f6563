#include "liftremesh/self_intersection.h"

#include <Eigen/Geometry>

#include <array>
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

// Whether triangles f and g of `mesh`, g != f, cross (see count_self_intersections).
bool cross(const Mesh& mesh, Eigen::Index f, Eigen::Index g) {
    std::array<int32_t, 3> tf, tg;
    int shared = 0;
    for (int i = 0; i < 3; ++i) {
        tf[i] = mesh.triangles(f, i);
        tg[i] = mesh.triangles(g, i);
    }
    for (int32_t u : tf)
        for (int32_t w : tg) shared += u == w;
    if (shared >= 2) return false;
    auto point = [&](int32_t v) { return Eigen::Vector3d(mesh.points.row(v).transpose()); };
    // Quick rejection: the vertices of one not on the other strictly on one side of its plane (no
    // tolerance: a vertex near or on the plane goes on to the exact tests below).
    auto one_side = [&](const std::array<int32_t, 3>& of, const std::array<int32_t, 3>& plane) {
        const Eigen::Vector3d a = point(plane[0]);
        const Eigen::Vector3d n = (point(plane[1]) - a).cross(point(plane[2]) - a);
        int above = 0, below = 0, off = 0;
        for (int32_t v : of) {
            if (v == plane[0] || v == plane[1] || v == plane[2]) continue;
            const double d = n.dot(point(v) - a);
            above += d > 0.0;
            below += d < 0.0;
            ++off;
        }
        return above == off || below == off;
    };
    if (one_side(tg, tf) || one_side(tf, tg)) return false;
    // The sides of `from` that do not end at a vertex of `into`, against `into`.
    auto sides_through = [&](const std::array<int32_t, 3>& from, const std::array<int32_t, 3>& into) {
        auto is_shared = [&](int32_t v) { return v == into[0] || v == into[1] || v == into[2]; };
        const Eigen::Vector3d a = point(into[0]), b = point(into[1]), c = point(into[2]);
        for (int i = 0; i < 3; ++i) {
            const int32_t p = from[i], q = from[(i + 1) % 3];
            if (!is_shared(p) && !is_shared(q) && segment_crosses_triangle(point(p), point(q), a, b, c)) return true;
        }
        return false;
    };
    return sides_through(tf, tg) || sides_through(tg, tf);
}

} // namespace

long count_self_intersections(const Mesh& mesh, const AabbTree& tree) {
    check_indices(mesh, "self-intersection test");
    // Candidates (triangles whose boxes meet) tested in parallel a batch at a time: memory stays
    // bounded, and a soup of long triangles all over each other's boxes stops at the budget.
    constexpr size_t kBatch = size_t{1} << 16;
    const long budget = kCandidatesPerTriangle * static_cast<long>(mesh.triangles.rows());
    std::vector<std::pair<int32_t, int32_t>> batch;
    long pairs = 0, seen = 0;
    auto test_batch = [&]() {
        const auto n = static_cast<long>(batch.size());
        long found = 0;
#pragma omp parallel for schedule(static) reduction(+ : found)
        for (long i = 0; i < n; ++i) found += cross(mesh, batch[i].first, batch[i].second) ? 1 : 0;
        pairs += found;
        batch.clear();
    };
    tree.overlapping_pairs([&](int32_t s, int32_t t) {
        batch.emplace_back(s, t);
        if (batch.size() == kBatch) test_batch();
        return ++seen < budget;
    });
    test_batch();
    return pairs;
}

} // namespace liftremesh
