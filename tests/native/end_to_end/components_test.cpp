// Components and orientation end to end: remesh() on a hollowed solid keeps its cavity facing
// inward; a stray inside-out piece added to a remeshed output is removed by the pipeline's step
// (stray_components.h) and the report says so.
#include "liftremesh/measure/quality.h"
#include "liftremesh/mesh/components.h"
#include "liftremesh/pipeline.h"
#include "liftremesh/repair/stray_components.h"
#include "liftremesh/report.h"
#include "helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;
using liftremesh::test::params_with;

namespace {

bool mentions(const std::vector<std::string>& warnings, const std::string& text) {
    for (const std::string& w : warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

} // namespace

// A hollowed cube (the cavity a cube of half the side, its wall facing inward, as a solid's
// cavity does): both walls come out, the inner one still a cavity facing inward, each enclosing
// its input's volume to 2%; nothing is removed and nothing warned of components.
TEST(Components, AHollowedSolidKeepsItsCavityFacingInward) {
    const Mesh input = test::joined(test::make_cube(1.0, 8), test::turned(test::make_cube(0.5, 4)));
    const RemeshResult r = remesh(input, params_with(1500));
    const MeshQuality &in = r.report.input, &out = r.report.output;
    EXPECT_EQ(in.components, 2);
    EXPECT_EQ(in.inward_components, 1);
    EXPECT_EQ(in.cavities, 1);
    EXPECT_EQ(out.components, 2);
    EXPECT_EQ(out.closed_components, 2);
    EXPECT_EQ(out.inward_components, 1);
    EXPECT_EQ(out.cavities, 1);
    EXPECT_EQ(r.report.stray_components_removed, 0);
    ASSERT_EQ(out.component_list.size(), 2u);
    EXPECT_NEAR(out.component_list[0].signed_volume, 8.0, 0.02 * 8.0);
    EXPECT_NEAR(out.component_list[1].signed_volume, -1.0, 0.02 * 1.0);
    EXPECT_FALSE(mentions(r.report.warnings, "components"));
    EXPECT_FALSE(mentions(r.report.warnings, "removed"));
}

// The frame's case, built: a remeshed part with two small inside-out boxes added, one inside
// its material and one beside it (signed volumes -0.001 and -0.0034 beside the part's +8). As
// handed on, the report warns of them; the pipeline's step, with the limits it takes from the
// input, removes exactly them, and the report counts and warns of the removal.
TEST(Components, AStrayInsideOutPieceIsRemovedCountedAndWarned) {
    const Mesh input = test::make_cube(1.0, 8);
    const RemeshResult r = remesh(input, params_with(600));
    ASSERT_EQ(r.report.output.components, 1);
    Mesh with_strays = test::joined(test::joined(r.mesh, test::turned(test::make_box({0.2, 0.2, 0.2}, {0.3, 0.3, 0.3}, 1))),
                                    test::turned(test::make_box({1.5, 0, 0}, {1.65, 0.15, 0.15}, 1)));

    RemeshReport kept = r.report;
    kept.output = measure_quality(with_strays);
    EXPECT_TRUE(kept.output.oriented); // neighbours agree: the old report's only check
    EXPECT_EQ(kept.output.inward_components, 2);
    const std::vector<std::string> kept_warnings = report_warnings(kept);
    EXPECT_TRUE(mentions(kept_warnings, "3 components, the source 1"));
    EXPECT_TRUE(mentions(kept_warnings, "2 closed components facing inward"));

    const StrayComponentStats removed = remove_stray_components(
        with_strays, stray_component_params(mesh_components(input)));
    EXPECT_EQ(removed.removed, 2);
    EXPECT_EQ(removed.inward_removed, 2);
    Mesh expected = r.mesh; // its vertices in order of first use, as the step leaves them
    remove_unreferenced_vertices(expected);
    ASSERT_EQ(with_strays.points.rows(), expected.points.rows());
    ASSERT_EQ(with_strays.triangles.rows(), expected.triangles.rows());
    EXPECT_EQ(with_strays.points, expected.points);
    EXPECT_EQ(with_strays.triangles, expected.triangles);
    RemeshReport cleaned = r.report;
    cleaned.stray_components_removed = removed.removed;
    cleaned.stray_inward_removed = removed.inward_removed;
    cleaned.output = measure_quality(with_strays);
    EXPECT_EQ(cleaned.output.inward_components, 0);
    const std::vector<std::string> warnings = report_warnings(cleaned);
    EXPECT_TRUE(mentions(warnings, "2 small closed pieces standing for no part of the source (2 facing inward) removed"));
    EXPECT_FALSE(mentions(warnings, "facing inward (negative volume)"));
}
