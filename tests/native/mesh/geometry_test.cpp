#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/mesh.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <vector>

using namespace liftremesh;

namespace {

// Area of triangle (a, b, c) inside the ball of radius r about p, computed the independent way:
// in the triangle's plane, the signed areas of the disk within the wedges (centre, edge), one per
// edge, each a sector and a triangle or two (up to two atan2 an edge), as the library did
// before. A reference for triangle_ball_intersection_area, which integrates round the boundary
// instead; but not where p's foot lies on a corner or on an edge's line between its ends, as at
// a T-junction: a wedge's angle is then the atan2 of rounding errors (an exact zero vector, or
// exactly opposite ones, aside).
double wedge_sum_ball_area(const Eigen::Vector3d& p, double r, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    Eigen::Vector3d u1 = b - a, u2 = c - a;
    if (!(u1.norm() > 0.0)) return 0.0;
    u1.normalize();
    u2 -= u1 * u1.dot(u2);
    if (!(u2.norm() > 1e-14 * (b - a).norm())) return 0.0;
    u2.normalize();
    const double dist = u1.cross(u2).dot(p - a), rho2 = r * r - dist * dist;
    if (rho2 <= 0.0) return 0.0;
    auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    auto sector = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
        return 0.5 * rho2 * std::atan2(cross(u, v), u.dot(v));
    };
    auto wedge = [&](const Eigen::Vector2d& s, const Eigen::Vector2d& t) { // disk within (0, s, t)
        if (s.squaredNorm() <= rho2 && t.squaredNorm() <= rho2) return 0.5 * cross(s, t);
        const Eigen::Vector2d d = t - s;
        const double qa = d.squaredNorm();
        if (!(qa > 0.0)) return 0.0;
        const double qb = s.dot(d), qc = s.squaredNorm() - rho2, disc = qb * qb - qa * qc;
        if (disc <= 0.0) return sector(s, t);
        const double t1 = (-qb - std::sqrt(disc)) / qa, t2 = (-qb + std::sqrt(disc)) / qa;
        if (t2 <= 0.0 || t1 >= 1.0) return sector(s, t);
        const Eigen::Vector2d p1 = s + d * std::max(t1, 0.0), p2 = s + d * std::min(t2, 1.0);
        return sector(s, p1) + 0.5 * cross(p1, p2) + sector(p2, t);
    };
    auto planar = [&](const Eigen::Vector3d& x) { return Eigen::Vector2d((x - p).dot(u1), (x - p).dot(u2)); };
    const Eigen::Vector2d A = planar(a), B = planar(b), C = planar(c);
    return std::abs(wedge(A, B) + wedge(B, C) + wedge(C, A));
}

} // namespace

TEST(Geometry, KappaIsOneForEquilateralAndZeroForDegenerate) {
    const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2, 0);
    EXPECT_NEAR(triangle_kappa(a, b, c), 1.0, 1e-12);
    EXPECT_NEAR(triangle_kappa(a, b, Eigen::Vector3d(2, 0, 0)), 0.0, 1e-12);
    // Right isosceles: angles 90, 45, 45 -> 4 sin90 sin45 sin45 / (1 + 2 sin45)
    const double s = std::sqrt(0.5), expected = 4 * s * s / (1 + 2 * s);
    EXPECT_NEAR(triangle_kappa(a, b, Eigen::Vector3d(0, 1, 0)), expected, 1e-12);
}

TEST(Geometry, TriangleAreaIsDimensionFree) {
    Eigen::Matrix<double, 6, 1> a = Eigen::Matrix<double, 6, 1>::Zero(), b = a, c = a;
    b[0] = 2;
    c[4] = 3; // a right triangle in the (x0, x4) plane of R^6
    EXPECT_NEAR(triangle_area(a, b, c), 3.0, 1e-14);
}

TEST(Geometry, BallIntersectionAreaMatchesLimits) {
    const Eigen::Vector3d a(-10, -10, 0), b(10, -10, 0), c(0, 10, 0);
    // Small ball inside the triangle, offset from the plane: a disk of radius sqrt(r^2 - d^2).
    EXPECT_NEAR(triangle_ball_intersection_area(Eigen::Vector3d(0, 0, 0.6), 1.0, a, b, c), M_PI * 0.64, 1e-12);
    // Huge ball: the whole triangle.
    EXPECT_NEAR(triangle_ball_intersection_area(Eigen::Vector3d(0, 0, 0), 100.0, a, b, c), 200.0, 1e-9);
    // Ball centred on a straight edge: half a disk.
    const Eigen::Vector3d p(0, -10, 0);
    EXPECT_NEAR(triangle_ball_intersection_area(p, 1.0, a, b, c), M_PI / 2, 1e-12);
    // Far away: nothing.
    EXPECT_EQ(triangle_ball_intersection_area(Eigen::Vector3d(0, 0, 5), 1.0, a, b, c), 0.0);
}

TEST(Geometry, BallIntersectionAreaIsZeroWithoutArea) {
    const Eigen::Vector3d a(1, 2, 3), b(4, 2, 7), c(0, 5, 3);
    // Collinear corners and a repeated corner: no area in any ball.
    using Corners = std::array<Eigen::Vector3d, 3>;
    for (const auto& [p, q, r] : {Corners{a, b, a + 2.0 * (b - a)}, Corners{a, a, c}})
        EXPECT_EQ(triangle_ball_intersection_area(p, 10.0, p, q, r), 0.0);
    // Given a normal facing the other way, or none: no area either.
    EXPECT_EQ(triangle_ball_intersection_area(a, 10.0, a, b, c, -triangle_normal(a, b, c)), 0.0);
    EXPECT_EQ(triangle_ball_intersection_area(a, 10.0, a, b, c, Eigen::Vector3d::Zero()), 0.0);
}

// The boundary integral against the sum of signed wedges (wedge_sum_ball_area), on balls
// placed where the two are most likely to part: the sphere through a corner, grazing an edge
// from either side, centred on an edge or a corner, as well as anywhere. (Centred off the plane
// right over a corner, the wedges go wrong: the next test has those cases.)
TEST(Geometry, BallIntersectionAreaAgreesWithWedgeSums) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random_point = [&] { return Eigen::Vector3d(unit(rng), unit(rng), unit(rng)); };
    double worst = 0.0;
    long cases = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Eigen::Vector3d a = random_point(), b = random_point(), c = random_point();
        const Eigen::Vector3d n = triangle_normal(a, b, c);
        const double area = triangle_area(a, b, c);
        if (!(area > 1e-3)) continue;
        const Eigen::Vector3d corners[3] = {a, b, c};
        const int i = trial % 3;
        const Eigen::Vector3d& s = corners[i];
        const Eigen::Vector3d& t = corners[(i + 1) % 3];
        const Eigen::Vector3d mid = 0.5 * (s + t), centroid = (a + b + c) / 3.0;
        const Eigen::Vector3d inward = n.cross(t - s).normalized(); // in the plane, into the triangle
        const double lift = 0.3 * unit(rng), r = 0.05 + std::abs(unit(rng));
        const double rho = std::sqrt(std::max(r * r - lift * lift, 0.0));
        std::vector<Eigen::Vector3d> centres = {
            centroid + random_point(),
            mid + lift * n,                                          // centred on an edge
            s,                                                       // on a corner
            s + random_point().normalized() * r,                     // the sphere through a corner
            mid + inward * rho + lift * n,                           // grazing an edge from inside
            mid - inward * rho + lift * n,                           // and from outside
            mid + inward * (rho * (1.0 + 1e-12)) + lift * n,         // just clear of it
            mid - inward * (rho * (1.0 - 1e-12)) + lift * n,         // just over it
        };
        for (const Eigen::Vector3d& o : centres) {
            const double fast = triangle_ball_intersection_area(o, r, a, b, c);
            const double plain = wedge_sum_ball_area(o, r, a, b, c);
            worst = std::max(worst, std::abs(fast - plain) / std::max(area, M_PI * r * r));
            ++cases;
        }
    }
    EXPECT_GT(cases, 10000);
    EXPECT_LT(worst, 1e-12) << "largest difference, relative to the larger of triangle and disk";
}

// What the eta-ball normals clip most (Section 5.2.1): triangles far smaller than the ball, across
// its rim, where the arc inside each is a small angle (the one the clipping takes from a series
// rather than atan2). Compared with the wedge sums relative to the triangle's own area.
TEST(Geometry, BallIntersectionAreaOfSmallTrianglesAcrossTheRim) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random_direction = [&] { return Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized(); };
    const Eigen::Vector3d o(0.3, -0.2, 0.1);
    const double r = 0.02;
    double worst = 0.0;
    long crossing = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const double size = r * (0.05 + 0.15 * std::abs(unit(rng)));
        const Eigen::Vector3d a = o + (r + size * unit(rng)) * random_direction();
        const Eigen::Vector3d b = a + size * random_direction(), c = a + size * random_direction();
        const double area = triangle_area(a, b, c);
        if (!(area > 0.05 * size * size)) continue;
        const double fast = triangle_ball_intersection_area(o, r, a, b, c);
        const double plain = wedge_sum_ball_area(o, r, a, b, c);
        worst = std::max(worst, std::abs(fast - plain) / area);
        if (fast > 0.0 && fast < area) ++crossing;
    }
    EXPECT_GT(crossing, 1000);
    EXPECT_LT(worst, 1e-12) << "largest difference, relative to the triangle's area";
}

// The disk wholly inside the triangle, the triangle wholly inside the ball, and a disk round a
// corner of the triangle, a quarter of it inside a right angle, from a ball centred off the
// plane over that corner, and half a disk about a point of an edge, as at a T-junction: in both
// the wedge sums took the angle of a vector of rounding errors.
TEST(Geometry, BallIntersectionAreaOfTheWholeDiskAndTheWholeTriangle) {
    const Eigen::Vector3d a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
    const Eigen::Vector3d s(0.1, 0.3, 0.7), t(1.9, -0.4, 0.2), u(0.4, 2.5, -0.3);
    for (const double along : {0.37, 0.5, 0.61}) {
        const Eigen::Vector3d on_edge = s + along * (t - s); // off the line by rounding
        EXPECT_NEAR(triangle_ball_intersection_area(on_edge, 0.2, s, t, u), M_PI * 0.02, 1e-14) << along;
    }
    EXPECT_NEAR(triangle_ball_intersection_area(Eigen::Vector3d(1, 1, 0.5), 0.9, a, b, c), M_PI * (0.81 - 0.25), 1e-14);
    EXPECT_NEAR(triangle_ball_intersection_area(Eigen::Vector3d(1, 1, 0), 6.0, a, b, c), 8.0, 1e-14);
    EXPECT_NEAR(triangle_ball_intersection_area(Eigen::Vector3d(0, 0, -0.6), 1.0, a, b, c), M_PI * 0.64 / 4, 1e-14);
}

TEST(Geometry, ClosestPointOnTriangleRegions) {
    const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_TRUE(closest_point_on_triangle({0.2, 0.2, 5}, a, b, c).isApprox(Eigen::Vector3d(0.2, 0.2, 0)));
    EXPECT_TRUE(closest_point_on_triangle({-1, -1, 0}, a, b, c).isApprox(a));
    EXPECT_TRUE(closest_point_on_triangle({0.5, -3, 1}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0, 0)));
    EXPECT_TRUE(closest_point_on_triangle({1, 1, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
}

TEST(Geometry, ClosestPointOnSegmentRegions) {
    const Eigen::Vector3d a(0.1, 0.7, -0.3), b(2.3, -1.9, 0.6);
    EXPECT_EQ(closest_point_on_segment({-5, 9, -4}, a, b), a); // beyond an end: the end point itself
    EXPECT_EQ(closest_point_on_segment({9, -9, 5}, a, b), b);
    const Eigen::Vector3d mid = 0.5 * (a + b), off = (b - a).cross(Eigen::Vector3d(0, 0, 1));
    const Eigen::Vector3d p = closest_point_on_segment(mid + 0.5 * off, a, b);
    EXPECT_NEAR((p - mid).norm(), 0.0, 1e-14);
    EXPECT_EQ(closest_point_on_segment({1, 1, 1}, a, a), a); // degenerate segment
}

// A point within reach of a corner goes onto it, else onto the nearest edge within reach; a
// point on the edge of a flat facet and one tilted below it then lies on both planes exactly.
TEST(Geometry, OntoTriangleRimWithinReach) {
    const Eigen::Vector3d a(0, 0, 22), b(10, 7, 22), c(0, 10, 22);
    EXPECT_EQ(onto_triangle_rim_within({1e-7, 1e-7, 22}, a, b, c, 1e-6), a); // a corner first
    const Eigen::Vector3d near_edge = a + 0.3 * (b - a) + 2e-7 * Eigen::Vector3d(-0.7, 1.0, 0.0).normalized();
    const Eigen::Vector3d on_edge = onto_triangle_rim_within(near_edge, a, b, c, 1e-6);
    EXPECT_EQ(on_edge.z(), 22.0);
    EXPECT_NEAR((on_edge - (a + 0.3 * (b - a))).norm(), 0.0, 1e-12);
    const Eigen::Vector3d inside(2, 5, 22);
    EXPECT_EQ(onto_triangle_rim_within(inside, a, b, c, 1e-6), inside); // out of reach: unchanged
    EXPECT_EQ(onto_triangle_rim_within(near_edge, a, b, c, 0.0), near_edge);
}

TEST(Mesh, EulerCharacteristicOfBuiltShapes) {
    EXPECT_EQ(euler_characteristic(test::make_icosphere(2)), 2);
    EXPECT_EQ(euler_characteristic(test::make_torus(1.0, 0.3, 24, 12)), 0);
    EXPECT_EQ(euler_characteristic(test::make_cube(1.0, 3)), 2);
    EXPECT_NEAR(surface_area(test::make_cube(1.0, 3)), 24.0, 1e-12);
}

TEST(Mesh, EdgeCountsAndUsesAreSortedPairsWithTheirTriangles) {
    auto expect_counts = [](const Triangles& t) {
        std::map<std::pair<int32_t, int32_t>, int> expected; // counted from scratch
        for (Eigen::Index f = 0; f < t.rows(); ++f)
            for (int j = 0; j < 3; ++j)
                ++expected[{std::min(t(f, j), t(f, (j + 1) % 3)), std::max(t(f, j), t(f, (j + 1) % 3))}];
        const std::vector<EdgeCount> got = edge_counts(t);
        ASSERT_EQ(got.size(), expected.size());
        auto it = expected.begin();
        for (const EdgeCount& e : got) {
            EXPECT_EQ(std::make_pair(e.a, e.b), it->first);
            EXPECT_EQ(e.count, it->second);
            ++it;
        }
    };
    // edge_uses: the same edges, each with the sides (3 f + j) of the live triangles that run
    // along it, in increasing order; every other row is left out (live[f] = 0).
    auto expect_uses = [](const Triangles& t, const std::vector<char>& live) {
        std::map<std::pair<int32_t, int32_t>, std::vector<int32_t>> expected;
        for (Eigen::Index f = 0; f < t.rows(); ++f)
            for (int j = 0; j < 3; ++j)
                if (live.empty() || live[f])
                    expected[{std::min(t(f, j), t(f, (j + 1) % 3)), std::max(t(f, j), t(f, (j + 1) % 3))}].push_back(
                        static_cast<int32_t>(3 * f + j));
        const EdgeUses got = edge_uses(t, live);
        ASSERT_EQ(got.size(), static_cast<long>(expected.size()));
        ASSERT_EQ(got.uses.offsets.size(), expected.size() + 1);
        auto it = expected.begin();
        for (long e = 0; e < got.size(); ++e, ++it) {
            EXPECT_EQ(std::make_pair(got.a[e], got.b[e]), it->first);
            EXPECT_EQ(std::vector<int32_t>(got.uses.begin(e), got.uses.end(e)), it->second) << e;
        }
    };
    auto expect_both = [&](const Triangles& t) {
        expect_counts(t);
        expect_uses(t, {});
        std::vector<char> odd(static_cast<size_t>(t.rows()), 0);
        for (size_t f = 1; f < odd.size(); f += 2) odd[f] = 1;
        expect_uses(t, odd);
    };
    expect_both(test::make_torus(1.0, 0.3, 12, 6).triangles);
    Triangles fin(4, 3); // three triangles on the edge {0, 1}, and one with a repeated index
    fin << 0, 1, 2, 1, 0, 3, 0, 1, 4, 4, 4, 0;
    expect_both(fin);
    fin(2, 2) = 1'000'000; // an index far beyond the triangle count: the other code path
    expect_both(fin);
    // Listed in lexicographic order, as the restricted Delaunay triangulation lists them.
    Triangles sorted = test::make_icosphere(3).triangles;
    std::vector<std::array<int32_t, 3>> rows(static_cast<size_t>(sorted.rows()));
    for (Eigen::Index f = 0; f < sorted.rows(); ++f) rows[f] = {sorted(f, 0), sorted(f, 1), sorted(f, 2)};
    std::sort(rows.begin(), rows.end());
    for (Eigen::Index f = 0; f < sorted.rows(); ++f) sorted.row(f) << rows[f][0], rows[f][1], rows[f][2];
    expect_both(sorted);
    EXPECT_TRUE(edge_counts(Triangles(0, 3)).empty());
    EXPECT_EQ(edge_uses(Triangles(0, 3)).size(), 0);
    EXPECT_EQ(edge_uses(Triangles(0, 3)).uses.offsets, std::vector<int32_t>{0});
    Triangles negative(1, 3);
    negative << 0, -1, 2;
    EXPECT_THROW(edge_uses(negative), InvalidInput);
    EXPECT_THROW(edge_counts(negative), InvalidInput);
    EXPECT_THROW(edge_uses(fin, std::vector<char>(3, 1)), InvalidInput); // 4 triangles, 3 flags
}

// A vertex far from the rest (a corrupt coordinate) is refused with its coordinates; a part of any
// size, or two parts far apart, is not: the test is of the bounding box against the median edge.
TEST(Mesh, CheckExtentRefusesAVertexFarFromTheRest) {
    Mesh sphere = test::make_icosphere(2); // unit radius, median edge about 0.3
    EXPECT_NO_THROW(check_extent(sphere, "input"));
    for (double scale : {1e-12, 1e12}) {
        Mesh scaled = sphere;
        scaled.points *= scale;
        EXPECT_NO_THROW(check_extent(scaled, "input")) << scale;
    }
    Mesh apart = sphere; // a second sphere 1e8 away: 3e8 median edges, accepted
    apart.points.rowwise() += Eigen::RowVector3d(1e8, 0.0, 0.0);
    EXPECT_NO_THROW(check_extent(test::joined(sphere, apart), "input"));

    Mesh corrupt = sphere;
    corrupt.points(7, 1) = -4e9; // 1.3e10 median edges from the rest
    try {
        check_extent(corrupt, "input");
        ADD_FAILURE() << "a vertex 4e9 away from a unit sphere is accepted";
    } catch (const InvalidInput& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("input mesh spans 4e+09"), std::string::npos) << message;
        EXPECT_NE(message.find(", -4e+09, "), std::string::npos) << message; // its coordinates
        EXPECT_NE(message.find("far from the rest"), std::string::npos) << message;
    }
}
