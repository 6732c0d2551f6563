// Triangle math, in one place: areas and tangent bases in any dimension, closest points,
// the aspect ratio kappa (Eq. 26), and triangle / disk intersection areas (Section 5.2.1).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace liftremesh {

//! Area of the triangle (a, b, c) in R^d, from the Gram determinant (works for d >= 2).
template <typename VecA, typename VecB, typename VecC>
inline double triangle_area(const VecA& a, const VecB& b, const VecC& c) {
    const auto e1 = (b - a).eval();
    const auto e2 = (c - a).eval();
    const double g11 = e1.squaredNorm(), g22 = e2.squaredNorm(), g12 = e1.dot(e2);
    const double det = g11 * g22 - g12 * g12;
    return det > 0.0 ? 0.5 * std::sqrt(det) : 0.0;
}

//! Orthonormal basis (u1, u2) of the plane of triangle (x1, x2, x3) in R^d (Eq. 15).
//! Returns false (basis undefined) when the triangle is flat.
template <int D>
inline bool tangent_basis(const Eigen::Matrix<double, D, 1>& x1, const Eigen::Matrix<double, D, 1>& x2,
                          const Eigen::Matrix<double, D, 1>& x3, Eigen::Matrix<double, D, 1>& u1,
                          Eigen::Matrix<double, D, 1>& u2) {
    u1 = x2 - x1;
    const double n1 = u1.norm();
    if (!(n1 > 0.0)) return false;
    u1 /= n1;
    u2 = (x3 - x1) - u1 * u1.dot(x3 - x1);
    const double n2 = u2.norm();
    if (!(n2 > 1e-14 * n1)) return false;
    u2 /= n2;
    return true;
}

//! Unit normal of a 3D triangle (zero vector if degenerate).
Eigen::Vector3d triangle_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! Whether a 3D triangle has zero area up to rounding: |cross| at most 1e-12 times its longest
//! side squared (an angle of 1e-12 radians is noise, not a shape), or a non-finite cross product.
bool zero_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! Aspect ratio kappa = 4 sin a sin b sin c / (sin a + sin b + sin c) (Eq. 26): 1 for an
//! equilateral triangle, 0 for a degenerate one. Evaluated from the edge lengths l1, l2, l3 and
//! the area A as 16 A^2 / (l1 l2 l3 (l1 + l2 + l3)), the same quantity.
double triangle_kappa(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! Smallest interior angle of a 3D triangle, in degrees (0 for a degenerate one).
double triangle_min_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! Most points a set of segments (a mesh's boundary or creases) is sampled at: 2^20, 24 MiB.
//! Segments of total length L are sampled at most max(spacing, L / kMaxSegmentSamples) apart
//! (segment_sample_spacing): the spacing asked for on any sensible input, a wider one where
//! the segments are many spacings long (a long needle beside a small part), instead of
//! gigabytes of samples. Searches allow for the spacing used, so only their speed changes.
constexpr double kMaxSegmentSamples = 1 << 20;
inline double segment_sample_spacing(double total_length, double spacing) {
    return std::max(spacing, total_length / kMaxSegmentSamples);
}

//! Closest point to p on the segment [a, b] in 3D (a itself when a == b).
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

//! Closest point to p on triangle (a, b, c) in 3D (Ericson, Real-Time Collision Detection 5.1.5).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! p, a point of triangle (a, b, c), put on the triangle's rim when it lies within `within` of
//! it: on the nearest corner within reach, else on the nearest point of the nearest edge within
//! reach, else p itself. A point a rounding away from an edge where two planar facets meet is
//! then on both facets' planes, not on one of them only, a rounding below the other.
Eigen::Vector3d onto_triangle_rim_within(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c, double within);

//! Area of the intersection of triangle (a, b, c) with the ball of radius r centred at p,
//! i.e. of the triangle with the disk cut by the ball in the triangle's plane (Section 5.2.1).
//! Zero for a triangle of no area.
double triangle_ball_intersection_area(const Eigen::Vector3d& p, double r, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c);

//! The same, given the triangle's unit normal n = triangle_normal(a, b, c), for a caller that
//! meets each triangle in many balls.
double triangle_ball_intersection_area(const Eigen::Vector3d& p, double r, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& n);

//! Indices 0..n-1 sorted along a Morton (Z-order) curve of n points, the point i being
//! xyz[i * stride + 0..2]: points near in space come near in the order (cache locality).
std::vector<long> morton_order(const double* xyz, long n, int stride);

} // namespace liftremesh
