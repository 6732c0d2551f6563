// Creases and corners of the input kept (issue 35, the feature angle): prisms built in code, a box
// with a chamfered edge (45-degree creases) and a prism whose side creases turn by 30 to 150
// degrees, remeshed with the crease snap alone (hold_creases off) and with the creases held (the
// default); every corner (where three creases meet) lies near an output vertex, and the creases
// lie along output edges that bend. And the junctions of t13's creases. The measure is issue 35's: crease samples within 0.1 h of an
// output edge over 15 degrees, h the target edge length.
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/pipeline.h"
#include "helpers.h"
#include "topology_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

using namespace liftremesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A polygon whose sides turn by `turns_deg` (summing to 360) at its corners, the first sides of
// the given lengths, the last two solved so that it closes (both positive for the turns below).
std::vector<Eigen::Vector2d> polygon_with_turns(const std::vector<double>& turns_deg, const std::vector<double>& sides) {
    std::vector<Eigen::Vector2d> dirs;
    double heading = 0.0;
    for (double t : turns_deg) {
        dirs.emplace_back(std::cos(heading * kPi / 180.0), std::sin(heading * kPi / 180.0));
        heading += t;
    }
    Eigen::Vector2d known = Eigen::Vector2d::Zero();
    for (size_t i = 0; i < sides.size(); ++i) known += sides[i] * dirs[i];
    Eigen::Matrix2d m;
    m.col(0) = dirs[dirs.size() - 2];
    m.col(1) = dirs.back();
    const Eigen::Vector2d last = m.colPivHouseholderQr().solve(-known);
    std::vector<double> lengths = sides;
    lengths.push_back(last(0));
    lengths.push_back(last(1));
    std::vector<Eigen::Vector2d> out = {Eigen::Vector2d::Zero()};
    for (size_t i = 0; i + 1 < lengths.size(); ++i) out.push_back(out.back() + lengths[i] * dirs[i]);
    return out;
}

// An edge used by two triangles (as a -> b and b -> a, a < b), with the cosine of the turn
// between their normals.
struct TurningEdge {
    int32_t a, b;
    double cos_turn;
};
std::vector<TurningEdge> turning_edges(const Mesh& mesh) {
    std::map<std::pair<int32_t, int32_t>, Eigen::Index> by_edge;
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j) by_edge[{mesh.triangles(f, j), mesh.triangles(f, (j + 1) % 3)}] = f;
    auto normal = [&](Eigen::Index f) { return triangle_normal(corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2)); };
    std::vector<TurningEdge> out;
    for (const auto& [e, f] : by_edge) {
        const auto twin = by_edge.find({e.second, e.first});
        if (twin != by_edge.end() && e.first < e.second) out.push_back({e.first, e.second, normal(f).dot(normal(twin->second))});
    }
    return out;
}

// The figures of issue 35 for a prism: crease recall and the worst corner distance, in h.
struct CreaseFigures {
    double recall = 0.0;
    double worst_corner_h = 0.0;
    double spurious = 0.0; // the length of the output's edges over 40 degrees 0.5 h from every crease, over theirs
};

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d d = b - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (a + t * d - p).norm();
}

// Every edge of the prism is a crease (its faces turn by 90 degrees at the rims, by the polygon's
// turns at the sides, all >= 30 for the polygons below) and every vertex a corner.
CreaseFigures crease_figures(const Mesh& input, const Mesh& output, double h) {
    // The output's edges whose two triangles turn by 15 degrees or more.
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> bent;
    for (const TurningEdge& e : turning_edges(output))
        if (std::acos(std::clamp(e.cos_turn, -1.0, 1.0)) >= 15.0 * kPi / 180.0)
            bent.emplace_back(output.points.row(e.a).transpose(), output.points.row(e.b).transpose());
    // The input's edges between two non-coplanar triangles, sampled every 0.05 h.
    long samples = 0, found = 0;
    for (const TurningEdge& e : turning_edges(input)) {
        if (e.cos_turn > std::cos(30.0 * kPi / 180.0)) continue;
        const Eigen::Vector3d a = input.points.row(e.a).transpose(), b = input.points.row(e.b).transpose();
        const int n = static_cast<int>(std::ceil((b - a).norm() / (0.05 * h)));
        for (int i = 0; i <= n; ++i) {
            const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n);
            double nearest = std::numeric_limits<double>::infinity();
            for (const auto& [s, t] : bent) nearest = std::min(nearest, segment_distance(p, s, t));
            ++samples;
            found += nearest <= 0.1 * h ? 1 : 0;
        }
    }
    CreaseFigures figures;
    figures.recall = static_cast<double>(found) / static_cast<double>(samples);
    double crease_length = 0.0, spurious_length = 0.0;
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> creases;
    for (const TurningEdge& e : turning_edges(input))
        if (e.cos_turn <= std::cos(30.0 * kPi / 180.0)) {
            creases.emplace_back(input.points.row(e.a).transpose(), input.points.row(e.b).transpose());
            crease_length += (creases.back().second - creases.back().first).norm();
        }
    for (const TurningEdge& e : turning_edges(output)) {
        if (std::acos(std::clamp(e.cos_turn, -1.0, 1.0)) <= 40.0 * kPi / 180.0) continue;
        const Eigen::Vector3d a = output.points.row(e.a).transpose(), b = output.points.row(e.b).transpose();
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& [s, t] : creases) nearest = std::min(nearest, segment_distance(0.5 * (a + b), s, t));
        if (nearest > 0.5 * h) spurious_length += (b - a).norm();
    }
    figures.spurious = spurious_length / crease_length;
    for (Eigen::Index v = 0; v < input.points.rows(); ++v)
        figures.worst_corner_h = std::max(
            figures.worst_corner_h, test::distance_to_nearest_vertex(output, input.points.row(v).transpose()) / h);
    return figures;
}

double edge_length_for(const Mesh& input, int vertices) {
    return std::sqrt(surface_area(input) / (std::sqrt(3.0) / 2.0 * vertices));
}

struct PrismCase {
    const char* name;
    std::vector<Eigen::Vector2d> polygon;
    double height;
    double min_recall; // issue 35's 0.99, or the closest met (docs/known-gaps.md)
};

std::vector<PrismCase> prism_cases() {
    // A 2 x 1 x 1 box with one vertical edge chamfered 0.3 wide: 45-degree creases and corners.
    const std::vector<Eigen::Vector2d> chamfered = {{0.0, 0.0}, {2.0, 0.0}, {2.0, 0.7}, {1.7, 1.0}, {0.0, 1.0}};
    return {{"ChamferedBox", chamfered, 1.0, 0.99},
            // Sides turning by 30, 60, 45, 75 and 150 degrees (a 30-degree wedge at the last corner).
            // Recall 0.984 while the moves onto the knife edge kept kappa 0.45: its row kept a few
            // vertices off it. They keep the project's 0.3 there now (steps.h).
            {"CreasesOf30To150Degrees", polygon_with_turns({30, 60, 45, 75, 150}, {4.0, 1.0, 1.0}), 1.5, 0.99}};
}

// At 6000 vertices, as issue 35 measures.
struct Remeshed {
    CreaseFigures figures;
    RemeshResult result;
};
Remeshed remesh_prism(const PrismCase& c, bool hold_creases = false) {
    const Mesh input = test::make_prism(c.polygon, c.height);
    const int vertices = 6000;
    RemeshParams params = test::params_with(vertices);
    params.hold_creases = hold_creases;
    RemeshResult r = remesh(input, params);
    const CreaseFigures figures = crease_figures(input, r.mesh, edge_length_for(input, vertices));
    return {figures, std::move(r)};
}

class CreasePrism : public ::testing::TestWithParam<int> {};

// Without the creases over the feature angle (feature_angle 180: the knife edges' snap only) the
// chamfered box came out with recall 0.991 and a corner 0.149 h from the nearest vertex, the
// other prism with recall 0.945 and a corner 0.488 h away.
TEST_P(CreasePrism, CornersOnVerticesAndCreasesAlongEdges) {
    const PrismCase c = prism_cases()[GetParam()];
    const auto [figures, r] = remesh_prism(c);
    EXPECT_GE(figures.recall, c.min_recall) << c.name;
    EXPECT_LE(figures.worst_corner_h, 0.1) << c.name;
    EXPECT_GE(r.report.output.kappa_min, 0.3) << c.name;
    EXPECT_GE(r.report.output.kappa_mean, 0.9) << c.name;
    EXPECT_TRUE(test::topology(r.mesh).closed_oriented_manifold()) << c.name;
    EXPECT_EQ(r.report.output.euler_characteristic, 2) << c.name;
}

// With the sites held on the creases (crease_sites.h), issue 35's literal bar on both prisms: the
// second's recall 0.997 or more and every corner on a vertex on seeds 1-8.
TEST_P(CreasePrism, HeldCreasesMeetTheLiteralBar) {
    const PrismCase c = prism_cases()[GetParam()];
    const auto [figures, r] = remesh_prism(c, true);
    EXPECT_GE(figures.recall, 0.99) << c.name;
    EXPECT_LE(figures.worst_corner_h, 0.1) << c.name;
    EXPECT_GE(r.report.output.kappa_min, 0.3) << c.name;
    EXPECT_GE(r.report.output.kappa_mean, 0.9) << c.name;
    EXPECT_TRUE(test::topology(r.mesh).closed_oriented_manifold()) << c.name;
    EXPECT_EQ(r.report.output.euler_characteristic, 2) << c.name;
    EXPECT_GT(r.report.crease_sites, 0) << c.name;
}

// The 30-degree wedge of the second prism, its knife edge's sites held, on seeds 1-12: edges
// between two of them were missing on seeds 5, 11 and 12 (spurious 0.021-0.025, Hausdorff
// 0.64-0.73%), where the cell of a site on one face reached round the edge onto the other and
// the triangulation joined the faces through the wedge (cvt/rdt.h).
TEST(CreasePrism, AKnifeEdgeHeldKeepsItsEdgesOnTwelveSeeds) {
    const PrismCase c = prism_cases()[1];
    const Mesh input = test::make_prism(c.polygon, c.height);
    const int vertices = 6000;
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        RemeshParams params = test::params_with(vertices);
        params.seed = seed;
        const RemeshResult r = remesh(input, params);
        const CreaseFigures figures = crease_figures(input, r.mesh, edge_length_for(input, vertices));
        EXPECT_GE(figures.recall, 0.99) << "seed " << seed;
        EXPECT_LE(figures.spurious, 0.02) << "seed " << seed;
        EXPECT_LE(r.report.hausdorff_relative, 0.005) << "seed " << seed;
        EXPECT_GE(r.report.output.kappa_min, 0.3) << "seed " << seed;
    }
}

INSTANTIATE_TEST_SUITE_P(Prisms, CreasePrism, ::testing::Values(0, 1),
                         [](const ::testing::TestParamInfo<int>& info) { return std::string(prism_cases()[info.param].name); });

} // namespace

namespace {

// The junctions of a mesh's creases as issue 35 takes them on a mesh without a B-rep: vertices
// where three or more edges whose two triangles turn by 30 degrees or more meet.
std::vector<Eigen::Vector3d> crease_junctions(const Mesh& mesh) {
    std::map<int32_t, int> degree;
    for (const TurningEdge& e : turning_edges(mesh))
        if (e.cos_turn <= std::cos(30.0 * kPi / 180.0)) {
            ++degree[e.a];
            ++degree[e.b];
        }
    std::vector<Eigen::Vector3d> out;
    for (const auto& [v, count] : degree)
        if (count >= 3) out.push_back(mesh.points.row(v).transpose());
    return out;
}

} // namespace

// gmsh_t13_data.stl has its junctions in pairs 0.39 h apart, where facets of 30.5 to 53 degrees
// meet round the ends of a cylinder; the vertex of one of a pair takes the other's too. Until
// the junctions no vertex could move onto were inserted (insert_input_points), one of a pair
// lay 0.26 h from the nearest vertex on seeds 1-3; issue 35 asks for 0.1 h.
TEST(SharedMeshCreases, EveryJunctionOfT13LiesOnAVertex) {
    LIFTREMESH_REQUIRE_SHARED(path, "gmsh_t13_data.stl");
    const Mesh input = read_mesh(path);
    const int vertices = 6000;
    const double h = edge_length_for(input, vertices);
    const std::vector<Eigen::Vector3d> junctions = crease_junctions(input);
    ASSERT_GE(junctions.size(), 6u);
    for (const std::uint64_t seed : {1, 2, 3}) {
        const RemeshResult r = remesh(input, test::params_with(vertices, RemeshParams{}.sigma, seed));
        double worst = 0.0;
        for (const Eigen::Vector3d& junction : junctions)
            worst = std::max(worst, test::distance_to_nearest_vertex(r.mesh, junction) / h);
        EXPECT_LE(worst, 0.1) << "seed " << seed;
        EXPECT_GE(r.report.output.kappa_min, 0.3) << "seed " << seed;
        EXPECT_GE(r.report.output.kappa_mean, 0.9) << "seed " << seed;
        EXPECT_TRUE(test::topology(r.mesh).closed_oriented_manifold()) << "seed " << seed;
        EXPECT_EQ(r.report.output.euler_characteristic, r.report.input.euler_characteristic) << "seed " << seed;
    }
}

// A prism on a triangle whose tip is a 22-degree knife edge (the triangle (0, 0), (10, 0),
// (0, 4), 6 high), at 267 vertices (edges of 0.9). Where the knife edge meets the caps, the
// triangulation often cuts the tip short by half an edge (its corner site's cell meets only two
// others, whose triangle the repair removes), and no split there reaches kappa 0.45: before the
// knife's junctions and the moves onto it kept the project's floor (steps.h), a tip lay 0.43 to
// 0.66 h from the nearest vertex on 7 of seeds 1-16; now on 6 (0.43 to 0.65 h: there the mesh's
// vertex nearest the tip would leave triangles of kappa 0.17 to 0.24, docs/known-gaps.md).
TEST(Remesh, TheTipsOfAKnifeEdgeLieOnVerticesOnTenSeedsOfSixteen) {
    const Mesh input = test::make_prism({{0.0, 0.0}, {10.0, 0.0}, {0.0, 4.0}}, 6.0);
    const int vertices = 267;
    const double h = edge_length_for(input, vertices);
    int on_vertices = 0;
    for (std::uint64_t seed = 1; seed <= 16; ++seed) {
        const RemeshResult r = remesh(input, test::params_with(vertices, RemeshParams{}.sigma, seed));
        const double worst = std::max(test::distance_to_nearest_vertex(r.mesh, Eigen::Vector3d(10.0, 0.0, 0.0)),
                                      test::distance_to_nearest_vertex(r.mesh, Eigen::Vector3d(10.0, 0.0, 6.0))) / h;
        on_vertices += worst <= 0.1 ? 1 : 0;
        EXPECT_GE(r.report.output.kappa_min, 0.3) << "seed " << seed;
        EXPECT_TRUE(test::topology(r.mesh).closed_oriented_manifold()) << "seed " << seed;
    }
    EXPECT_GE(on_vertices, 10);
}
