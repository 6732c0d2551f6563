#include "helpers.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/system/threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

using namespace liftremesh;

namespace {

// What a query that appends triangle indices finds, sorted; it must append, not clear.
template <class Query>
std::vector<int32_t> appended_by(const Query& query) {
    std::vector<int32_t> found = {-7};
    query(found);
    if (found.empty() || found.front() != -7) {
        ADD_FAILURE() << "the query cleared the vector it appends to";
        return found;
    }
    found.erase(found.begin());
    std::sort(found.begin(), found.end());
    return found;
}

//! Closest point by testing every triangle.
ClosestPoint brute_force_closest(const Mesh& mesh, const Eigen::Vector3d& q) {
    ClosestPoint best{Eigen::Vector3d::Zero(), std::numeric_limits<double>::infinity(), -1};
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
        const Eigen::Vector3d p = closest_point_on_triangle(q, mesh.points.row(mesh.triangles(f, 0)).transpose(),
                                                            mesh.points.row(mesh.triangles(f, 1)).transpose(),
                                                            mesh.points.row(mesh.triangles(f, 2)).transpose());
        const double d2 = (p - q).squaredNorm();
        if (d2 < best.squared_distance) best = {p, d2, static_cast<int32_t>(f)};
    }
    return best;
}

//! Checks the tree against brute force on `n` random queries in the cube [-extent, extent]^3.
void expect_matches_brute_force(const Mesh& mesh, double extent, int n, std::uint64_t seed) {
    const AabbTree tree(mesh);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> coordinate(-extent, extent);
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d q(coordinate(rng), coordinate(rng), coordinate(rng));
        const ClosestPoint got = tree.closest(q);
        const ClosestPoint want = brute_force_closest(mesh, q);
        ASSERT_NEAR(got.squared_distance, want.squared_distance, 1e-12 * (1 + want.squared_distance)) << "query " << i;
        ASSERT_GE(got.triangle, 0);
        ASSERT_LT(got.triangle, mesh.triangles.rows());
        // The reported point lies on the reported triangle and at the reported distance
        // (ties between triangles sharing the closest point may pick either).
        const Eigen::Vector3d on_triangle =
            closest_point_on_triangle(q, mesh.points.row(mesh.triangles(got.triangle, 0)).transpose(),
                                      mesh.points.row(mesh.triangles(got.triangle, 1)).transpose(),
                                      mesh.points.row(mesh.triangles(got.triangle, 2)).transpose());
        ASSERT_LT((on_triangle - got.point).norm(), 1e-12);
        ASSERT_NEAR((got.point - q).squaredNorm(), got.squared_distance, 1e-12);
        ASSERT_LT((got.point - want.point).norm(), 1e-6 + 1e-6 * std::sqrt(want.squared_distance));
    }
}

} // namespace

TEST(AabbTree, ClosestPointMatchesBruteForceOnIcosphere) {
    expect_matches_brute_force(test::make_icosphere(3), 2.0, 2000, 1);
    expect_matches_brute_force(test::make_icosphere(3), 0.3, 500, 2); // inside, far from the surface
}

TEST(AabbTree, ClosestPointMatchesBruteForceOnNonConvexShapes) {
    expect_matches_brute_force(test::make_torus(1.0, 0.3, 40, 16), 1.5, 1000, 3);
    expect_matches_brute_force(test::make_cube(1.0, 5), 3.0, 1000, 4);
}

// 20 480 triangles: the tree's halves are built as tasks, on two threads and on one. The trees
// are the same, so the answers are, to the bit, and they match brute force.
TEST(AabbTree, TreeBuiltOnSeveralThreadsAnswersAsOneBuiltOnOne) {
    const Mesh mesh = test::make_icosphere(5);
    ASSERT_GE(mesh.triangles.rows(), 16384);
    std::unique_ptr<AabbTree> parallel, serial;
    {
        const ThreadCountScope two(2);
        parallel = std::make_unique<AabbTree>(mesh);
    }
    {
        const ThreadCountScope one(1);
        serial = std::make_unique<AabbTree>(mesh);
    }
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
    for (int i = 0; i < 300; ++i) {
        const Eigen::Vector3d q(coordinate(rng), coordinate(rng), coordinate(rng));
        const ClosestPoint a = parallel->closest(q), b = serial->closest(q);
        ASSERT_EQ(a.triangle, b.triangle) << "query " << i;
        ASSERT_EQ(a.point, b.point) << "query " << i;
        ASSERT_NEAR(a.squared_distance, brute_force_closest(mesh, q).squared_distance, 1e-12) << "query " << i;
    }
}

TEST(AabbTree, VerticesAreAtDistanceZero) {
    const Mesh mesh = test::make_icosphere(2);
    const AabbTree tree(mesh);
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) {
        const ClosestPoint c = tree.closest(mesh.points.row(i).transpose());
        EXPECT_EQ(c.squared_distance, 0.0);
        EXPECT_TRUE(c.point == mesh.points.row(i).transpose());
    }
}

TEST(AabbTree, HandlesDegenerateAndDuplicateTriangles) {
    // Many triangles with the same centroid, and flat ones: the median split must still work.
    Mesh mesh = test::make_icosphere(1);
    const Eigen::Index n = mesh.triangles.rows();
    mesh.triangles.conservativeResize(3 * n, 3);
    for (Eigen::Index f = 0; f < n; ++f) {
        mesh.triangles.row(n + f) = mesh.triangles.row(f);                                                 // duplicate
        mesh.triangles.row(2 * n + f) << mesh.triangles(f, 0), mesh.triangles(f, 0), mesh.triangles(f, 1); // flat
    }
    expect_matches_brute_force(mesh, 1.5, 500, 5);
}

TEST(AabbTree, EmptyMeshAndBadIndices) {
    Mesh empty;
    empty.points.resize(0, 3);
    empty.triangles.resize(0, 3);
    const AabbTree tree(empty);
    const ClosestPoint c = tree.closest(Eigen::Vector3d::Zero());
    EXPECT_EQ(c.triangle, -1);
    EXPECT_TRUE(std::isinf(c.squared_distance));

    Mesh bad = test::make_icosphere(0);
    bad.triangles(3, 1) = -1;
    EXPECT_THROW(AabbTree{bad}, InvalidInput);
}

TEST(AabbTree, MovedTreeStillAnswers) {
    const Mesh mesh = test::make_icosphere(2);
    AabbTree a(mesh);
    AabbTree b = std::move(a);
    AabbTree c(test::make_icosphere(0));
    c = std::move(b);
    EXPECT_NEAR(std::sqrt(c.closest(Eigen::Vector3d(0, 0, 3)).squared_distance), 2.0, 0.05);
}

TEST(AabbTree, WarmStartGivesTheSameDistanceAsAColdQuery) {
    const Mesh m = liftremesh::test::make_torus(1.0, 0.3, 40, 16);
    const AabbTree tree(m);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> coord(-1.6, 1.6);
    for (int i = 0; i < 500; ++i) {
        const Eigen::Vector3d q(coord(rng), coord(rng), 0.5 * coord(rng));
        const Eigen::Vector3d hint = m.points.row(i % m.points.rows()).transpose(); // on the mesh, maybe far
        const ClosestPoint cold = tree.closest(q), warm = tree.closest(q, hint);
        EXPECT_NEAR(warm.squared_distance, cold.squared_distance, 1e-14) << i;
        EXPECT_NEAR((warm.point - cold.point).norm(), 0.0, 1e-7) << i;
    }
    // A hint that is the answer itself: nothing is strictly nearer, the hint comes back.
    const Eigen::Vector3d q(1.5, 0.0, 0.0);
    const ClosestPoint exact = tree.closest(q);
    EXPECT_EQ(tree.closest(q, exact.point).squared_distance, exact.squared_distance);
}

TEST(AabbTree, AnyWithinFindsATriangleExactlyWhenOneIsNearerThanTheRadius) {
    const Mesh m = liftremesh::test::make_torus(1.0, 0.3, 40, 16);
    const AabbTree tree(m);
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> coord(-1.6, 1.6), radius(0.0, 0.4);
    int hits = 0, misses = 0;
    for (int i = 0; i < 2000; ++i) {
        const Eigen::Vector3d q(coord(rng), coord(rng), 0.5 * coord(rng));
        const double r = radius(rng);
        const double nearest = std::sqrt(brute_force_closest(m, q).squared_distance);
        const int32_t t = tree.any_within(q, r);
        if (nearest < r * (1 - 1e-9)) {
            ASSERT_GE(t, 0) << i;
            ++hits;
            const Eigen::Vector3d p = closest_point_on_triangle(q, m.points.row(m.triangles(t, 0)).transpose(),
                                                                m.points.row(m.triangles(t, 1)).transpose(),
                                                                m.points.row(m.triangles(t, 2)).transpose());
            EXPECT_LT((p - q).norm(), r) << i; // the triangle returned is within the radius
        } else if (nearest > r * (1 + 1e-9)) {
            EXPECT_EQ(t, -1) << i;
            ++misses;
        }
    }
    EXPECT_GT(hits, 100);
    EXPECT_GT(misses, 100);
    EXPECT_EQ(AabbTree(Mesh{}).any_within(Eigen::Vector3d::Zero(), 1.0), -1);
}

// Every triangle nearer than r, each once, on a torus and on a fan of long slivers (a CAD disk,
// whose bounding spheres all reach the centre; vertex_normals asks these queries).
TEST(AabbTree, TrianglesWithinAreThoseNearerThanTheRadius) {
    std::vector<Eigen::Vector3d> fan_points = {Eigen::Vector3d::Zero()};
    std::vector<std::array<int32_t, 3>> fan_triangles;
    const int n = 500;
    for (int k = 0; k < n; ++k) {
        fan_points.emplace_back(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n), 0.0);
        fan_triangles.push_back({0, 1 + k, 1 + (k + 1) % n});
    }
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> coord(-1.6, 1.6), radius(0.0, 0.4);
    for (const Mesh& m : {liftremesh::test::make_torus(1.0, 0.3, 40, 16), make_mesh(fan_points, fan_triangles)}) {
        const AabbTree tree(m);
        long total = 0;
        for (int i = 0; i < 300; ++i) {
            const Eigen::Vector3d q(coord(rng), coord(rng), 0.3 * coord(rng));
            const double r = radius(rng);
            const std::vector<int32_t> found =
                appended_by([&](std::vector<int32_t>& out) { tree.triangles_within(q, r, out); });
            std::vector<int32_t> expected;
            for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
                const Eigen::Vector3d p = closest_point_on_triangle(q, m.points.row(m.triangles(f, 0)).transpose(),
                                                                    m.points.row(m.triangles(f, 1)).transpose(),
                                                                    m.points.row(m.triangles(f, 2)).transpose());
                if ((p - q).squaredNorm() < r * r) expected.push_back(static_cast<int32_t>(f));
            }
            EXPECT_EQ(found, expected) << i;
            total += static_cast<long>(found.size());
        }
        EXPECT_GT(total, 300); // the queries do find triangles
    }
    std::vector<int32_t> none;
    AabbTree(Mesh{}).triangles_within(Eigen::Vector3d::Zero(), 1.0, none);
    EXPECT_TRUE(none.empty());
}

TEST(AabbTree, TrianglesMeetingABoxAreThoseWhoseBoxesMeetIt) {
    const Mesh m = liftremesh::test::make_torus(1.0, 0.3, 40, 16);
    const AabbTree tree(m);
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> coord(-1.6, 1.6), side(0.0, 0.8);
    long total = 0;
    for (int i = 0; i < 300; ++i) {
        const Eigen::Vector3d lo(coord(rng), coord(rng), 0.3 * coord(rng));
        const Eigen::Vector3d hi = lo + Eigen::Vector3d(side(rng), side(rng), i % 10 == 0 ? 0.0 : side(rng));
        const std::vector<int32_t> found =
            appended_by([&](std::vector<int32_t>& out) { tree.triangles_meeting_box(lo, hi, out); });
        std::vector<int32_t> expected;
        for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
            Eigen::Vector3d tlo = Eigen::Vector3d::Constant(1e300), thi = -tlo;
            for (int j = 0; j < 3; ++j) {
                tlo = tlo.cwiseMin(m.points.row(m.triangles(f, j)).transpose());
                thi = thi.cwiseMax(m.points.row(m.triangles(f, j)).transpose());
            }
            if ((tlo.array() <= hi.array()).all() && (thi.array() >= lo.array()).all())
                expected.push_back(static_cast<int32_t>(f));
        }
        EXPECT_EQ(found, expected) << i;
        total += static_cast<long>(found.size());
    }
    EXPECT_GT(total, 300);
    std::vector<int32_t> none;
    AabbTree(Mesh{}).triangles_meeting_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), none);
    EXPECT_TRUE(none.empty());
}

TEST(AabbTree, ClosestWhereIsTheNearestAcceptedTriangleWithinTheRadius) {
    const Mesh m = liftremesh::test::make_torus(1.0, 0.3, 40, 16);
    const AabbTree tree(m);
    // The triangles facing up only (against -z): brute force over them.
    const std::vector<Eigen::Vector3d> down = {-Eigen::Vector3d::UnitZ()};
    const auto up = [&](int32_t f) { return tree.triangle_normal(f).z() > 0.2; };
    Mesh facing_up = m;
    Eigen::Index kept = 0;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        if (up(static_cast<int32_t>(f))) facing_up.triangles.row(kept++) = m.triangles.row(f);
    facing_up.triangles.conservativeResize(kept, 3);
    ASSERT_GT(kept, 0);
    ASSERT_LT(kept, m.triangles.rows());
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> coord(-1.6, 1.6), radius(0.05, 0.8);
    int found = 0, none = 0;
    for (int i = 0; i < 2000; ++i) {
        const Eigen::Vector3d q(coord(rng), coord(rng), 0.5 * coord(rng));
        const double r = radius(rng);
        const ClosestPoint want = brute_force_closest(facing_up, q),
                           got = tree.closest_where(q, r, {down, -0.2}, [](int32_t, const Eigen::Vector3d&) {
                               return true;
                           });
        if (want.squared_distance < r * r * (1 - 1e-9)) {
            ASSERT_GE(got.triangle, 0) << i;
            EXPECT_TRUE(up(got.triangle)) << i;
            EXPECT_NEAR(got.squared_distance, want.squared_distance, 1e-12) << i;
            ++found;
        } else if (want.squared_distance > r * r * (1 + 1e-9)) {
            EXPECT_EQ(got.triangle, -1) << i;
            EXPECT_EQ(got.squared_distance, r * r) << i;
            ++none;
        }
    }
    EXPECT_GT(found, 100);
    EXPECT_GT(none, 100);
}

TEST(AabbTree, ClosestWhereSkipsOnlyTrianglesThatDoNotFaceAsAsked) {
    // Several directions and a point-dependent `accept`, on a torus joined to a sphere (normals
    // of every direction, a tree of several levels): the search, whose subtrees are skipped by
    // their normals' boxes, against every triangle tested. Thresholds up to max_dot = 1 - 1e-12,
    // where nearly every triangle faces so, and down to -0.99, where few do.
    Mesh sphere = liftremesh::test::make_icosphere(3, 0.5);
    sphere.points.rowwise() += Eigen::RowVector3d(1.0, 0.0, 0.2);
    const Mesh m = liftremesh::test::joined(liftremesh::test::make_torus(1.0, 0.3, 48, 20), sphere);
    const AabbTree tree(m);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> coord(-1.6, 1.6), radius(0.05, 1.0), unit(-1.0, 1.0);
    const std::array<double, 5> thresholds = {-0.99, -0.9, -0.4, 0.3, 1.0 - 1e-12};
    int found = 0, none = 0;
    for (int i = 0; i < 3000; ++i) {
        const Eigen::Vector3d q(coord(rng), coord(rng), 0.5 * coord(rng));
        const double r = radius(rng);
        std::vector<Eigen::Vector3d> directions(1 + i % 3);
        for (Eigen::Vector3d& d : directions) d = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
        const double max_dot = thresholds[static_cast<size_t>(i) % thresholds.size()];
        const auto accept = [&](int32_t f, const Eigen::Vector3d& p) { return f % 5 != 0 && p.x() > q.x() - 0.2; };
        const auto faces = [&](const Eigen::Vector3d& n) {
            return std::any_of(directions.begin(), directions.end(), [&](const Eigen::Vector3d& d) { return n.dot(d) < max_dot; });
        };
        double want = r * r;
        for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
            if (!faces(tree.triangle_normal(static_cast<int32_t>(f)))) continue;
            const Eigen::Vector3d p = closest_point_on_triangle(q, m.points.row(m.triangles(f, 0)).transpose(),
                                                                m.points.row(m.triangles(f, 1)).transpose(),
                                                                m.points.row(m.triangles(f, 2)).transpose());
            if ((p - q).squaredNorm() < want && accept(static_cast<int32_t>(f), p)) want = (p - q).squaredNorm();
        }
        const ClosestPoint got = tree.closest_where(q, r, {directions, max_dot}, accept);
        EXPECT_EQ(got.squared_distance, want) << i;
        if (got.triangle >= 0) {
            EXPECT_TRUE(faces(tree.triangle_normal(got.triangle))) << i;
            EXPECT_TRUE(accept(got.triangle, got.point)) << i;
            ++found;
        } else {
            ++none;
        }
    }
    EXPECT_GT(found, 500);
    EXPECT_GT(none, 300);
}

TEST(AabbTree, OverlappingPairsAreExactlyThePairsWhoseBoxesMeetEachOnce) {
    // A torus (1280 triangles, a tree of several levels) and a sphere through it, as one mesh.
    Mesh sphere = liftremesh::test::make_icosphere(2, 0.5);
    sphere.points.rowwise() += Eigen::RowVector3d(1.0, 0.0, 0.2);
    const Mesh m = liftremesh::test::joined(liftremesh::test::make_torus(1.0, 0.3, 40, 16), sphere);
    std::vector<Eigen::Vector3d> lo(m.triangles.rows()), hi(m.triangles.rows());
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
        lo[f] = hi[f] = m.points.row(m.triangles(f, 0)).transpose();
        for (int j = 1; j < 3; ++j) {
            lo[f] = lo[f].cwiseMin(m.points.row(m.triangles(f, j)).transpose());
            hi[f] = hi[f].cwiseMax(m.points.row(m.triangles(f, j)).transpose());
        }
    }
    std::vector<std::pair<int32_t, int32_t>> expected, visited;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (Eigen::Index g = f + 1; g < m.triangles.rows(); ++g)
            if ((lo[f].array() <= hi[g].array()).all() && (lo[g].array() <= hi[f].array()).all())
                expected.emplace_back(static_cast<int32_t>(f), static_cast<int32_t>(g));
    AabbTree(m).overlapping_pairs([&](int32_t a, int32_t b) {
        visited.emplace_back(std::min(a, b), std::max(a, b));
        return true;
    });
    std::sort(visited.begin(), visited.end());
    EXPECT_TRUE(std::adjacent_find(visited.begin(), visited.end()) == visited.end()) << "a pair twice";
    EXPECT_EQ(visited, expected);
    EXPECT_GT(expected.size(), 3 * static_cast<size_t>(m.triangles.rows())); // neighbours, and where the two cross
    long calls = 0;
    AabbTree(m).overlapping_pairs([&](int32_t, int32_t) { return ++calls < 10; });
    EXPECT_EQ(calls, 10); // stopped when asked
}
