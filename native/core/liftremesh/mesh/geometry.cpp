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

Eigen::Vector3d onto_triangle_rim_within(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c, double within) {
    const Eigen::Vector3d* corners[3] = {&a, &b, &c};
    const Eigen::Vector3d* nearest = nullptr;
    double best = within;
    for (const Eigen::Vector3d* x : corners) {
        const double d = (*x - p).norm();
        if (d <= best) best = d, nearest = x;
    }
    if (nearest) return *nearest;
    Eigen::Vector3d out = p;
    best = within;
    for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d q = closest_point_on_segment(p, *corners[j], *corners[(j + 1) % 3]);
        const double d = (q - p).norm();
        if (d <= best) best = d, out = q;
    }
    return out;
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

// Whether o + x lies inside the triangle o + p[0..2] of unit normal n (x and p taken from o):
// on the inner side of its three edges.
bool in_triangle(const Eigen::Vector3d p[3], const Eigen::Vector3d& n, const Eigen::Vector3d& x) {
    for (int i = 0; i < 3; ++i)
        if (!(n.dot((p[i == 2 ? 0 : i + 1] - p[i]).cross(x - p[i])) > 0.0)) return false;
    return true;
}

// The arcs a ball's rim leaves in triangles far smaller than it, as the eta-ball normals clip by
// the million, are small angles: as wide as a triangle seen from the ball's centre. Up to
// atan(1/8) (7.1 degrees) the odd series of atan to t^15 gives them: its next term, t^17 / 17,
// is under 2.6e-17, below the angle's rounding, and it costs a fraction of atan2.
constexpr double kSeriesMaxTan = 0.125;

double small_atan(double t) {
    const double t2 = t * t;
    return t * (1.0 + t2 * (-1.0 / 3 + t2 * (1.0 / 5 + t2 * (-1.0 / 7 + t2 * (1.0 / 9 + t2 * (-1.0 / 11 +
                                                                   t2 * (1.0 / 13 + t2 * (-1.0 / 15))))))));
}

} // namespace

double triangle_ball_intersection_area(const Eigen::Vector3d& o, double r, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return triangle_ball_intersection_area(o, r, a, b, c, triangle_normal(a, b, c));
}

// The ball meets the triangle's plane in a disk of radius rho about o's foot o' = o + h n. The
// area of triangle and disk is half the integral of n . (x - o') x dx round their common
// boundary (Green): the parts of the edges inside the ball, each giving n . (x cross y) for its
// ends x and y, and the arcs of the circle from where that boundary leaves it to where it comes
// back, each giving rho^2 times its angle. Taken from o rather than o', points of the plane give
// the same n . (x cross y), and x . y less h^2. One arctangent per arc, where a sum of signed
// wedges over the three edges takes up to six atan2.
double triangle_ball_intersection_area(const Eigen::Vector3d& o, double r, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& n) {
    const Eigen::Vector3d p[3] = {a - o, b - o, c - o};
    const double whole2 = n.dot((p[1] - p[0]).cross(p[2] - p[0])); // twice the triangle's area
    if (!(whole2 > 0.0)) return 0.0; // no area, or no normal
    const double h = n.dot(p[0]), r2 = r * r, rho2 = r2 - h * h;
    if (!(rho2 > 0.0)) return 0.0; // the ball misses the plane
    bool in[3];
    for (int i = 0; i < 3; ++i) in[i] = p[i].squaredNorm() <= r2;
    if (in[0] && in[1] && in[2]) return 0.5 * whole2;
    // The parts of the edges inside the ball, in the triangle's order: from `from` to `to`, which
    // are corners when `from_corner` / `to_corner`, else points on the circle.
    struct Part {
        Eigen::Vector3d from, to;
        bool from_corner, to_corner;
        int edge; // from corner `edge` to the next
    } parts[3];
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        const int j = i == 2 ? 0 : i + 1;
        const Eigen::Vector3d d = p[j] - p[i];
        const double qa = d.squaredNorm(), qb = p[i].dot(d), qc = p[i].squaredNorm() - r2;
        Part& part = parts[count];
        part.edge = i;
        part.from_corner = in[i];
        part.to_corner = in[j];
        if (in[i] && in[j]) {
            part.from = p[i];
            part.to = p[j];
            ++count;
            continue;
        }
        // |p_i + t d|^2 = r^2 at t = (-qb -+ s) / qa: the edge enters the ball at the first root
        // and leaves it at the second. A corner inside puts the roots on either side of it.
        const double disc = qb * qb - qa * qc;
        if (!(qa > 0.0) || (!in[i] && !in[j] && !(disc > 0.0))) continue;
        const double s = std::sqrt(std::max(disc, 0.0));
        const double t_in = in[i] ? 0.0 : std::clamp((-qb - s) / qa, 0.0, 1.0);
        const double t_out = in[j] ? 1.0 : std::clamp((-qb + s) / qa, 0.0, 1.0);
        if (!in[i] && !in[j] && !(t_in < t_out)) continue; // the line meets the ball off the edge
        part.from = in[i] ? p[i] : Eigen::Vector3d(p[i] + t_in * d);
        part.to = in[j] ? p[j] : Eigen::Vector3d(p[i] + t_out * d);
        ++count;
    }
    const Eigen::Vector3d foot = h * n; // o', taken from o
    if (count == 0) // no edge meets the ball: the disk lies inside the triangle, or apart from it
        return in_triangle(p, n, foot) ? M_PI * rho2 : 0.0;
    double twice = 0.0;
    for (int k = 0; k < count; ++k) {
        const Part& part = parts[k];
        twice += n.dot(part.from.cross(part.to));
        if (part.to_corner) continue;
        // The arc from where this part leaves the ball, counter-clockwise, to where the next one
        // enters it: an angle in [0, 2 pi), from its sine and cosine (times rho^2).
        const Part& next = parts[k + 1 == count ? 0 : k + 1];
        const Eigen::Vector3d &x = part.to, &y = next.from;
        const double sine = n.dot(x.cross(y)), cosine = x.dot(y) - h * h;
        double angle = cosine > 0.0 && std::abs(sine) <= kSeriesMaxTan * cosine ? small_atan(sine / cosine)
                                                                               : std::atan2(sine, cosine);
        // Leaving and coming back at nearly one point, the arc is nearly nothing or nearly the
        // whole circle, which rounding alone may decide. Near the corner between two edges it is
        // nothing: a circle through a corner has points outside its angle (less than pi) on both
        // sides of it. On one edge, it goes round if the disk's centre is inside the triangle (the
        // disk is then all inside but a sliver), and not if it is outside (a sliver is inside).
        const bool round =
            std::abs(angle) < 1e-7 ? next.edge == part.edge && in_triangle(p, n, foot) : angle < 0.0;
        if (round) angle += 2.0 * M_PI;
        twice += rho2 * std::max(angle, 0.0);
    }
    return std::clamp(0.5 * twice, 0.0, 0.5 * whole2);
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
