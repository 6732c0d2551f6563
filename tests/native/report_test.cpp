#include "liftremesh/report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace liftremesh;

namespace {

RemeshReport sample_report() {
    RemeshReport r;
    r.input.vertices = 788;
    r.input.triangles = 1580;
    r.input.kappa_min = 0.0016;
    r.input.kappa_mean = 0.4831234567891;
    r.input.kappa_histogram = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    r.input.oriented = false;
    r.input.euler_characteristic = -2;
    r.output.kappa_min = std::numeric_limits<double>::quiet_NaN();
    r.output.sharp_edge_length = std::numeric_limits<double>::infinity();
    r.input_cleaning = {3, 10, 102}; // degenerate, duplicates, turned
    r.bbox_diagonal = 123.5;
    r.hausdorff_relative = 1.5e-5;
    r.sites = 6000;
    r.iterations = 42;
    r.energy_final = -std::numeric_limits<double>::infinity();
    r.timings = {{"read", 0.25}, {"optimize", 1.5}, {"read", 0.5}, {"odd \"name\"\n", 0.0}};
    return r;
}

size_t count(const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
    return n;
}

} // namespace

TEST(Report, JsonHasEveryKeyAndValidNumbers) {
    const std::string json = to_json(sample_report());
    for (const char* key :
         {"input", "output", "input_duplicates_removed", "input_degenerate_removed", "input_facets_turned", "bbox_diagonal", "hausdorff_relative", "mean_distance_relative", "sites", "iterations",
          "evaluations", "energy_initial", "energy_final", "crease_sites", "parts_unheld", "parts_eta_reduced", "sites_split", "parts", "parts_kept", "holes_filled", "triangles_removed", "edges_collapsed",
          "vertices_inserted", "edges_flipped", "vertices_moved", "boundary_vertices_snapped", "stray_components_removed", "stray_inward_removed", "cracks_closed",
          "vertex_fans_split", "expected_euler_characteristic", "timings", "warnings"})
        EXPECT_EQ(count(json, std::string("\"") + key + "\": "), 1u) << key;
    for (const char* key :
         {"vertices", "triangles", "kappa_min", "kappa_mean", "kappa_histogram", "min_angle_deg", "boundary_edges",
          "boundary_loops", "nonmanifold_edges", "nonmanifold_vertices", "extra_vertex_fans", "oriented", "euler_characteristic", "sharp_edge_length",
          "self_intersections", "components", "closed_components", "inward_components", "cavities", "component_list"})
        EXPECT_EQ(count(json, std::string("\"") + key + "\": "), 2u) << key;
    EXPECT_NE(json.find("\"kappa_histogram\": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]"), std::string::npos) << json;
    EXPECT_NE(json.find("\"kappa_mean\": 0.483123457,"), std::string::npos) << json; // 9 digits
    EXPECT_NE(json.find("\"euler_characteristic\": -2"), std::string::npos);
    EXPECT_NE(json.find("\"oriented\": false"), std::string::npos);
    EXPECT_NE(json.find("\"oriented\": true"), std::string::npos);
    EXPECT_NE(json.find("\"hausdorff_relative\": 1.5e-05"), std::string::npos) << json;
    EXPECT_NE(json.find("\"sites\": 6000"), std::string::npos);
    EXPECT_NE(json.find("\"input_duplicates_removed\": 10,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"input_degenerate_removed\": 3,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"input_facets_turned\": 102,"), std::string::npos) << json;
    // Non-finite values are null: NaN, inf and -inf are not JSON.
    EXPECT_EQ(count(json, "null"), 3u) << json;
    EXPECT_EQ(json.find("nan"), std::string::npos);
    EXPECT_EQ(json.find("inf"), std::string::npos);
    // A stage timed twice is summed, strings are escaped.
    EXPECT_NE(json.find("\"read\": 0.75"), std::string::npos) << json;
    EXPECT_EQ(count(json, "\"read\""), 1u);
    EXPECT_NE(json.find("\"odd \\\"name\\\"\\n\": 0"), std::string::npos) << json;
    // Balanced and closed.
    EXPECT_EQ(count(json, "{"), count(json, "}"));
    EXPECT_EQ(json.front(), '{');
    EXPECT_EQ(json.substr(json.size() - 2), "}\n");
    EXPECT_EQ(json.find(",\n}"), std::string::npos);
}

TEST(Report, WarnsOfAnotherTopologyNewHolesAndALargeDistance) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = 2;
    r.hausdorff_relative = 0.004;
    EXPECT_TRUE(report_warnings(r).empty());
    EXPECT_NE(to_json(r).find("\"warnings\": []"), std::string::npos) << to_json(r);

    r.output.euler_characteristic = -16;
    r.output.boundary_edges = 12;
    r.output.boundary_loops = 2;
    r.hausdorff_relative = 0.175;
    r.warnings = report_warnings(r);
    ASSERT_EQ(r.warnings.size(), 3u);
    EXPECT_NE(r.warnings[0].find("Euler characteristic -16, source 2"), std::string::npos) << r.warnings[0];
    EXPECT_NE(r.warnings[1].find("2 boundary loops, the source 0"), std::string::npos) << r.warnings[1];
    EXPECT_NE(r.warnings[2].find("18 %"), std::string::npos) << r.warnings[2];
    EXPECT_NE(to_json(r).find("\"warnings\": [\"the result's topology differs"), std::string::npos) << to_json(r);
}

TEST(Report, WarnsOfTrianglesPassingThroughEachOtherWhateverTheInputHas) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = 2;
    r.input.self_intersections = 424; // a soup (igl_truck.obj): still worth saying of the result
    EXPECT_TRUE(report_warnings(r).empty());
    r.output.self_intersections = 607;
    const std::vector<std::string> w = report_warnings(r);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("607 pairs of triangles passing through each other or touching (the source 424)"),
              std::string::npos)
        << w[0];
    EXPECT_NE(to_json(r).find("\"self_intersections\": 607"), std::string::npos) << to_json(r);
}

TEST(Report, WarnsOfFoldedEdgesBeyondTheSourcesKnifeEdges) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = 2;
    r.input.folded_edges = 4; // a knife edge of 1 under 10 degrees, in 4 edges
    r.input.folded_edge_length = 1.0;
    r.output.folded_edges = 9; // followed at a finer size: 9 edges, as long
    r.output.folded_edge_length = 1.05;
    EXPECT_TRUE(report_warnings(r).empty());
    r.output.folded_edges = 12; // and a patch facing against its neighbours
    r.output.folded_edge_length = 1.3;
    const std::vector<std::string> w = report_warnings(r);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("12 edges whose two triangles are folded onto each other (the source 4)"), std::string::npos)
        << w[0];
    EXPECT_NE(to_json(r).find("\"folded_edges\": 12"), std::string::npos) << to_json(r);
}

TEST(Report, WarnsOfPartsKeepingTheSourcesTriangles) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = 6;
    r.parts = 3;
    EXPECT_TRUE(report_warnings(r).empty());
    r.parts_kept = 1;
    std::vector<std::string> w = report_warnings(r);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("of the source's 3 parts, 1 is thinner or smaller than the target edge length and keeps the "
                        "source's triangles"),
              std::string::npos)
        << w[0];
    r.parts_kept = 2;
    w = report_warnings(r);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("2 are thinner or smaller than the target edge length and keep the source's"), std::string::npos)
        << w[0];
    EXPECT_NE(to_json(r).find("\"parts_kept\": 2"), std::string::npos) << to_json(r);
}

TEST(Report, WarnsOfPartsWhoseCreasesWereSnappedToRatherThanHeld) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = -14;
    r.parts = 3;
    r.crease_sites = 500;
    EXPECT_TRUE(report_warnings(r).empty());
    r.parts_unheld = 1;
    const std::vector<std::string> w = report_warnings(r);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("the creases of 1 of the source's 3 parts were snapped to, not held"), std::string::npos) << w[0];
    EXPECT_NE(to_json(r).find("\"parts_unheld\": 1"), std::string::npos) << to_json(r);
}

TEST(Report, WarnsOfPartsLiftedAgainOverSmallerBalls) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = -186;
    EXPECT_TRUE(report_warnings(r).empty());
    r.parts_eta_reduced = 1;
    const std::vector<std::string> w = report_warnings(r);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("the normals of 1 of the source's 1 part were averaged over balls a quarter"), std::string::npos)
        << w[0];
    EXPECT_NE(to_json(r).find("\"parts_eta_reduced\": 1"), std::string::npos) << to_json(r);
}

TEST(Report, AnOpenSurfaceKeepingItsBordersOrACrackClosedIsNoWarning) {
    // An open surface: its border, remeshed finer, has more edges but is still one loop.
    RemeshReport open;
    open.input.euler_characteristic = open.output.euler_characteristic = 1;
    open.input.boundary_edges = 3;
    open.output.boundary_edges = 348;
    open.input.boundary_loops = open.output.boundary_loops = 1;
    EXPECT_TRUE(report_warnings(open).empty());

    // A closed part with two cracks (gmsh_object.stl: chi 0, two loops) comes out closed (chi 2).
    RemeshReport cracked;
    cracked.input.euler_characteristic = 0;
    cracked.input.boundary_loops = 2;
    cracked.output.euler_characteristic = 2;
    EXPECT_EQ(cracks_closed(cracked), 2);
    EXPECT_EQ(cracks_closed(open), 0);
    EXPECT_TRUE(report_warnings(cracked).empty());
    // The JSON carries the counts, so that its readers (report_summary.py, the task panel) need
    // not repeat the rule.
    const std::string json = to_json(cracked);
    EXPECT_NE(json.find("\"cracks_closed\": 2,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"vertex_fans_split\": 0,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"expected_euler_characteristic\": 2,"), std::string::npos) << json;
    // Closing the cracks does not excuse another change: chi 1 with both loops gone, or chi 2
    // with one loop left, is another topology.
    cracked.output.euler_characteristic = 1;
    ASSERT_EQ(report_warnings(cracked).size(), 1u);
    EXPECT_NE(report_warnings(cracked)[0].find("Euler characteristic 1, source 0"), std::string::npos);
    cracked.output.euler_characteristic = 2;
    cracked.output.boundary_loops = 1;
    EXPECT_EQ(report_warnings(cracked).size(), 1u);
}

TEST(Report, PartsTouchingAtAVertexComingOutApartIsNoWarning) {
    // Two spheres touching at a vertex (chi 3, one vertex with two fans) come out as two spheres
    // (chi 4): the fan split is the repair, as in vertex_fans_split().
    RemeshReport touching;
    touching.input.euler_characteristic = 3;
    touching.input.nonmanifold_vertices = 1;
    touching.input.extra_vertex_fans = 1;
    touching.output.euler_characteristic = 4;
    touching.input.components = touching.output.components = 2; // joined through edges only
    EXPECT_EQ(vertex_fans_split(touching), 1);
    EXPECT_EQ(expected_euler_characteristic(touching), 4);
    EXPECT_TRUE(report_warnings(touching).empty());
    EXPECT_NE(to_json(touching).find("\"vertex_fans_split\": 1,"), std::string::npos);
    EXPECT_NE(to_json(touching).find("\"expected_euler_characteristic\": 4,"), std::string::npos);
    // Merged into one sphere (chi 2), or the pinch kept and a handle made (chi 1): warned.
    for (int chi : {2, 3}) {
        touching.output.euler_characteristic = chi;
        ASSERT_EQ(report_warnings(touching).size(), 1u) << chi;
        EXPECT_NE(report_warnings(touching)[0].find("topology differs"), std::string::npos);
    }
    touching.output.euler_characteristic = 3;
    touching.output.extra_vertex_fans = 1; // the pinch kept: the same topology
    EXPECT_TRUE(report_warnings(touching).empty());
}

// The frame's case: the output has two small closed components facing inward beside the part.
// Kept, they are warned of twice (more components, inward ones); removed, the removal is.
TEST(Report, WarnsOfComponentsAndInwardOnesTheSourceDoesNotHave) {
    RemeshReport r;
    r.input.euler_characteristic = r.output.euler_characteristic = 2;
    r.input.components = r.input.closed_components = 1;
    r.output.components = r.output.closed_components = 3;
    r.output.inward_components = 2;
    r.output.euler_characteristic = 6;
    r.warnings = report_warnings(r);
    ASSERT_EQ(r.warnings.size(), 3u);
    EXPECT_NE(r.warnings[0].find("topology differs"), std::string::npos) << r.warnings[0];
    EXPECT_NE(r.warnings[1].find("3 components, the source 1"), std::string::npos) << r.warnings[1];
    EXPECT_NE(r.warnings[2].find("2 closed components facing inward (negative volume), the source 0"), std::string::npos)
        << r.warnings[2];

    r.output = r.input;
    r.stray_components_removed = r.stray_inward_removed = 2;
    r.warnings = report_warnings(r);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("2 small closed pieces standing for no part of the source (2 facing inward) removed"),
              std::string::npos)
        << r.warnings[0];
    EXPECT_NE(to_json(r).find("\"stray_components_removed\": 2,"), std::string::npos);

    // A hollowed solid: its cavity comes out facing inward, as the source's does.
    RemeshReport hollow;
    hollow.input.components = hollow.output.components = 2;
    hollow.input.inward_components = hollow.output.inward_components = 1;
    EXPECT_TRUE(report_warnings(hollow).empty());
}

TEST(Report, ComponentListIsJson) {
    RemeshReport r;
    MeshComponent solid;
    solid.triangles = 12;
    solid.area = 6.0;
    solid.closed = true;
    solid.signed_volume = -1.0;
    solid.cavity = true;
    MeshComponent patch;
    patch.triangles = 2;
    patch.area = 1.0;
    r.output.component_list = {solid, patch};
    const std::string json = to_json(r);
    EXPECT_NE(json.find("\"component_list\": [{\"triangles\": 12, \"area\": 6, \"closed\": true, \"signed_volume\": -1, "
                        "\"cavity\": true}, {\"triangles\": 2, \"area\": 1, \"closed\": false, \"signed_volume\": null, "
                        "\"cavity\": false}]"),
              std::string::npos)
        << json;
}
