#include "liftremesh/edit/edge_collapse.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/measure/quality.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

using namespace liftremesh;

TEST(EdgeCollapse, RemovesACrowdedVertexAndKeepsTopology) {
    Mesh m = test::make_icosphere(3);
    // Pull vertex 50 almost onto one of its neighbours: two very short edges' worth of slivers.
    int32_t neighbour = -1;
    for (Eigen::Index f = 0; f < m.triangles.rows() && neighbour < 0; ++f)
        for (int j = 0; j < 3; ++j)
            if (m.triangles(f, j) == 50) neighbour = m.triangles(f, (j + 1) % 3);
    m.points.row(50) = 0.97 * m.points.row(neighbour) + 0.03 * m.points.row(50);
    const double before = test::min_kappa(m);
    const long vertices = m.points.rows();
    const long collapsed = collapse_short_edges(m, {}).collapsed;
    EXPECT_GE(collapsed, 1);
    EXPECT_EQ(m.points.rows(), vertices - collapsed);
    const test::Topology t = test::topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_GT(test::min_kappa(m), std::max(0.3, 2 * before));
    EXPECT_EQ(test::facing_inward(m, Eigen::Vector3d::Zero()), 0);
}

TEST(EdgeCollapse, LeavesAGoodMeshAlone) {
    Mesh m = test::make_icosphere(3);
    const Mesh original = m;
    EXPECT_EQ(collapse_short_edges(m, {}).collapsed, 0);
    EXPECT_EQ(m.triangles, original.triangles);
}

TEST(EdgeCollapse, RefusesCollapsesThatBreakTheLinkCondition) {
    // A tetrahedron: every collapse would make it degenerate.
    Mesh m = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.01}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
    EXPECT_EQ(collapse_short_edges(m, {10.0}).collapsed, 0);
    EXPECT_EQ(m.triangles.rows(), 4);
}

TEST(EdgeCollapse, NeverJoinsTwoBoundaryVerticesThroughTheInside) {
    // A strip one cell wide: every rung joins its two boundaries. Rung 5 is pinched to a short
    // edge; cells 4 and 5 are split by diagonals from its ends, the others fanned around a middle
    // vertex (so the vertices opposite the rung have four triangles). Collapsing the rung would
    // join the two boundaries at one vertex: a non-manifold vertex, the strip cut in two.
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    for (int i = 0; i <= 10; ++i) {
        p.emplace_back(i, 0.0, 0.0);
        p.emplace_back(i, i == 5 ? 0.04 : 1.0, 0.0);
    }
    for (int32_t i = 0; i < 10; ++i) {
        const int32_t a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1; // counter-clockwise
        if (i == 4) {
            f.push_back({a, b, d});
            f.push_back({d, b, c});
        } else if (i == 5) {
            f.push_back({a, b, c});
            f.push_back({a, c, d});
        } else {
            const auto m = static_cast<int32_t>(p.size());
            p.push_back((p[a] + p[b] + p[c] + p[d]) / 4.0);
            f.push_back({a, b, m});
            f.push_back({b, c, m});
            f.push_back({c, d, m});
            f.push_back({d, a, m});
        }
    }
    Mesh m = test::make_mesh(p, f);
    const test::Topology before = test::topology(m);
    ASSERT_TRUE(before.oriented_manifold());
    collapse_short_edges(m, {});
    const test::Topology after = test::topology(m);
    EXPECT_EQ(after.nonmanifold_vertices, 0);
    EXPECT_EQ(after.chi, before.chi);
    EXPECT_EQ(after.boundary_edges, before.boundary_edges);
}

namespace {

//! Vertex x of m (inside a closed surface) split in two along the path n_0 - x - n_(k/2) of its
//! neighbours n_0 ... n_(k-1) in fan order: x keeps the triangles from n_0 to n_(k/2), moved
//! `offset` towards them, a new vertex takes the others, moved as far towards those, and the
//! slit between them is closed by the edge n_0 - n_(k/2), not by an edge between the two halves
//! of x: two triangles (n_0, x, n_(k/2)) and (n_(k/2), x', n_0) folded shut onto each other.
Mesh with_pair_folded_shut(const Mesh& m, int32_t x, double offset) {
    std::map<int32_t, int32_t> next; // around x: (x, u, next[u]) is a triangle
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            if (m.triangles(f, j) == x) next[m.triangles(f, (j + 1) % 3)] = m.triangles(f, (j + 2) % 3);
    std::vector<int32_t> ring = {next.begin()->first};
    while (static_cast<int32_t>(ring.size()) < static_cast<int32_t>(next.size())) ring.push_back(next[ring.back()]);
    const size_t half = ring.size() / 2;
    Mesh out = m;
    const int32_t y = static_cast<int32_t>(m.points.rows());
    out.points.conservativeResize(y + 1, 3);
    Eigen::Vector3d towards_x = Eigen::Vector3d::Zero(), towards_y = Eigen::Vector3d::Zero();
    for (size_t i = 1; i < half; ++i) towards_x += m.points.row(ring[i]).transpose() / static_cast<double>(half - 1);
    for (size_t i = half + 1; i < ring.size(); ++i)
        towards_y += m.points.row(ring[i]).transpose() / static_cast<double>(ring.size() - half - 1);
    const Eigen::Vector3d p = m.points.row(x).transpose();
    for (Eigen::Index f = 0; f < m.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            if (m.triangles(f, j) == x) {
                const int32_t u = m.triangles(f, (j + 1) % 3);
                const size_t i = static_cast<size_t>(std::find(ring.begin(), ring.end(), u) - ring.begin());
                if (i >= half) out.triangles(f, j) = y;
            }
    out.points.row(x) = (p + offset * (towards_x - p).normalized()).transpose();
    out.points.row(y) = (p + offset * (towards_y - p).normalized()).transpose();
    const Eigen::Index rows = out.triangles.rows();
    out.triangles.conservativeResize(rows + 2, 3);
    out.triangles.row(rows) << ring[0], x, ring[half];
    out.triangles.row(rows + 1) << ring[half], y, ring[0];
    return out;
}

} // namespace

// An icosphere (edges of about 0.15) with a pair folded shut, made as a vertex split whose slit
// is closed the wrong way round: two triangles on the edge between two opposite neighbours of
// the vertex, 0.3 long and 0.011 under it, their apexes its two halves, 0.0005 to either side of
// where it was: they turn by about 175 degrees (the chip resistor 1210_SMD had such a pair at a
// corner of its body, 175 degrees, its apexes 4% of the edge apart). The pair goes, its apexes
// joined: the sphere again, one vertex and two triangles fewer, closed, nothing folded, no
// triangle facing inwards or under kappa 0.3.
TEST(FoldedPairs, APairFoldedShutIsRemovedAndTheSphereKept) {
    const Mesh sphere = test::make_icosphere(3);
    const int32_t x = 100; // valence 6 (not one of the icosahedron's twelve)
    Mesh m = with_pair_folded_shut(sphere, x, 0.0005);
    ASSERT_TRUE(test::topology(m).closed_oriented_manifold());
    ASSERT_EQ(test::topology(m).chi, 2);
    ASSERT_GT(measure_quality(m, {170.0}).sharp_edge_length, 0.0); // the fold
    const long vertices = m.points.rows(), triangles = m.triangles.rows();

    EXPECT_EQ(collapse_folded_pairs(m, test::OwnedReference(sphere)).collapsed, 1);
    EXPECT_EQ(m.points.rows(), vertices - 1);
    EXPECT_EQ(m.triangles.rows(), triangles - 2);
    const test::Topology t = test::topology(m);
    EXPECT_TRUE(t.closed_oriented_manifold());
    EXPECT_EQ(t.chi, 2);
    EXPECT_EQ(measure_quality(m, {90.0}).sharp_edge_length, 0.0);
    EXPECT_EQ(test::facing_inward(m, Eigen::Vector3d::Zero()), 0);
    EXPECT_GE(test::min_kappa(m), 0.3);
    EXPECT_EQ(collapse_folded_pairs(m, test::OwnedReference(sphere)).collapsed, 0); // nothing left to remove
}

// The same pair, its apexes 0.001 apart at an edge of 0.3, is left alone when the apexes must be
// closer than that (gap_ratio), or the turn larger (min_turn_deg).
TEST(FoldedPairs, ThePairMustTurnFarAndItsApexesBeClose) {
    const Mesh sphere = test::make_icosphere(3);
    const Mesh folded = with_pair_folded_shut(sphere, 100, 0.0005);
    for (const FoldedPairParams& p : {FoldedPairParams{150.0, 0.001, 0.3}, FoldedPairParams{179.0, 0.25, 0.3}}) {
        Mesh m = folded;
        EXPECT_EQ(collapse_folded_pairs(m, test::OwnedReference(sphere), p).collapsed, 0);
        EXPECT_EQ(m.triangles, folded.triangles);
    }
}

// The pair of with_pair_folded_shut: its edge's ends and the triangles' corners.
struct FoldedPair {
    Eigen::Vector3d a, b;
    std::array<std::array<Eigen::Vector3d, 3>, 2> triangles;
};

FoldedPair folded_pair_of(const Mesh& folded) {
    const Eigen::Index rows = folded.triangles.rows();
    FoldedPair pair;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 3; ++j) pair.triangles[k][j] = corner(folded, rows - 2 + k, j);
    pair.a = pair.triangles[0][0];
    pair.b = pair.triangles[0][2];
    return pair;
}

// The pair measured against an input that has the same two triangles, each apart (its own
// corners, joined to nothing: no crease): each lies on the input, facing as it does, and the pair
// is kept.
TEST(FoldedPairs, APairWhoseTrianglesFaceAsTheInputIsKept) {
    const Mesh sphere = test::make_icosphere(3);
    const Mesh folded = with_pair_folded_shut(sphere, 100, 0.0005);
    const FoldedPair pair = folded_pair_of(folded);
    Mesh input = sphere;
    for (const auto& t : pair.triangles) input = test::joined(input, test::make_mesh({t[0], t[1], t[2]}, {{0, 1, 2}}));
    Mesh m = folded;
    EXPECT_EQ(collapse_folded_pairs(m, test::OwnedReference(input)).collapsed, 0);
    EXPECT_EQ(m.triangles, folded.triangles);
    EXPECT_EQ(m.points, folded.points);
}

// The pair against an input with a knife edge (a tent of two triangles turning by 157 degrees)
// 0.08 outside the middle of the pair's edge, within its length (0.3) but farther from its
// triangles than the sphere (which they face against): kept, as a pair standing for that edge
// would be; with the knife edge taken as a crease only past 160 degrees, removed.
TEST(FoldedPairs, APairNearAKnifeEdgeOfTheInputIsKept) {
    const Mesh sphere = test::make_icosphere(3);
    const Mesh folded = with_pair_folded_shut(sphere, 100, 0.0005);
    const FoldedPair pair = folded_pair_of(folded);
    const Eigen::Vector3d mid = 0.5 * (pair.a + pair.b), r = mid.normalized(), t = (pair.b - pair.a).normalized();
    const Eigen::Vector3d s = r.cross(t), e = mid + 0.08 * r;
    const Mesh knife = test::make_mesh({e - 0.05 * t, e + 0.05 * t, e + 0.05 * r + 0.01 * s, e + 0.05 * r - 0.01 * s},
                                       {{0, 1, 2}, {1, 0, 3}});
    const Mesh input = test::joined(sphere, knife);
    Mesh m = folded;
    EXPECT_EQ(collapse_folded_pairs(m, test::OwnedReference(input)).collapsed, 0);
    EXPECT_EQ(m.triangles, folded.triangles);
    FoldedPairParams sharper;
    sharper.knife_turn_deg = 160.0;
    EXPECT_EQ(collapse_folded_pairs(m, test::OwnedReference(input), sharper).collapsed, 1);
}

TEST(FoldedPairs, RefusesParametersOutOfRange) {
    Mesh m = test::make_icosphere(1);
    const AabbTree tree(m);
    for (const FoldedPairParams& p : {FoldedPairParams{90.0, 0.25, 0.3}, FoldedPairParams{180.0, 0.25, 0.3},
                                      FoldedPairParams{150.0, 0.0, 0.3}, FoldedPairParams{150.0, 1.0, 0.3},
                                      FoldedPairParams{150.0, 0.25, -0.1}, FoldedPairParams{150.0, 0.25, 1.5},
                                      FoldedPairParams{150.0, 0.25, 0.3, 0.0}, FoldedPairParams{150.0, 0.25, 0.3, 180.0}})
        EXPECT_THROW(collapse_folded_pairs(m, {m, tree}, p), InvalidInput);
}

namespace {
// The 4 x 4 grid of make_square(4, 4) with its middle vertex (2, 2) moved to (2.45, 1.55, z),
// next to the edge (2, 1)-(3, 2) of its fan: a sliver there, as a polish leaves a vertex of a thin
// kite at its neighbours' centroid.
Mesh with_sliver(double z) {
    Mesh m = test::make_square(4.0, 4);
    m.points.row(12) << 2.45, 1.55, z;
    return m;
}

// A strip's triangle a-b-c, a (0, 0), b (2.84, 0), c (0.77, 0.567): kappa 0.299, its apex over
// a-b near a; the triangle a-b-(1.42, -1.3) below it and b-z-c beyond b-c, z (1.57, 1.61). Every
// vertex on the boundary.
Mesh strip_triangle() {
    return test::make_mesh({{0, 0, 0}, {2.84, 0, 0}, {0.77, 0.567, 0}, {1.42, -1.3, 0}, {1.57, 1.61, 0}},
                           {{0, 1, 2}, {1, 0, 3}, {1, 4, 2}});
}

// An oriented manifold with the Euler characteristic and boundary it `was` of.
void expect_topology_kept(const Mesh& m, const test::Topology& was) {
    const test::Topology is = test::topology(m);
    EXPECT_TRUE(is.oriented_manifold());
    EXPECT_EQ(is.chi, was.chi);
    EXPECT_EQ(is.boundary_edges, was.boundary_edges);
}
} // namespace

TEST(PoorTriangles, AVertexBesideAnEdgeOfItsFanIsCollapsed) {
    const Mesh input = test::make_square(4.0, 4);
    Mesh m = with_sliver(0.0);
    const double before = test::min_kappa(m);
    ASSERT_LT(before, 0.1);
    const test::Topology was = test::topology(m);
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.collapsed, 1);
    EXPECT_EQ(stats.split, 0);
    EXPECT_EQ(m.points.rows(), input.points.rows() - 1);
    EXPECT_GT(test::min_kappa(m), std::max(0.25, 4 * before)); // the hexagon fanned from one corner
    expect_topology_kept(m, was);
    EXPECT_EQ(m.points.col(2).cwiseAbs().maxCoeff(), 0.0); // still the square
}

TEST(PoorTriangles, APoorTriangleOfBoundaryVerticesHasItsLongEdgeSplit) {
    // Two triangles on the edge a-b, every vertex on the boundary: no collapse may move it. The
    // apex c lies 0.12 from the middle of a-b.
    const Mesh input = test::make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 0.12, 0}, {0.5, -0.6, 0}}, {{0, 1, 2}, {1, 0, 3}});
    Mesh m = input;
    const double before = test::min_kappa(m);
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.collapsed, 0);
    EXPECT_EQ(stats.split, 1);
    ASSERT_EQ(m.points.rows(), 5);
    EXPECT_TRUE(m.points.row(4).isApprox(Eigen::RowVector3d(0.5, 0, 0)));
    EXPECT_EQ(m.triangles.rows(), 4);
    EXPECT_GT(test::min_kappa(m), std::max(0.3, 2 * before));
    const test::Topology is = test::topology(m);
    EXPECT_TRUE(is.oriented_manifold());
    EXPECT_EQ(is.chi, 1);
    EXPECT_EQ(is.boundary_edges, 4);
}

TEST(PoorTriangles, ASplitWhoseHalfIsPoorHasThatHalfsRimFlipped) {
    // A strip's triangle a-b-c (kappa 0.299) whose apex c stands over a-b near a, every vertex on
    // the boundary: no collapse. Split at the middle m of a-b, the half m-b-c is worse (0.224), so
    // the split alone is refused; flipping b-c with the triangle b-z-c beyond it makes m-b-z and
    // m-z-c instead (0.87 and 0.74), as a mesh with a vertex more along the strip has.
    const Mesh input = strip_triangle();
    Mesh m = input;
    ASSERT_NEAR(test::min_kappa(m), 0.299, 0.001);
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.collapsed, 0);
    EXPECT_EQ(stats.split, 1);
    EXPECT_EQ(stats.flipped, 1);
    ASSERT_EQ(m.points.rows(), 6);
    EXPECT_TRUE(m.points.row(5).isApprox(Eigen::RowVector3d(1.42, 0, 0)));
    EXPECT_EQ(m.triangles.rows(), 5);
    EXPECT_GT(test::min_kappa(m), 0.6);
    const test::Topology is = test::topology(m);
    EXPECT_TRUE(is.oriented_manifold());
    EXPECT_EQ(is.chi, 1);
    EXPECT_EQ(is.boundary_edges, 5);
    EXPECT_EQ(m.points.col(2).cwiseAbs().maxCoeff(), 0.0); // still the plane
}

TEST(PoorTriangles, ASplitsFlipLeavesACreaseOnItsRim) {
    // The same, but b-z-c turned 30 degrees about b-c: b-c is a crease, which no flip may take
    // away, and the split alone would make a worse triangle. Nothing is done.
    Mesh input = strip_triangle();
    const Eigen::Vector3d b = input.points.row(1).transpose(), c = input.points.row(2).transpose();
    const Eigen::AngleAxisd turn(30.0 * M_PI / 180.0, (c - b).normalized());
    input.points.row(4) = (b + turn * (input.points.row(4).transpose() - b)).transpose();
    Mesh m = input;
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.split, 0);
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_EQ(m.points, input.points);
    EXPECT_EQ(m.triangles, input.triangles);
}

TEST(PoorTriangles, APoorTriangleOnACreaseHasItsCreaseEdgeSplit) {
    // The sliver's vertex 0.15 above the square, on the input: its fan is no plane a collapse
    // would keep, and its long edge (2, 1)-(3, 2) is a crease of the input, its two triangles
    // turning by 65 degrees. Split on it, each half stays on its face.
    const Mesh input = with_sliver(0.15);
    Mesh m = input;
    const double before = test::min_kappa(m);
    ASSERT_LT(before, 0.3);
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.collapsed, 0);
    EXPECT_EQ(stats.split, 1);
    ASSERT_EQ(m.points.rows(), input.points.rows() + 1);
    EXPECT_TRUE(m.points.bottomRows(1).isApprox(Eigen::RowVector3d(2.5, 1.5, 0.0)));
    EXPECT_GT(test::min_kappa(m), 0.3);
    expect_topology_kept(m, test::topology(input));
}

TEST(PoorTriangles, APoorTriangleOnAChordAcrossACreaseIsLeft) {
    // The same sliver, but the input splits the square's cell under its long edge by the other
    // diagonal, (3, 1)-(2.45, 1.55, 0.15): the long edge is a chord across that crease, its
    // middle 0.13 below the input. Split at the input's point nearest to it, on the crease, the
    // sliver's halves would turn by 49 and 55 degrees from it: left, where the crease's own
    // edge was split above.
    const Mesh mesh = with_sliver(0.15);
    ASSERT_LT(test::min_kappa(mesh), 0.3);
    Mesh input = mesh;
    const int32_t a = 7, b = 13, c = 12, d = 8; // (2, 1), (3, 2), the sliver's vertex, (3, 1)
    int replaced = 0;
    for (Eigen::Index f = 0; f < input.triangles.rows(); ++f) {
        const auto t = input.triangles.row(f);
        if ((t.array() == a).any() && (t.array() == b).any())
            input.triangles.row(f) = replaced++ == 0 ? Eigen::RowVector3i(a, d, c) : Eigen::RowVector3i(d, b, c);
    }
    ASSERT_EQ(replaced, 2);
    ASSERT_TRUE(test::topology(input).oriented_manifold());
    Mesh m = mesh;
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.collapsed + stats.split, 0);
    EXPECT_EQ(m.points, mesh.points);
    EXPECT_EQ(m.triangles, mesh.triangles);
}

TEST(PoorTriangles, AnEdgeFoldedShutOnTheInputIsNotSplit) {
    // The sliver's vertex moved across its long edge (2, 1)-(3, 2), to (2.55, 1.45): the sliver is
    // turned over onto the triangle across that edge, both on the flat input. The edge runs along
    // the input, but split at its middle, both its halves would be folded shut. (The vertex's move
    // leaves another poor triangle or two beside it, whose flat edges are split.)
    Mesh mesh = test::make_square(4.0, 4);
    mesh.points.row(12) << 2.55, 1.45, 0.0;
    const Mesh input = test::make_square(4.0, 4);
    ASSERT_LT(test::min_kappa(mesh), 0.3);
    Mesh m = mesh;
    mend_poor_triangles(m, test::OwnedReference(input));
    for (Eigen::Index v = mesh.points.rows(); v < m.points.rows(); ++v)
        EXPECT_GT((m.points.row(v) - Eigen::RowVector3d(2.5, 1.5, 0.0)).norm(), 1e-6) << "vertex " << v;
    EXPECT_TRUE(test::topology(m).oriented_manifold());
}

TEST(PoorTriangles, NoBoundaryVertexIsCollapsedAway) {
    // A rim L-B-R along y = 0 and V 0.1 above B: slivers (L, B, V) and (B, R, V). B's fan is flat,
    // V's is not (the vertex above it lifted): only B could go, and the rim would then run
    // through V, inside the surface.
    const std::vector<Eigen::Vector3d> p = {
        {-1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0.1, 0},   // L, B, R, V
        {-1, 1, 0}, {0, 1.2, 0.5}, {1, 1, 0},             // P1, P2 (lifted), P3
        {-2, 0, 0}, {-2, 1, 0}, {2, 0, 0}, {2, 1, 0}};    // LL, Q1, RR, Q3
    enum { L, B, R, V, P1, P2, P3, LL, Q1, RR, Q3 };
    const Mesh before = test::make_mesh(p, {{L, B, V}, {B, R, V}, {R, P3, V}, {V, P3, P2}, {V, P2, P1}, {V, P1, L},
                                            {LL, L, Q1}, {Q1, L, P1}, {R, RR, Q3}, {R, Q3, P3}});
    ASSERT_LT(test::min_kappa(before), 0.3);
    Mesh m = before;
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(before));
    EXPECT_EQ(stats.collapsed, 0);
    bool b_kept = false;
    for (Eigen::Index v = 0; v < m.points.rows(); ++v) b_kept = b_kept || m.points.row(v).isZero();
    EXPECT_TRUE(b_kept);
    EXPECT_TRUE(test::topology(m).oriented_manifold());
}

TEST(PoorTriangles, RefusesParametersOutOfRange) {
    Mesh m = test::make_square(1.0, 2);
    const test::OwnedReference input(m);
    PoorTriangleParams p;
    p.kappa_below = 1.5;
    EXPECT_THROW(mend_poor_triangles(m, input, p), InvalidInput);
    p = PoorTriangleParams{};
    p.flat_angle_deg = 90.0;
    EXPECT_THROW(mend_poor_triangles(m, input, p), InvalidInput);
}

TEST(PoorTriangles, AVertexOffAFlatFanGoesWhereTheSurfaceStaysAsNearTheInput) {
    // The grid's vertex (2, 2) moved to (2, 1.15), 0.15 from (2, 1): slivers on that short edge.
    // Its vertices on the flat input, but (2, 0) and (2, 3) 0.3 above it, as where the output cuts
    // across a feature of the input finer than its triangles. The sliver towards (3, 2) goes as
    // before, onto a vertex of a flat fan; the one towards (1, 1), kappa 0.27, would stay: of its
    // vertices only (1, 1) is on a flat fan, and no collapse of it helps. Collapsing the short
    // edge moves no triangle farther from the input than it was (those on (2, 3) rise to it as
    // high as before), and the vertex gone lies on those left: it goes. The tests above where
    // the mending leaves a vertex or splits an edge (the sliver on a crease, on a chord across
    // one, by the boundary) fail when the distances are not checked.
    const Mesh input = test::make_square(4.0, 4);
    Mesh m = input;
    m.points.row(12) << 2.0, 1.15, 0.0;
    m.points(2, 2) = m.points(17, 2) = 0.3;
    const double before = test::min_kappa(m);
    ASSERT_LT(before, 0.3);
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(input));
    EXPECT_EQ(stats.collapsed, 2);
    EXPECT_GT(test::min_kappa(m), 0.3);
    expect_topology_kept(m, test::topology(input));
}

TEST(PoorTriangles, TheSplitsVerticesAreGivenAsTheCollapsesRenumberThem) {
    // Two pieces mended in one pass: the boundary triangle of APoorTriangleOfBoundaryVertices...
    // (split at (0.5, 0, 0)), then, 10 away, the sliver that AVertexBesideAnEdge... collapses. The
    // collapse renumbers the vertices in order of first use, which puts the split's vertex,
    // first used by the first piece's triangles, among the first rather than last.
    const Mesh split_piece =
        test::make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 0.12, 0}, {0.5, -0.6, 0}}, {{0, 1, 2}, {1, 0, 3}});
    Mesh square = with_sliver(0.0);
    square.points.col(0).array() += 10.0;
    Mesh flat = test::make_square(4.0, 4);
    flat.points.col(0).array() += 10.0;
    Mesh m = test::joined(split_piece, square);
    const PoorTriangleStats stats = mend_poor_triangles(m, test::OwnedReference(test::joined(split_piece, flat)));
    EXPECT_EQ(stats.collapsed, 1);
    ASSERT_EQ(stats.split, 1);
    ASSERT_EQ(stats.added.size(), 1u);
    ASSERT_GE(stats.added[0], 0);
    ASSERT_LT(stats.added[0], m.points.rows());
    EXPECT_TRUE(m.points.row(stats.added[0]).isApprox(Eigen::RowVector3d(0.5, 0, 0)));
    EXPECT_FALSE(m.points.row(m.points.rows() - 1).isApprox(Eigen::RowVector3d(0.5, 0, 0))); // not last
}

TEST(PoorTriangles, ALongerEdgeAcrossIsSplitFirst) {
    // The frame's top face between a corner and its pin hole, 30,000 vertices, seed 3: a poor
    // triangle (0.23) from the corner a to the rim vertices c, e, whose long edge a-e runs to
    // the middle of the top face's crease edge a-f (2.53 long) beside it, over the wall
    // (a, f, w) at x = 0. Split at its middle, a-e leaves (a, m, f) at 0.12, and its rim a-f is
    // a crease no flip may take. The triangle across, (e, f, a), has the longer edge a-f: split
    // first, on the crease, its rim flip takes a-e and joins c to the crease's new vertex.
    const Mesh top = test::make_mesh({{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}}, {{0, 1, 2}, {0, 2, 3}});
    const Mesh wall = test::make_mesh({{0, 0, 0}, {0, 3, 0}, {0, 3, -3}, {0, 0, -3}}, {{0, 1, 2}, {0, 2, 3}});
    const test::OwnedReference input(test::joined(top, wall));
    // a, c, e, f, w
    Mesh m = test::make_mesh({{0, 0, 0}, {0.722, 1.048, 0}, {0.619, 1.895, 0}, {0, 2.531, 0}, {0, 1.86, -1.72}},
                             {{1, 2, 0}, {2, 3, 0}, {0, 3, 4}});
    const double before = test::min_kappa(m);
    ASSERT_NEAR(before, 0.23, 0.01);
    const PoorTriangleStats stats = mend_poor_triangles(m, input);
    EXPECT_EQ(stats.collapsed, 0);
    EXPECT_EQ(stats.split, 1);
    EXPECT_EQ(stats.flipped, 1);
    ASSERT_EQ(m.points.rows(), 6);
    EXPECT_TRUE(m.points.row(5).isApprox(Eigen::RowVector3d(0, 1.2655, 0)));
    EXPECT_GT(test::min_kappa(m), 0.5);
    const test::Topology is = test::topology(m);
    EXPECT_TRUE(is.oriented_manifold());
    EXPECT_EQ(is.chi, 1);
}
