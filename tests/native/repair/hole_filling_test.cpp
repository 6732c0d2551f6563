#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/repair/hole_filling.h"
#include "liftremesh/repair/repair.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <random>
#include <array>
#include <set>
#include <algorithm>

using namespace liftremesh;
using namespace liftremesh::test;

namespace {

// Whether every loop edge loop[i] -> loop[i+1] is traversed by a triangle the other way,
// b -> a (the documented convention), and no vertex repeats within a loop.
void expect_loops_follow_convention(const Mesh& m, const std::vector<std::vector<int32_t>>& loops) {
    std::set<std::pair<int32_t, int32_t>> directed;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) directed.insert({m.triangles(f, j), m.triangles(f, (j + 1) % 3)});
    for (const auto& loop : loops) {
        EXPECT_EQ(std::set<int32_t>(loop.begin(), loop.end()).size(), loop.size()) << "loop is not simple";
        for (size_t i = 0; i < loop.size(); ++i) {
            const int32_t a = loop[i], b = loop[(i + 1) % loop.size()];
            EXPECT_TRUE(directed.count({b, a})) << a << " -> " << b;
            EXPECT_FALSE(directed.count({a, b})) << a << " -> " << b;
        }
    }
}

// Vertex of the mesh with the given valence (number of triangles around it).
int32_t vertex_with_valence(const Mesh& m, int valence) {
    std::vector<int> count(static_cast<size_t>(m.points.rows()), 0);
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) ++count[m.triangles(f, j)];
    for (size_t v = 0; v < count.size(); ++v)
        if (count[v] == valence) return static_cast<int32_t>(v);
    return -1;
}

// A disk of k triangles along the great-circle arc from p to q: grown from the triangle nearest
// p by adding, each time, the neighbour nearest the arc among those that share exactly one
// edge with the disk and whose third vertex is new (so the region stays a topological disk).
std::set<Eigen::Index> band(const Mesh& m, const Eigen::Vector3d& p, const Eigen::Vector3d& q, size_t k) {
    auto distance_to_arc = [&](Eigen::Index f) {
        const Eigen::Vector3d c = ((corner(m, f, 0) + corner(m, f, 1) + corner(m, f, 2)) / 3.0).normalized();
        double best = 1e9;
        for (int s = 0; s <= 50; ++s) best = std::min(best, (c - (p + (q - p) * s / 50.0).normalized()).norm());
        return best;
    };
    Eigen::Index seed = 0;
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        if ((corner(m, f, 0) - p.normalized()).norm() < (corner(m, seed, 0) - p.normalized()).norm()) seed = f;
    std::set<Eigen::Index> disk = {seed};
    std::set<int32_t> verts = {m.triangles(seed, 0), m.triangles(seed, 1), m.triangles(seed, 2)};
    while (disk.size() < k) {
        Eigen::Index best = -1;
        double best_d = 1e9;
        for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
            if (disk.count(f)) continue;
            int in = 0;
            for (int j = 0; j < 3; ++j) in += verts.count(m.triangles(f, j)) ? 1 : 0;
            if (in != 2) continue; // exactly one shared edge... if the two shared vertices form an edge of the disk
            bool shares_edge = false;
            for (Eigen::Index g : disk) {
                int common = 0;
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) common += m.triangles(f, i) == m.triangles(g, j);
                shares_edge = shares_edge || common == 2;
            }
            if (!shares_edge) continue;
            const double d = distance_to_arc(f);
            if (d < best_d) {
                best_d = d;
                best = f;
            }
        }
        if (best < 0) break;
        disk.insert(best);
        for (int j = 0; j < 3; ++j) verts.insert(m.triangles(best, j));
    }
    return disk;
}

// An annulus of m quads between a loop at radius 1 and one at radius 1.6, both on the saddle
// z = amplitude * (r^2 / 1) cos(2 theta), facing +z. Vertices 0..m-1 are the inner loop.
Mesh saddle_annulus(int m, double amplitude) {
    std::vector<Eigen::Vector3d> pts;
    for (double r : {1.0, 1.6})
        for (int i = 0; i < m; ++i) {
            const double t = 2 * M_PI * i / m;
            pts.emplace_back(r * std::cos(t), r * std::sin(t), amplitude * r * r * std::cos(2 * t));
        }
    std::vector<std::array<int32_t, 3>> tris;
    for (int i = 0; i < m; ++i) {
        const int32_t in0 = i, in1 = (i + 1) % m, out0 = m + i, out1 = m + (i + 1) % m;
        tris.push_back({in0, out0, out1});
        tris.push_back({in0, out1, in1});
    }
    return make_mesh(pts, tris);
}

// A 10 x 10 grid of unit squares in z = 0, facing +z, without the 2 x 2 cells around its
// centre vertex: its points and triangles, and the index of the point (i, j).
struct GridWithHole {
    static constexpr int n = 10;
    std::vector<Eigen::Vector3d> pts;
    std::vector<std::array<int32_t, 3>> tris;
    static int32_t id(int i, int j) { return static_cast<int32_t>(j * (n + 1) + i); }
    GridWithHole() {
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) pts.emplace_back(i, j, 0.0);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                if ((i == 4 || i == 5) && (j == 4 || j == 5)) continue;
                tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            }
    }
};

bool contains(const std::vector<int32_t>& loop, int32_t v) { return std::find(loop.begin(), loop.end(), v) != loop.end(); }

} // namespace

TEST(HoleFilling, ClosedMeshHasNoLoopAndNothingToFill) {
    Mesh m = make_icosphere(2);
    EXPECT_TRUE(boundary_loops(m).empty());
    EXPECT_EQ(fill_holes(m, {}).filled, 0);
}

TEST(HoleFilling, LoopRunsOppositeToTheTriangleOnEachEdge) {
    const Mesh sphere = make_icosphere(3);
    const int32_t v = vertex_with_valence(sphere, 6);
    Mesh m = without_triangles(sphere, triangles_at(sphere, v));
    const auto loops = boundary_loops(m);
    ASSERT_EQ(loops.size(), 1u);
    EXPECT_EQ(loops[0].size(), 6u);
    expect_loops_follow_convention(m, loops);

    // A removed triangle comes back as its own loop, in its own orientation (up to rotation).
    Mesh one = without_triangles(sphere, {42});
    const auto l = boundary_loops(one);
    ASSERT_EQ(l.size(), 1u);
    ASSERT_EQ(l[0].size(), 3u);
    const std::array<int32_t, 3> removed = {sphere.triangles(42, 0), sphere.triangles(42, 1), sphere.triangles(42, 2)};
    int shift = -1;
    for (int s = 0; s < 3; ++s)
        if (l[0][s] == removed[0]) shift = s;
    ASSERT_GE(shift, 0);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(l[0][(shift + j) % 3], removed[j]);
}

TEST(HoleFilling, SingleTriangleHoleIsClosed) {
    const Mesh sphere = make_icosphere(3);
    Mesh m = without_triangles(sphere, {100});
    const Eigen::Index before = m.triangles.rows();
    EXPECT_EQ(fill_holes(m, {}).filled, 1);
    const Topology t = topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(m.triangles.rows(), before + 1);
    EXPECT_GT(min_kappa(m, before), 0.2);
    EXPECT_EQ(m.points, sphere.points); // no vertex added or moved
}

TEST(HoleFilling, VertexFanHoleIsClosedWithGoodTriangles) {
    const Mesh sphere = make_icosphere(3);
    for (int valence : {5, 6}) {
        const int32_t v = vertex_with_valence(sphere, valence);
        ASSERT_GE(v, 0);
        Mesh m = without_triangles(sphere, triangles_at(sphere, v));
        const Eigen::Index before = m.triangles.rows();
        EXPECT_EQ(fill_holes(m, {}).filled, 1);
        const Topology t = topology(m);
        EXPECT_TRUE(t.closed_oriented_manifold()) << "valence " << valence;
        EXPECT_EQ(t.chi, 2);
        EXPECT_EQ(m.triangles.rows(), before + valence - 2);
        EXPECT_GT(min_kappa(m, before), 0.2);
        EXPECT_EQ(facing_inward(m, Eigen::Vector3d::Zero(), before), 0);
    }
}

TEST(HoleFilling, BandHoleIsClosedWithGoodTriangles) {
    const Mesh sphere = make_icosphere(3);
    const auto drop = band(sphere, Eigen::Vector3d(1, 0, 0.1), Eigen::Vector3d(0.3, 1, -0.1), 20);
    Mesh m = without_triangles(sphere, drop);
    const auto loops = boundary_loops(m);
    ASSERT_EQ(loops.size(), 1u) << "the band should be one disk-shaped hole";
    const Eigen::Index before = m.triangles.rows();
    EXPECT_EQ(fill_holes(m, {}).filled, 1);
    const Topology t = topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(m.triangles.rows(), before + static_cast<Eigen::Index>(loops[0].size()) - 2);
    EXPECT_GT(min_kappa(m, before), 0.2);
    EXPECT_EQ(facing_inward(m, Eigen::Vector3d::Zero(), before), 0);
}

TEST(HoleFilling, HoleLargerThanTheSurfaceLeftIsFilledFacingOutward) {
    // Only a cap (z > 0.7) of the sphere is left: the hole winds clockwise about the cap's
    // normals, and the flat fill must face down, closing a lens. The cap's boundary has 8
    // "teeth" (triangles with two boundary edges) whose third edge joins two loop vertices, so
    // that chord is closed to the fill. With no tooth left, the planar CDT is free; with 2,
    // ear clipping gets stuck on them and the exact planar triangulation must take over; with
    // all 8, no flat triangulation avoids them: the fill may fold, but it must still close.
    for (int teeth_left : {0, 2, 8}) {
        const Mesh sphere = make_icosphere(3);
        std::set<Eigen::Index> drop;
        for (Eigen::Index f = 0; f < sphere.triangles.rows(); ++f)
            if ((corner(sphere, f, 0) + corner(sphere, f, 1) + corner(sphere, f, 2)).z() / 3.0 < 0.7) drop.insert(f);
        Mesh m = without_triangles(sphere, drop);
        std::map<std::pair<int32_t, int32_t>, int> uses;
        for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
            for (int j = 0; j < 3; ++j) {
                const int32_t a = m.triangles(f, j), b = m.triangles(f, (j + 1) % 3);
                ++uses[{std::min(a, b), std::max(a, b)}];
            }
        std::set<Eigen::Index> teeth;
        for (Eigen::Index f = 0; f < m.triangles.rows(); ++f) {
            int boundary = 0;
            for (int j = 0; j < 3; ++j) {
                const int32_t a = m.triangles(f, j), b = m.triangles(f, (j + 1) % 3);
                boundary += uses[{std::min(a, b), std::max(a, b)}] == 1;
            }
            if (boundary == 2) teeth.insert(f);
        }
        ASSERT_EQ(teeth.size(), 8u);
        for (int k = 0; k < teeth_left; ++k) teeth.erase(teeth.begin());
        m = without_triangles(m, teeth);
        ASSERT_EQ(boundary_loops(m).size(), 1u);
        const Eigen::Index before = m.triangles.rows();
        EXPECT_EQ(fill_holes(m, {}).filled, 1);
        const Topology t = topology(m);
        EXPECT_TRUE(t.closed_oriented_manifold()) << teeth_left << " teeth";
        EXPECT_EQ(t.chi, 2);
        if (teeth_left < 8)
            for (Eigen::Index f = before; f < m.triangles.rows(); ++f)
                EXPECT_LT((corner(m, f, 1) - corner(m, f, 0)).cross(corner(m, f, 2) - corner(m, f, 0)).z(), 0.0)
                    << teeth_left << " teeth";
    }
}

TEST(HoleFilling, SeveralHolesAreCountedAndAllClosed) {
    const Mesh sphere = make_icosphere(3);
    std::set<Eigen::Index> drop = triangles_at(sphere, 0); // valence 5 at the icosahedron vertex 0
    for (Eigen::Index f : {300, 700, 1100}) drop.insert(f);
    const auto far_band = band(sphere, Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0.5, 0, -0.8), 12);
    drop.insert(far_band.begin(), far_band.end());
    Mesh m = without_triangles(sphere, drop);
    const auto loops = boundary_loops(m);
    EXPECT_EQ(fill_holes(m, {}).filled, static_cast<long>(loops.size()));
    const Topology t = topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
}

TEST(HoleFilling, TorusKeepsItsGenus) {
    const Mesh torus = make_torus(2.0, 0.7, 32, 16);
    ASSERT_EQ(topology(torus).chi, 0);
    std::set<Eigen::Index> drop = triangles_at(torus, 5);
    for (Eigen::Index f : {200, 201, 202}) drop.insert(f);
    Mesh m = without_triangles(torus, drop);
    EXPECT_GE(fill_holes(m, {}).filled, 1);
    const Topology t = topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 0);
}

TEST(HoleFilling, PredicateLeavesTheOuterBoundaryOfAPlanarGridOpen) {
    const GridWithHole grid;
    auto id = &GridWithHole::id;
    Mesh m = make_mesh(grid.pts, grid.tris);
    ASSERT_EQ(boundary_loops(m).size(), 2u);
    ASSERT_EQ(topology(m).chi, 0);
    const int32_t corner_vertex = id(0, 0);
    const Eigen::Index before = m.triangles.rows();
    long asked = 0;
    const long filled = fill_holes(m, {[&](const std::vector<int32_t>& loop) {
                                        ++asked;
                                        return !contains(loop, corner_vertex);
                                    }}).filled;
    EXPECT_EQ(asked, 2);
    EXPECT_EQ(filled, 1);
    const Topology t = topology(m);
    EXPECT_TRUE(t.oriented_manifold());
    EXPECT_EQ(t.chi, 1);
    const auto left = boundary_loops(m);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_TRUE(contains(left[0], corner_vertex));
    EXPECT_EQ(m.triangles.rows(), before + 6); // 8 loop vertices -> 6 triangles
    for (Eigen::Index f = before; f < m.triangles.rows(); ++f) {
        const Eigen::Vector3d nrm = (corner(m, f, 1) - corner(m, f, 0)).cross(corner(m, f, 2) - corner(m, f, 0));
        EXPECT_GT(nrm.z(), 0.0) << "new triangle " << f << " is flat or faces down";
        EXPECT_EQ(nrm.x(), 0.0);
        EXPECT_EQ(nrm.y(), 0.0);
    }
    EXPECT_GT(min_kappa(m, before), 0.2);
}

// A dart: a triangle on the rim of a hole whose third vertex no other triangle uses, jutting
// across the hole and past its far side, as RLF_7030's slots left one (a site that kept one
// triangle of its fan). The loop round it crosses itself, and any fill of it folds; without the
// dart the hole is the 2 x 2 cells' square, filled flat.
TEST(HoleFilling, ADartJuttingAcrossAHoleIsRemovedBeforeTheFill) {
    GridWithHole grid;
    auto id = &GridWithHole::id;
    auto& pts = grid.pts;
    auto& tris = grid.tris;
    const Mesh holed = make_mesh(pts, tris);
    const auto dart_tip = static_cast<int32_t>(pts.size());
    pts.emplace_back(4.5, 6.5, 0.0); // past the hole's far side, y = 6
    tris.push_back({id(4, 4), id(5, 4), dart_tip});
    Mesh m = make_mesh(pts, tris);
    ASSERT_TRUE(topology(m).oriented_manifold());
    auto inner = [&](const std::vector<int32_t>& loop) { return !contains(loop, id(0, 0)); };

    Mesh folded = m; // filled as it is
    ASSERT_EQ(fill_holes(folded, {inner}).filled, 1);
    long facing_down = 0;
    for (Eigen::Index f = m.triangles.rows(); f < folded.triangles.rows(); ++f)
        facing_down += (corner(folded, f, 1) - corner(folded, f, 0)).cross(corner(folded, f, 2) - corner(folded, f, 0)).z() < 0.0;
    EXPECT_GT(facing_down, 0);

    EXPECT_EQ(remove_darts(m, {inner}), 1);
    EXPECT_EQ(m.triangles, holed.triangles);
    EXPECT_EQ(remove_darts(m, {inner}), 0);
    const Eigen::Index before = m.triangles.rows();
    ASSERT_EQ(fill_holes(m, {inner}).filled, 1);
    for (Eigen::Index f = before; f < m.triangles.rows(); ++f)
        EXPECT_GT((corner(m, f, 1) - corner(m, f, 0)).cross(corner(m, f, 2) - corner(m, f, 0)).z(), 0.0);
    EXPECT_TRUE(topology(m).oriented_manifold());
    // The sheet's corners at (10, 0) and (0, 10) are such triangles too: the outer boundary is
    // not a hole to fill, and they stay.
    Mesh sheet = holed;
    EXPECT_EQ(remove_darts(sheet, {inner}), 0);
    EXPECT_EQ(sheet.triangles, holed.triangles);
}

TEST(HoleFilling, ConvexPlanarHoleGetsTheDelaunayTriangulation) {
    // A convex hole in a plane: its constrained Delaunay triangulation is the Delaunay
    // triangulation of the loop vertices, so no loop vertex may lie inside the circumcircle of a
    // new triangle. The loop is an ellipse with jittered radii, tilted out of the coordinate
    // planes so that the projection is not trivial.
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> jitter(-0.04, 0.04);
    const int n = 40;
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    std::vector<Eigen::Vector2d> flat;
    for (double scale : {1.0, 1.5})
        for (int i = 0; i < n; ++i) {
            const double t = 2 * M_PI * (i + (scale > 1.0 ? 0.5 : jitter(rng) * 3)) / n;
            const double r = scale * (scale > 1.0 ? 1.0 : 1.0 + jitter(rng));
            flat.emplace_back(2.0 * r * std::cos(t), r * std::sin(t));
        }
    std::vector<Eigen::Vector3d> pts;
    for (const auto& x : flat) pts.push_back(tilt * Eigen::Vector3d(x.x(), x.y(), 0.0));
    std::vector<std::array<int32_t, 3>> tris;
    for (int i = 0; i < n; ++i) {
        const int32_t in0 = i, in1 = (i + 1) % n, out0 = n + i, out1 = n + (i + 1) % n;
        tris.push_back({in0, out0, out1});
        tris.push_back({in0, out1, in1});
    }
    Mesh m = make_mesh(pts, tris);
    const Eigen::Index before = m.triangles.rows();
    ASSERT_EQ(fill_holes(m, {[](const std::vector<int32_t>& loop) { return contains(loop, 0); }}).filled, 1);
    ASSERT_EQ(m.triangles.rows(), before + n - 2);
    EXPECT_TRUE(topology(m).oriented_manifold());
    long violations = 0;
    for (Eigen::Index f = before; f < m.triangles.rows(); ++f) {
        const Eigen::Vector2d a = flat[m.triangles(f, 0)], b = flat[m.triangles(f, 1)], c = flat[m.triangles(f, 2)];
        // Circumcentre of (a, b, c).
        const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
        ASSERT_GT(d, 0.0) << "new triangle " << f << " is not counter-clockwise in the plane";
        const Eigen::Vector2d centre(
            (a.squaredNorm() * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) + c.squaredNorm() * (a.y() - b.y())) / d,
            (a.squaredNorm() * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) + c.squaredNorm() * (b.x() - a.x())) / d);
        const double r2 = (a - centre).squaredNorm();
        for (int i = 0; i < n; ++i)
            if ((flat[i] - centre).squaredNorm() < r2 * (1 - 1e-9)) ++violations;
    }
    EXPECT_EQ(violations, 0);
}

TEST(HoleFilling, SaddleLoopIsFilledWithoutNonManifoldEdges) {
    // Mild saddle: the projection onto the PCA plane is simple. Strong saddle: it folds (points
    // coincide in projection), so the 3D fallback must do the job.
    for (double amplitude : {0.3, 2.5}) {
        for (int count : {16, 17}) {
            Mesh m = saddle_annulus(count, amplitude);
            const Eigen::Index before = m.triangles.rows();
            const long filled = fill_holes(m, {[](const std::vector<int32_t>& loop) { return contains(loop, 0); }}).filled;
            EXPECT_EQ(filled, 1) << "amplitude " << amplitude << ", " << count << " vertices";
            const Topology t = topology(m);
            EXPECT_TRUE(t.oriented_manifold()) << "amplitude " << amplitude;
            EXPECT_EQ(t.chi, 1);
            EXPECT_EQ(m.triangles.rows(), before + count - 2);
            const auto left = boundary_loops(m);
            ASSERT_EQ(left.size(), 1u);
            EXPECT_FALSE(contains(left[0], 0));
        }
    }
}

// A hole across a knife edge, as the restricted Delaunay triangulation left one on the 30-degree
// wedge of the crease prism (tests/freecad/cad_parts.py, 6000 vertices, seed 1): the surface
// within 2.2 mm of it, faces y = 0 (facing -y) and the wedge's other face (facing
// (-0.5, 0.87, 0)) meeting along the z axis. Most of the hole's loop lies on the first face, a
// spike on the other, the rest on the edge. Projected onto the loop's best-fit plane the spike
// folds over, and its constrained Delaunay triangulation held a triangle turned right over
// against the face beside it (kappa 0.02 in the output). The fill must not fold back.
TEST(HoleFilling, AHoleAcrossAKnifeEdgeIsNotFilledFoldedBack) {
    const std::vector<Eigen::Vector3d> points = {
        {1.0239, 0.5911, 1.7084}, {0.0861, 0.0222, 1.7399}, {1.8784, 0.0000, 2.2426}, {0.1263, 0.0339, 1.9910},
        {0.7919, 0.4550, 2.4816}, {1.4531, 0.8389, 2.4573}, {2.3282, 0.0000, 2.8259}, {1.7712, 1.0226, 3.0445},
        {0.0769, 0.0192, 2.5201}, {0.5025, 0.2901, 2.9049}, {0.7923, 0.4645, 3.1797}, {1.0072, -0.0000, 2.3600},
        {0.6434, 0.0000, 3.0692}, {0.2782, 0.1138, 3.1201}, {1.4498, 0.0000, 2.9766}, {2.6621, 0.0000, 3.5972},
        {0.1446, 0.0441, 3.4942}, {0.1276, 0.0300, 3.6083}, {1.4869, 0.8584, 3.6150}, {0.9185, 0.5333, 4.0213},
        {1.6236, 0.9374, 4.2923}, {2.0789, 1.2003, 3.7121}, {1.9683, 0.0000, 3.4542}, {1.9791, 0.0000, 4.1396},
        {1.1255, 0.0000, 3.7577}, {2.6722, 0.0000, 4.3965}, {0.1342, 0.0317, 4.1065}, {1.2033, 0.0000, 4.5542},
        {0.0802, 0.0231, 4.4026}, {0.9864, 0.5695, 4.7497}, {0.1326, 0.0322, 4.7570}, {2.2402, 1.2934, 4.3889},
        {0.0810, 0.0233, 5.1124}, {1.7329, 1.0005, 4.9671}, {0.1547, 0.0386, 5.4195}, {1.0776, 0.6221, 5.4762},
        {1.2194, 0.0000, 5.2974}, {2.0074, -0.0000, 4.8789}, {0.1132, 0.0336, 5.6780},
    };
    const std::vector<std::array<int32_t, 3>> triangles = {
        {0, 1, 3}, {0, 4, 5}, {0, 3, 4}, {4, 3, 8}, {4, 8, 9}, {4, 10, 5}, {4, 9, 10}, {3, 11, 8}, {8, 11, 12},
        {8, 13, 9}, {8, 12, 13}, {11, 2, 14}, {11, 14, 12}, {13, 10, 9}, {13, 16, 10}, {13, 12, 16},
        {10, 16, 17}, {10, 18, 7}, {10, 7, 5}, {10, 17, 19}, {10, 19, 18}, {2, 6, 14}, {18, 19, 20},
        {18, 21, 7}, {18, 20, 21}, {22, 6, 15}, {22, 15, 23}, {22, 14, 6}, {22, 24, 14}, {22, 23, 24},
        {15, 25, 23}, {26, 27, 28}, {19, 28, 29}, {19, 29, 20}, {28, 30, 29}, {28, 27, 30}, {24, 23, 27},
        {21, 20, 31}, {29, 30, 32}, {29, 33, 20}, {29, 32, 34}, {29, 34, 35}, {29, 35, 33}, {30, 27, 36},
        {30, 36, 32}, {27, 23, 37}, {27, 37, 36}, {33, 31, 20}, {23, 25, 37}, {32, 36, 34}, {34, 38, 35},
    };
    Mesh m = make_mesh(points, triangles);
    const Eigen::Index before = m.triangles.rows();
    const std::vector<int32_t> hole = {12, 14, 24, 27, 26, 28, 19, 17, 16};
    const long filled = fill_holes(m, {[&](const std::vector<int32_t>& loop) {
                                       return loop.size() == hole.size() && contains(loop, hole[0]) && contains(loop, hole[6]);
                                   }}).filled;
    ASSERT_EQ(filled, 1);
    ASSERT_EQ(m.triangles.rows(), before + static_cast<Eigen::Index>(hole.size()) - 2);
    // Each new triangle against the triangles it shares an edge with: never turned by more than
    // 165 degrees (a knife edge of 15 degrees inside).
    const EdgeUses edges = edge_uses(m.triangles);
    auto normal = [&](long f) { return triangle_normal(corner(m, f, 0), corner(m, f, 1), corner(m, f, 2)); };
    double worst = 1.0;
    for (long e = 0; e < edges.size(); ++e) {
        if (edges.count(e) != 2) continue;
        const long f = edges.uses.begin(e)[0] / 3, g = edges.uses.begin(e)[1] / 3;
        if (std::max(f, g) >= before) worst = std::min(worst, normal(f).dot(normal(g)));
    }
    EXPECT_GT(worst, std::cos(165.0 * M_PI / 180.0)) << "the cosine of the largest turn at a new triangle";
    EXPECT_TRUE(topology(m).oriented_manifold());
}

TEST(HoleFilling, PinchedBoundaryIsSplitIntoSimpleLoops) {
    // Two triangles of a valence-6 fan that share only the centre vertex: the boundary passes
    // through the centre twice.
    const Mesh sphere = make_icosphere(3);
    const int32_t v = vertex_with_valence(sphere, 6);
    const auto fan = triangles_at(sphere, v);
    const Eigen::Index first = *fan.begin();
    Eigen::Index opposite = -1;
    for (Eigen::Index f : fan) {
        int shared = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) shared += sphere.triangles(f, i) == sphere.triangles(first, j);
        if (shared == 1) opposite = f;
    }
    ASSERT_GE(opposite, 0);
    Mesh m = without_triangles(sphere, {first, opposite});
    ASSERT_EQ(topology(m).nonmanifold_vertices, 1);
    const auto loops = boundary_loops(m);
    ASSERT_EQ(loops.size(), 2u);
    for (const auto& loop : loops) {
        EXPECT_EQ(loop.size(), 3u);
        EXPECT_TRUE(contains(loop, v));
    }
    expect_loops_follow_convention(m, loops);
    EXPECT_EQ(fill_holes(m, {}).filled, 2);
    const Topology t = topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
}

TEST(HoleFilling, ThousandVertexLoopsAreFilled) {
    // An open tube: two planar loops of 1000 vertices, one circular (all co-circular, the
    // hardest case for the Delaunay flips), one star-shaped and strongly non-convex. Plus a
    // 1000-vertex strong saddle that needs the 3D fallback.
    const int n = 1000;
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < n; ++i) {
        const double t = 2 * M_PI * i / n;
        pts.emplace_back(std::cos(t), std::sin(t), 0.0);
    }
    for (int i = 0; i < n; ++i) {
        const double t = 2 * M_PI * i / n, r = 1.0 + 0.4 * std::sin(37 * t);
        pts.emplace_back(r * std::cos(t), r * std::sin(t), 1.0);
    }
    std::vector<std::array<int32_t, 3>> tris;
    for (int i = 0; i < n; ++i) {
        const int32_t a = i, b = (i + 1) % n, c = n + (i + 1) % n, d = n + i;
        tris.push_back({a, b, c});
        tris.push_back({a, c, d});
    }
    Mesh tube = make_mesh(pts, tris);
    ASSERT_EQ(boundary_loops(tube).size(), 2u);
    EXPECT_EQ(fill_holes(tube, {}).filled, 2);
    Topology t = topology(tube);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);

    Mesh saddle = saddle_annulus(n, 2.5);
    EXPECT_EQ(fill_holes(saddle, {[](const std::vector<int32_t>& loop) { return contains(loop, 0); }}).filled, 1);
    t = topology(saddle);
    EXPECT_TRUE(t.oriented_manifold());
    EXPECT_EQ(t.chi, 1);
}

TEST(HoleFilling, NeverCreatesAnEdgeTheMeshAlreadyHas) {
    // Two triangles forming a square: its loop's short diagonal is taken, so the fill must
    // use the other one (a flat, two-sided pillow, but a valid closed manifold).
    Mesh quad = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
    EXPECT_EQ(fill_holes(quad, {}).filled, 1);
    EXPECT_TRUE(topology(quad).closed_oriented_manifold());

    // A lone triangle: filling its loop would duplicate it, so it is left alone.
    Mesh lone = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
    EXPECT_EQ(fill_holes(lone, {}).filled, 0);
    EXPECT_EQ(lone.triangles.rows(), 1);

    // A tetrahedron missing two faces: the loop 0-2-1-3 has the diagonal 0-1 already, so
    // the fill must take 2-3, which closes the tetrahedron.
    Mesh tet = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}});
    const auto loops = boundary_loops(tet);
    ASSERT_EQ(loops.size(), 1u);
    ASSERT_EQ(loops[0].size(), 4u);
    EXPECT_EQ(fill_holes(tet, {}).filled, 1);
    const Topology t = topology(tet);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(facing_inward(tet, Eigen::Vector3d(0.25, 0.25, 0.25)), 0);
}

TEST(HoleFilling, DegenerateLoopsDoNotBreakIt) {
    // A cone over four collinear points: its boundary loop has zero area.
    Mesh cone = make_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {1.5, 1, 0}},
                          {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
    ASSERT_EQ(boundary_loops(cone).size(), 1u);
    fill_holes(cone, {});
    EXPECT_TRUE(topology(cone).oriented_manifold());

    // All points at one place.
    Mesh point = make_mesh({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
                           {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
    fill_holes(point, {});
    EXPECT_TRUE(topology(point).oriented_manifold());

    Mesh empty;
    EXPECT_EQ(fill_holes(empty, {}).filled, 0);
    EXPECT_TRUE(boundary_loops(empty).empty());

    Mesh bad = make_icosphere(0);
    bad.triangles(0, 0) = -1;
    EXPECT_THROW(fill_holes(bad, {}), InvalidInput);
}

TEST(HoleFilling, RepairedRandomSoupsStayOrientedManifolds) {
    std::mt19937 rng(777);
    for (int trial = 0; trial < 40; ++trial) {
        const int nv = 10 + trial % 30, nf = 20 + 9 * trial;
        Mesh m = random_soup(rng, nv, nf);
        make_manifold(m);
        const auto loops = boundary_loops(m);
        expect_loops_follow_convention(m, loops);
        const long filled = fill_holes(m, {}).filled;
        EXPECT_LE(filled, static_cast<long>(loops.size()));
        const Topology t = topology(m);
        EXPECT_TRUE(t.oriented_manifold()) << "trial " << trial << ": " << t.nonmanifold_edges << " nm edges, "
                                           << t.misoriented_edges << " misoriented, " << t.nonmanifold_vertices
                                           << " nm vertices, " << t.duplicates << " duplicates";
        EXPECT_EQ(static_cast<long>(boundary_loops(m).size()), static_cast<long>(loops.size()) - filled);
    }
}
