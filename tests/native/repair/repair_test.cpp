#include "liftremesh/exceptions.h"
#include "liftremesh/repair/hole_filling.h"
#include "liftremesh/repair/repair.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <random>

using namespace liftremesh;
using namespace liftremesh::test;

namespace {

// Appends triangles (and points) to a mesh.
void add_triangles(Mesh& m, const std::vector<std::array<int32_t, 3>>& tris, const std::vector<Eigen::Vector3d>& pts = {}) {
    const Eigen::Index np = m.points.rows(), nf = m.triangles.rows();
    m.points.conservativeResize(np + static_cast<Eigen::Index>(pts.size()), 3);
    for (size_t i = 0; i < pts.size(); ++i) m.points.row(np + static_cast<Eigen::Index>(i)) = pts[i].transpose();
    m.triangles.conservativeResize(nf + static_cast<Eigen::Index>(tris.size()), 3);
    for (size_t i = 0; i < tris.size(); ++i)
        for (int j = 0; j < 3; ++j) m.triangles(nf + static_cast<Eigen::Index>(i), j) = tris[i][j];
}

std::array<int32_t, 3> tri(const Mesh& m, Eigen::Index f) { return {m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2)}; }

// The triangle other than f that uses the edge a-b.
Eigen::Index across(const Mesh& m, Eigen::Index f, int32_t a, int32_t b) {
    for (Eigen::Index g = 0; g < m.triangles.rows(); ++g) {
        if (g == f) continue;
        int hits = 0;
        for (int j = 0; j < 3; ++j) hits += m.triangles(g, j) == a || m.triangles(g, j) == b;
        if (hits == 2) return g;
    }
    return -1;
}

} // namespace

TEST(Repair, CleanSphereIsLeftAlone) {
    Mesh m = make_icosphere(2);
    const Mesh before = m;
    const RepairStats s = make_manifold(m);
    EXPECT_EQ(s.degenerate_removed + s.duplicates_removed + s.nonmanifold_removed + s.flipped, 0);
    // remove_unreferenced_vertices may renumber: compare through the coordinates.
    ASSERT_EQ(m.points.rows(), before.points.rows());
    ASSERT_EQ(m.triangles.rows(), before.triangles.rows());
    std::map<std::array<double, 3>, int32_t> original;
    for (Eigen::Index i = 0; i < before.points.rows(); ++i)
        original[{before.points(i, 0), before.points(i, 1), before.points(i, 2)}] = static_cast<int32_t>(i);
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) {
            const auto v = m.triangles(f, j);
            EXPECT_EQ(original.at({m.points(v, 0), m.points(v, 1), m.points(v, 2)}), before.triangles(f, j));
        }
}

TEST(Repair, RemovesDegenerateAndDuplicateTriangles) {
    const Mesh sphere = make_icosphere(2);
    Mesh m = sphere;
    const auto t0 = tri(m, 0), t1 = tri(m, 1), t2 = tri(m, 2);
    // Duplicates: same order, rotated, reversed.
    add_triangles(m, {t0, {t1[1], t1[2], t1[0]}, {t2[0], t2[2], t2[1]}, {t0[2], t0[1], t0[0]}});
    // A repeated index, and a zero-area triangle on the edge t0[0]-t0[1] through its midpoint.
    const Eigen::Vector3d mid = 0.5 * (sphere.points.row(t0[0]) + sphere.points.row(t0[1])).transpose();
    const auto m_index = static_cast<int32_t>(m.points.rows());
    add_triangles(m, {{t0[0], t0[0], t0[2]}, {t0[0], m_index, t0[1]}}, {mid});
    ASSERT_GT(topology(m).nonmanifold_edges, 0);

    const RepairStats s = make_manifold(m);
    EXPECT_EQ(s.degenerate_removed, 2);
    EXPECT_EQ(s.duplicates_removed, 4);
    const Topology t = topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(m.triangles.rows(), sphere.triangles.rows());
    EXPECT_EQ(m.points.rows(), sphere.points.rows()); // the midpoint went with its triangle
    EXPECT_EQ(facing_inward(m, Eigen::Vector3d::Zero()), 0);
}

TEST(Repair, ReorientsAFlippedPatchToTheMajority) {
    Mesh m = make_icosphere(3);
    long flipped = 0;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
        const Eigen::Vector3d c = (corner(m, f, 0) + corner(m, f, 1) + corner(m, f, 2)) / 3.0;
        if (c.z() > 0.6) {
            std::swap(m.triangles(f, 1), m.triangles(f, 2));
            ++flipped;
        }
    }
    ASSERT_GT(flipped, 10);
    ASSERT_GT(topology(m).misoriented_edges, 0);
    const RepairStats s = make_manifold(m);
    EXPECT_EQ(s.flipped, flipped);
    EXPECT_EQ(s.nonmanifold_removed, 0);
    EXPECT_TRUE(topology(m).closed_oriented_manifold());
    EXPECT_EQ(facing_inward(m, Eigen::Vector3d::Zero()), 0);
}

TEST(Repair, MinorityIsFlippedEvenWhenItIsTheFirstTriangle) {
    Mesh m = make_icosphere(1);
    std::swap(m.triangles(0, 1), m.triangles(0, 2)); // the BFS seed is the odd one out
    const RepairStats s = make_manifold(m);
    EXPECT_EQ(s.flipped, 1);
    EXPECT_EQ(facing_inward(m, Eigen::Vector3d::Zero()), 0);
}

TEST(Repair, RemovesAFinOnAnExistingEdgeInEitherOrientation) {
    const Mesh sphere = make_icosphere(2);
    for (bool reversed : {false, true}) {
        Mesh m = sphere;
        const auto t = tri(m, 7);
        // A well-shaped fin standing out of the surface on edge t[0]-t[1].
        const Eigen::Vector3d a = m.points.row(t[0]).transpose(), b = m.points.row(t[1]).transpose();
        const Eigen::Vector3d tip = 0.5 * (a + b) * 1.0 + (a + b).normalized() * (b - a).norm() * 0.87;
        const auto k = static_cast<int32_t>(m.points.rows());
        add_triangles(m, {reversed ? std::array<int32_t, 3>{t[1], t[0], k} : std::array<int32_t, 3>{t[0], t[1], k}}, {tip});
        ASSERT_EQ(topology(m).nonmanifold_edges, 1);
        const RepairStats s = make_manifold(m);
        EXPECT_EQ(s.nonmanifold_removed, 1) << "reversed fin: " << reversed;
        const Topology top = topology(m);
        EXPECT_TRUE(top.closed_oriented_manifold());
        EXPECT_EQ(top.chi, 2);
        EXPECT_EQ(m.triangles.rows(), sphere.triangles.rows());
        EXPECT_EQ(m.points.rows(), sphere.points.rows());
    }
}

TEST(Repair, KeepsOneDiagonalOfFourCocircularSites) {
    // Four nearly co-circular sites a, b, d, c give all four triangles of their tetrahedron:
    // each quad side then has three triangles. One diagonal's pair must go.
    const Mesh sphere = make_icosphere(2);
    Mesh m = sphere;
    const auto t1 = tri(m, 11); // (a, b, c)
    const int32_t a = t1[0], b = t1[1], c = t1[2];
    const Eigen::Index f2 = across(m, 11, b, c);
    ASSERT_GE(f2, 0);
    int32_t d = -1;
    for (int j = 0; j < 3; ++j)
        if (m.triangles(f2, j) != b && m.triangles(f2, j) != c) d = m.triangles(f2, j);
    add_triangles(m, {{a, b, d}, {a, d, c}}); // the other diagonal, oriented like the surface
    ASSERT_EQ(topology(m).nonmanifold_edges, 4);
    const RepairStats s = make_manifold(m);
    EXPECT_EQ(s.nonmanifold_removed, 2);
    const Topology top = topology(m);
    EXPECT_TRUE(top.closed_oriented_manifold());
    EXPECT_EQ(top.chi, 2);
    EXPECT_EQ(m.triangles.rows(), sphere.triangles.rows());
    EXPECT_EQ(facing_inward(m, Eigen::Vector3d::Zero()), 0);
}

TEST(Repair, TwoSpheresTouchingAtAVertexKeepTheLargerFan) {
    // Sphere A (level 2) and a smaller sphere B (level 1) outside it, sharing one vertex: A's
    // vertex 12 (valence 6) is B's vertex 0 (valence 5), so B loses its fan there.
    const Mesh A = make_icosphere(2);
    Mesh B = make_icosphere(1, 0.5);
    const int32_t shared = 12;
    const Eigen::Vector3d pa = A.points.row(shared).transpose();
    const Eigen::Vector3d dir = pa.normalized();
    const Eigen::Quaterniond rot = Eigen::Quaterniond::FromTwoVectors(B.points.row(0).transpose().normalized(), -dir);
    const Eigen::Vector3d center = pa + 0.5 * dir;
    Mesh m = A;
    const auto offset = static_cast<int32_t>(A.points.rows()) - 1; // B's vertex 0 becomes `shared`
    std::vector<Eigen::Vector3d> pts;
    for (Eigen::Index i = 1; i < B.points.rows(); ++i) pts.push_back(center + rot * B.points.row(i).transpose());
    std::vector<std::array<int32_t, 3>> tris;
    for (Eigen::Index f = 0; f < B.triangles.rows(); ++f) {
        std::array<int32_t, 3> t;
        for (int j = 0; j < 3; ++j) t[j] = B.triangles(f, j) == 0 ? shared : B.triangles(f, j) + offset;
        tris.push_back(t);
    }
    add_triangles(m, tris, pts);
    ASSERT_EQ(topology(m).nonmanifold_vertices, 1);
    ASSERT_EQ(topology(m).chi, 3); // 2 + 2 - 1 shared vertex

    const RepairStats s = make_manifold(m);
    EXPECT_EQ(s.nonmanifold_removed, 5);
    Topology top = topology(m);
    EXPECT_TRUE(top.oriented_manifold());
    EXPECT_EQ(top.boundary_edges, 5);
    EXPECT_EQ(top.chi, 3); // a closed sphere and a disk
    EXPECT_EQ(boundary_loops(m).size(), 1u);
    EXPECT_EQ(m.points.rows(), A.points.rows() + B.points.rows() - 1);

    EXPECT_EQ(fill_holes(m, {}).filled, 1);
    top = topology(m);
    EXPECT_TRUE(top.closed_oriented_manifold());
    EXPECT_EQ(top.chi, 4); // two spheres
}

TEST(Repair, TwoSpheresSharingAnEdgeKeepAConsistentPair) {
    // Sphere B touches sphere A along the edge a-b: four triangles on it, A1 (a -> b) and A2
    // (b -> a) from A, B1 (a -> b) and B2 (b -> a) from B. Shapes are set so that the pair with
    // the best smaller kappa, (A1, B1), runs the same way: keeping it would glue B to A with
    // B's orientation reversed. A consistent pair must win and no triangle may be flipped.
    const Mesh A = make_icosphere(2);
    const Mesh B = make_icosphere(1, 0.6);
    const int32_t a = A.triangles(0, 0), b = A.triangles(0, 1); // A1 = A's triangle 0
    const int32_t c = B.triangles(0, 0), d = B.triangles(0, 1); // B2 = B's triangle 0, c -> d becomes b -> a
    const Eigen::Vector3d pa = A.points.row(a).transpose(), pb = A.points.row(b).transpose();
    const Eigen::Vector3d pc = B.points.row(c).transpose(), pd = B.points.row(d).transpose();
    // Rigid motion of B: midpoint of c-d onto that of a-b, B's centre outside A, d - c along a - b.
    const Eigen::Vector3d ma = 0.5 * (pa + pb), mb = 0.5 * (pc + pd);
    const Eigen::Quaterniond r1 = Eigen::Quaterniond::FromTwoVectors(mb.normalized(), -ma.normalized());
    const Eigen::Vector3d target = (pa - pb) - (pa - pb).dot(ma.normalized()) * ma.normalized();
    const Eigen::Quaterniond rot = Eigen::Quaterniond::FromTwoVectors(r1 * (pd - pc), target) * r1;
    const Eigen::Vector3d shift = ma - rot * mb;
    Mesh m = A;
    std::vector<int32_t> remap(static_cast<size_t>(B.points.rows()), -1);
    std::vector<Eigen::Vector3d> pts;
    for (Eigen::Index i = 0; i < B.points.rows(); ++i) {
        if (i == c) {
            remap[i] = b;
        } else if (i == d) {
            remap[i] = a;
        } else {
            remap[i] = static_cast<int32_t>(A.points.rows() + static_cast<Eigen::Index>(pts.size()));
            pts.push_back(rot * B.points.row(i).transpose() + shift);
        }
    }
    std::vector<std::array<int32_t, 3>> tris;
    for (Eigen::Index f = 0; f < B.triangles.rows(); ++f)
        tris.push_back({remap[B.triangles(f, 0)], remap[B.triangles(f, 1)], remap[B.triangles(f, 2)]});
    add_triangles(m, tris, pts);
    const Eigen::Index A1 = 0, A2 = across(A, 0, a, b), B2 = A.triangles.rows();
    Eigen::Index B1 = -1;
    for (Eigen::Index f = A.triangles.rows() + 1; f < m.triangles.rows(); ++f)
        if (std::set<int32_t>{m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2)}.count(a) &&
            std::set<int32_t>{m.triangles(f, 0), m.triangles(f, 1), m.triangles(f, 2)}.count(b))
            B1 = f;
    ASSERT_GE(A2, 0);
    ASSERT_GE(B1, 0);
    // Pull the apex of A2 a little and that of B2 a lot towards the shared edge.
    auto pull = [&](Eigen::Index f, double amount) {
        for (int j = 0; j < 3; ++j) {
            const int32_t v = m.triangles(f, j);
            if (v != a && v != b) m.points.row(v) = (1 - amount) * m.points.row(v) + amount * ma.transpose();
        }
    };
    pull(A2, 0.3);
    pull(B2, 0.8);
    auto kappa = [&](Eigen::Index f) { return triangle_kappa(corner(m, f, 0), corner(m, f, 1), corner(m, f, 2)); };
    ASSERT_LT(kappa(A2), std::min(kappa(A1), kappa(B1)));
    ASSERT_LT(kappa(B2), kappa(A2));
    ASSERT_EQ(topology(m).nonmanifold_edges, 1);
    ASSERT_EQ(topology(m).misoriented_edges, 0);

    const RepairStats s = make_manifold(m);
    EXPECT_TRUE(topology(m).oriented_manifold());
    EXPECT_EQ(s.flipped, 0);
}

TEST(Repair, RandomSoupsBecomeOrientedManifolds) {
    std::mt19937 rng(12345);
    for (int trial = 0; trial < 40; ++trial) {
        const int nv = 8 + trial % 25, nf = 10 + 7 * trial;
        Mesh m = random_soup(rng, nv, nf);
        const RepairStats s = make_manifold(m);
        const Topology t = topology(m);
        EXPECT_TRUE(t.oriented_manifold()) << "trial " << trial << ": " << t.nonmanifold_edges << " nm edges, "
                                           << t.misoriented_edges << " misoriented, " << t.nonmanifold_vertices
                                           << " nm vertices";
        EXPECT_LE(m.triangles.rows(), nf);
        EXPECT_EQ(m.triangles.rows() + s.degenerate_removed + s.duplicates_removed + s.nonmanifold_removed, nf);
        // Every vertex kept is used.
        std::vector<char> used(static_cast<size_t>(m.points.rows()), 0);
        for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
            for (int j = 0; j < 3; ++j) used[m.triangles(f, j)] = 1;
        EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
    }
}

TEST(Repair, MoebiusBandIsCutToBecomeOrientable) {
    // A Moebius band of 12 quads: no orientation exists, so a triangle must go.
    const int n = 12;
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < n; ++i) {
        const double u = 2 * M_PI * i / n;
        for (double s : {-0.3, 0.3}) {
            const double r = 1 + s * std::cos(u / 2);
            pts.emplace_back(r * std::cos(u), r * std::sin(u), s * std::sin(u / 2));
        }
    }
    std::vector<std::array<int32_t, 3>> tris;
    for (int i = 0; i < n; ++i) {
        const int32_t a = 2 * i, b = 2 * i + 1;
        // The last quad joins the strip back with its sides swapped.
        const int32_t c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
        tris.push_back({a, c, d});
        tris.push_back({a, d, b});
    }
    Mesh m = make_mesh(pts, tris);
    ASSERT_EQ(topology(m).chi, 0);
    const RepairStats s = make_manifold(m);
    EXPECT_GE(s.nonmanifold_removed, 1);
    EXPECT_TRUE(topology(m).oriented_manifold());
}

TEST(Repair, RejectsOutOfRangeIndices) {
    Mesh m = make_icosphere(0);
    m.triangles(3, 1) = 99;
    EXPECT_THROW(make_manifold(m), InvalidInput);
}
