// Vertices on the chords of a curved crease onto the curve: the rims of a 16-sided prism (a
// cylinder as a CAD export tessellates it) go onto the circle, a cube's straight creases and a
// slot's straight sides between two arcs stay straight, and no vertex moves farther than asked.
#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/snap/crease_curves.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/self_intersection.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

using namespace liftremesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A prism of height `height` over the closed polygon `ring` (counter-clockwise in the plane
// z = 0), each side cut into `cuts` pieces, outward oriented: the side strip alone, or with its
// two caps fanned from the origin's column. The bottom ring's vertices come first, then the top's.
Mesh prism(const std::vector<Eigen::Vector2d>& ring, double height, int cuts, bool caps) {
    std::vector<Eigen::Vector2d> around;
    for (size_t i = 0; i < ring.size(); ++i)
        for (int c = 0; c < cuts; ++c)
            around.push_back(ring[i] + (ring[(i + 1) % ring.size()] - ring[i]) * (static_cast<double>(c) / cuts));
    const int32_t m = static_cast<int32_t>(around.size());
    std::vector<Eigen::Vector3d> pts;
    for (double z : {0.0, height})
        for (const Eigen::Vector2d& p : around) pts.emplace_back(p.x(), p.y(), z);
    std::vector<std::array<int32_t, 3>> tris;
    for (int32_t i = 0; i < m; ++i) {
        const int32_t j = (i + 1) % m;
        tris.push_back({i, j, m + j});
        tris.push_back({i, m + j, m + i});
    }
    if (caps) {
        pts.emplace_back(0.0, 0.0, 0.0);
        pts.emplace_back(0.0, 0.0, height);
        for (int32_t i = 0; i < m; ++i) {
            const int32_t j = (i + 1) % m;
            tris.push_back({2 * m, j, i});
            tris.push_back({2 * m + 1, m + i, m + j});
        }
    }
    return test::make_mesh(pts, tris);
}

// n points round the circle of radius r about c, from angle `from` to `to` (radians), both ends
// included unless the arc closes.
std::vector<Eigen::Vector2d> arc(const Eigen::Vector2d& c, double r, double from, double to, int chords, bool closed) {
    std::vector<Eigen::Vector2d> out;
    for (int i = 0; i < (closed ? chords : chords + 1); ++i) {
        const double a = from + (to - from) * i / chords;
        out.push_back(c + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return out;
}

// The worst kappa of the triangles at vertex v.
double worst_kappa_at(const Mesh& mesh, Eigen::Index v) {
    double worst = 1.0;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        if ((mesh.triangles.row(f).array() == v).any())
            worst = std::min(worst, triangle_kappa(mesh.points.row(mesh.triangles(f, 0)).transpose(),
                                                   mesh.points.row(mesh.triangles(f, 1)).transpose(),
                                                   mesh.points.row(mesh.triangles(f, 2)).transpose()));
    return worst;
}

CreaseCurveParams unbounded() {
    CreaseCurveParams p;
    p.near = 1e-3; // the vertices on chords lie on them, the others farther
    p.max_move = 1.0;
    p.kappa_floor = 0.0;
    return p;
}

// A slot's outline: two half circles of radius 1 about (-2, 0) and (2, 0), 8 chords each, and the
// two straight sides 4 long between them.
std::vector<Eigen::Vector2d> slot() {
    std::vector<Eigen::Vector2d> ring = arc({2.0, 0.0}, 1.0, -0.5 * kPi, 0.5 * kPi, 8, false);
    for (const Eigen::Vector2d& p : arc({-2.0, 0.0}, 1.0, 0.5 * kPi, 1.5 * kPi, 8, false)) ring.push_back(p);
    return ring;
}

} // namespace

TEST(CreaseCurves, PutTheRimsOfAFacetedCylinderOnItsCircles) {
    const std::vector<Eigen::Vector2d> circle = arc({0.0, 0.0}, 1.0, 0.0, 2.0 * kPi, 16, true);
    const Mesh input = prism(circle, 0.3, 1, true);
    Mesh mesh = prism(circle, 0.3, 4, false);
    const double sagitta = 1.0 - std::cos(kPi / 16.0);
    double worst_before = 0.0;
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v)
        worst_before = std::max(worst_before, 1.0 - mesh.points.row(v).head<2>().norm());
    ASSERT_NEAR(worst_before, sagitta, 1e-12); // the chords' middles, as the input leaves them
    const Mesh was = mesh;
    const CreaseCurveStats stats = move_onto_crease_curves(mesh, input, unbounded());
    EXPECT_EQ(stats.creases, 2 * 16);
    EXPECT_EQ(stats.moved, 2 * 16 * 3); // all but the polygon's own corners
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v) {
        EXPECT_NEAR(mesh.points.row(v).head<2>().norm(), 1.0, 1e-5 * sagitta) << "vertex " << v; // a cubic on an arc
        EXPECT_NEAR(mesh.points(v, 2), was.points(v, 2), 1e-15) << "vertex " << v; // within the rim's plane
        if (v % 4 == 0) EXPECT_EQ(mesh.points.row(v), was.points.row(v)) << "corner " << v;
    }
    const test::Topology after = test::topology(mesh);
    EXPECT_EQ(after.chi, test::topology(was).chi);
}

TEST(CreaseCurves, MoveNoVertexFartherThanAsked) {
    const std::vector<Eigen::Vector2d> circle = arc({0.0, 0.0}, 1.0, 0.0, 2.0 * kPi, 16, true);
    const Mesh input = prism(circle, 0.3, 1, true);
    Mesh mesh = prism(circle, 0.3, 4, false);
    const Mesh was = mesh;
    CreaseCurveParams p = unbounded();
    p.max_move = 0.005; // a quarter of the sagitta
    EXPECT_EQ(move_onto_crease_curves(mesh, input, p).moved, 2 * 16 * 3);
    double largest = 0.0;
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v)
        largest = std::max(largest, (mesh.points.row(v) - was.points.row(v)).norm());
    EXPECT_NEAR(largest, p.max_move, 1e-12);
}

// The pipeline hands the step the crease snap's creases, sampled at the snap's spacing: the moves
// are those of the creases the step finds itself, at spacings from a tenth of a chord to two.
TEST(CreaseCurves, TakeTheSameStepsWithCreasesFoundAtAnySpacing) {
    const std::vector<Eigen::Vector2d> circle = arc({0.0, 0.0}, 1.0, 0.0, 2.0 * kPi, 16, true);
    const Mesh input = prism(circle, 0.3, 1, true);
    const Mesh was = prism(circle, 0.3, 4, false);
    const CreaseCurveParams p = unbounded();
    Mesh own = was;
    const long moved = move_onto_crease_curves(own, input, p).moved;
    ASSERT_EQ(moved, 2 * 16 * 3);
    for (const double spacing : {0.04, 0.4, 0.8}) {
        Mesh given = was;
        const AcuteCreases creases(input, p.min_turn_deg, spacing, p.min_length);
        EXPECT_EQ(move_onto_crease_curves(given, input, creases, p).moved, moved) << "spacing " << spacing;
        EXPECT_EQ(given.points, own.points) << "spacing " << spacing;
    }
}

TEST(CreaseCurves, LeaveStraightCreasesStraight) {
    const Mesh input = test::make_cube(1.0, 2); // a vertex in each edge's middle: chains of two
    Mesh mesh = test::make_cube(1.0, 6);
    const Mesh was = mesh;
    const CreaseCurveStats stats = move_onto_crease_curves(mesh, input, unbounded());
    EXPECT_EQ(stats.creases, 24);
    EXPECT_LE((mesh.points - was.points).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(CreaseCurves, KeepASlotsSidesStraightBetweenItsArcs) {
    const Mesh input = prism(slot(), 0.3, 1, true);
    Mesh mesh = prism(slot(), 0.3, 4, false);
    const Mesh was = mesh;
    move_onto_crease_curves(mesh, input, unbounded());
    int on_arcs = 0;
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v) {
        const Eigen::Vector2d x = was.points.row(v).head<2>().transpose();
        if (std::abs(x.x()) < 2.0) { // on a straight side
            EXPECT_LE((mesh.points.row(v) - was.points.row(v)).norm(), 1e-12) << "vertex " << v;
        } else {
            const Eigen::Vector2d centre(x.x() > 0.0 ? 2.0 : -2.0, 0.0);
            // The tangents at the arcs' ends from one side only: within a twentieth of the chords'
            // sagitta (0.019) of the circle.
            EXPECT_NEAR((mesh.points.row(v).head<2>().transpose() - centre).norm(), 1.0, 1e-3) << "vertex " << v;
            ++on_arcs;
        }
    }
    EXPECT_EQ(on_arcs, 2 * 2 * (8 * 4 + 1));
    // Without the chords' length ratio, the junctions count as smooth and the sides bulge.
    Mesh bulging = was;
    CreaseCurveParams any_ratio = unbounded();
    any_ratio.max_chord_ratio = 100.0;
    move_onto_crease_curves(bulging, input, any_ratio);
    EXPECT_GT((bulging.points - was.points).rowwise().norm().maxCoeff(), 0.05);
}

TEST(CreaseCurves, RefuseAMoveThatWouldSpoilATriangle) {
    const std::vector<Eigen::Vector2d> circle = arc({0.0, 0.0}, 1.0, 0.0, 2.0 * kPi, 16, true);
    const Mesh input = prism(circle, 0.3, 1, true);
    // The output's caps fanned from the axis: thin triangles, whose kappa a rim vertex moved out
    // changes. With the floor above all of them, a move may only leave them better.
    Mesh mesh = prism(circle, 0.3, 4, true);
    CreaseCurveParams p = unbounded();
    p.kappa_floor = 1.0;
    const Mesh was = mesh;
    const CreaseCurveStats stats = move_onto_crease_curves(mesh, input, p);
    EXPECT_LT(stats.moved, 2 * 16 * 3);
    // Each move leaves its fan's worst triangle no worse: so the whole mesh's.
    double worst_before = 1.0, worst_after = 1.0;
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v) {
        worst_before = std::min(worst_before, worst_kappa_at(was, v));
        worst_after = std::min(worst_after, worst_kappa_at(mesh, v));
    }
    EXPECT_GE(worst_after, worst_before);
    // Without the floor every one moves, and some fans are left worse than they were.
    Mesh unfloored = was;
    EXPECT_EQ(move_onto_crease_curves(unfloored, input, unbounded()).moved, 2 * 16 * 3);
    int worse = 0;
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v) worse += worst_kappa_at(unfloored, v) < worst_kappa_at(was, v);
    EXPECT_GT(worse, 0);
}

TEST(CreaseCurves, MoveNoVertexThroughAnotherPartOfTheSurface) {
    const std::vector<Eigen::Vector2d> circle = arc({0.0, 0.0}, 1.0, 0.0, 2.0 * kPi, 16, true);
    // A cup: the top rim a crease, the bottom one a border, whose vertices stay.
    Mesh input = prism(circle, 0.3, 1, true);
    std::vector<Eigen::Index> cup;
    for (Eigen::Index f = 0; f < input.triangles.rows(); ++f)
        if ((input.triangles.row(f).array() != input.points.rows() - 2).all()) cup.push_back(f);
    input.triangles = Triangles(input.triangles(cup, Eigen::all));
    const Mesh strip = prism(circle, 0.3, 4, false);
    // A sheet standing across the first chord's middle between the chord (0.981 from the axis
    // there) and the circle, as the other part of an assembly touching this one would.
    const double mid = kPi / 16.0, at = 0.99;
    const Eigen::Vector3d radial(std::cos(mid), std::sin(mid), 0.0), along(-std::sin(mid), std::cos(mid), 0.0);
    std::vector<Eigen::Vector3d> corners;
    for (double z : {0.05, 0.45})
        for (double t : {-0.08, 0.08}) corners.push_back(at * radial + t * along + Eigen::Vector3d(0.0, 0.0, z));
    const Mesh sheet = test::make_mesh(corners, std::vector<std::array<int32_t, 3>>{{0, 1, 3}, {0, 3, 2}});
    Mesh mesh = test::joined(strip, sheet);
    ASSERT_EQ(count_self_intersections(mesh, AabbTree(mesh)), 0);
    const Eigen::Index middle = strip.points.rows() / 2 + 2; // the top ring's first chord's middle
    const Eigen::Vector3d was = mesh.points.row(middle).transpose();
    move_onto_crease_curves(mesh, input, unbounded());
    EXPECT_EQ(count_self_intersections(mesh, AabbTree(mesh)), 0);
    EXPECT_LT(mesh.points.row(middle).head<2>().norm(), at);
    // Without the sheet it goes onto the circle, through where the sheet stands.
    Mesh alone = strip;
    move_onto_crease_curves(alone, input, unbounded());
    EXPECT_NEAR(alone.points.row(middle).head<2>().norm(), 1.0, 1e-6);
    EXPECT_LT(was.head<2>().norm(), at);
}

TEST(CreaseCurves, RejectParametersOutOfRange) {
    const Mesh input = test::make_cube(1.0, 2);
    Mesh mesh = test::make_cube(1.0, 4);
    for (auto spoil : {+[](CreaseCurveParams& p) { p.near = -1.0; }, +[](CreaseCurveParams& p) { p.max_move = NAN; },
                       +[](CreaseCurveParams& p) { p.smooth_turn_deg = 0.0; },
                       +[](CreaseCurveParams& p) { p.max_chord_ratio = 0.5; },
                       +[](CreaseCurveParams& p) { p.min_length = -1.0; }}) {
        CreaseCurveParams p = unbounded();
        spoil(p);
        EXPECT_THROW(move_onto_crease_curves(mesh, input, p), InvalidInput);
    }
}
