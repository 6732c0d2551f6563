#include "liftremesh/mesh/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <utility>

namespace liftremesh {

Eigen::Vector3d triangle_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

bool zero_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return !((b - a).cross(c - a).norm() > 1e-12 * longest2);
}

double triangle_kappa(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double l1 = (b - c).norm(), l2 = (c - a).norm(), l3 = (a - b).norm();
    const double denom = l1 * l2 * l3 * (l1 + l2 + l3);
    if (!(denom > 0.0)) return 0.0;
    const double area = 0.5 * (b - a).cross(c - a).norm();
    return std::clamp(16.0 * area * area / denom, 0.0, 1.0); // Eq. 26
}

double triangle_min_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d* p[3] = {&a, &b, &c};
    double best = 180.0;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d u = *p[(i + 1) % 3] - *p[i];
        const Eigen::Vector3d v = *p[(i + 2) % 3] - *p[i];
        const double nu = u.norm(), nv = v.norm();
        if (!(nu > 0.0 && nv > 0.0)) return 0.0;
        // atan2 of |u x v| and u.v is accurate for tiny and near-180-degree angles alike.
        const double angle = std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / M_PI;
        best = std::min(best, angle);
    }
    return best;
}

Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double len2 = ab.squaredNorm();
    if (!(len2 > 0.0)) return a;
    const double t = std::clamp(ab.dot(p - a) / len2, 0.0, 1.0);
    // The end points exactly, not a + 1.0 * (b - a), so that a point snapped to a corner is on it.
    if (t == 0.0) return a;
    if (t == 1.0) return b;
    return a + t * ab;
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = va + vb + vc;
    if (!(std::abs(denom) > 0.0)) return a; // degenerate triangle: any vertex
    return a + ab * (vb / denom) + ac * (vc / denom);
}

namespace {

// Signed area of (disk of radius r at the origin) intersected with the triangle (0, a, b).
double disk_wedge_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double r) {
    auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    auto sector = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
        return 0.5 * r * r * std::atan2(cross(u, v), u.dot(v));
    };
    const double r2 = r * r;
    if (a.squaredNorm() <= r2 && b.squaredNorm() <= r2) return 0.5 * cross(a, b);
    const Eigen::Vector2d d = b - a;
    const double qa = d.squaredNorm();
    if (!(qa > 0.0)) return 0.0;
    const double qb = a.dot(d), qc = a.squaredNorm() - r2;
    const double disc = qb * qb - qa * qc;
    if (disc <= 0.0) return sector(a, b);
    const double s = std::sqrt(disc);
    const double t1 = (-qb - s) / qa, t2 = (-qb + s) / qa;
    if (t2 <= 0.0 || t1 >= 1.0) return sector(a, b);
    const Eigen::Vector2d p1 = a + d * std::max(t1, 0.0);
    const Eigen::Vector2d p2 = a + d * std::min(t2, 1.0);
    return sector(a, p1) + 0.5 * cross(p1, p2) + sector(p2, b);
}

} // namespace

PlaneFrame plane_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const PlaneFrame none{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    Eigen::Vector3d u1 = b - a;
    const double l1 = u1.norm();
    if (!(l1 > 0.0)) return none;
    u1 /= l1;
    Eigen::Vector3d u2 = (c - a) - u1 * u1.dot(c - a);
    const double l2 = u2.norm();
    if (!(l2 > 1e-14 * l1)) return none;
    u2 /= l2;
    return {u1, u2};
}

double triangle_ball_intersection_area(const Eigen::Vector3d& p, double r, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return triangle_ball_intersection_area(p, r, a, b, c, plane_frame(a, b, c));
}

double triangle_ball_intersection_area(const Eigen::Vector3d& p, double r, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c, const PlaneFrame& frame) {
    const Eigen::Vector3d &u1 = frame.u1, &u2 = frame.u2;
    if (u1.isZero(0.0)) return 0.0; // no area
    const Eigen::Vector3d n = u1.cross(u2);
    const double dist = n.dot(p - a);
    const double rho2 = r * r - dist * dist;
    if (rho2 <= 0.0) return 0.0;
    const double rho = std::sqrt(rho2);
    auto to2d = [&](const Eigen::Vector3d& x) {
        const Eigen::Vector3d q = x - p;
        return Eigen::Vector2d(q.dot(u1), q.dot(u2));
    };
    const Eigen::Vector2d A = to2d(a), B = to2d(b), C = to2d(c);
    const double area = disk_wedge_area(A, B, rho) + disk_wedge_area(B, C, rho) + disk_wedge_area(C, A, rho);
    return std::abs(area);
}

namespace {
// Interleaves the low 21 bits of x with two zero bits between each (for 3D Morton codes).
std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}
} // namespace

std::vector<long> morton_order(const double* xyz, long n, int stride) {
    std::vector<long> order(static_cast<size_t>(std::max(0L, n)));
    if (n <= 0) return order;
    double lo[3], hi[3];
    for (int j = 0; j < 3; ++j) lo[j] = hi[j] = xyz[j];
    for (long i = 0; i < n; ++i)
        for (int j = 0; j < 3; ++j) {
            lo[j] = std::min(lo[j], xyz[i * stride + j]);
            hi[j] = std::max(hi[j], xyz[i * stride + j]);
        }
    const double scale = static_cast<double>((1 << 21) - 1);
    std::vector<std::pair<std::uint64_t, long>> keys(order.size());
    for (long i = 0; i < n; ++i) {
        std::uint64_t code = 0;
        for (int j = 0; j < 3; ++j) {
            const double extent = hi[j] - lo[j];
            const double t = extent > 0.0 ? (xyz[i * stride + j] - lo[j]) / extent : 0.0;
            code |= spread_bits(static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * scale)) << j;
        }
        keys[i] = {code, i};
    }
    std::sort(keys.begin(), keys.end());
    for (long i = 0; i < n; ++i) order[i] = keys[i].second;
    return order;
}

} // namespace liftremesh
