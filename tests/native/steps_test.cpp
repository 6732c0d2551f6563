// The steps' settings (steps.h): one tolerance and the quality floors shared by every step, each
// distance a fixed multiple of the spacing, and settings every step accepts.
#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/steps.h"
#include "helpers.h"

#include <gtest/gtest.h>

using namespace liftremesh;

TEST(StepSettings, EveryStepSharesTheToleranceAndItsFloor) {
    const double spacing = 0.02, scale = 50.0; // h = 1 in the input's units
    const StepSettings s = step_settings(spacing, scale, 6000);
    const double tolerance = s.hausdorff_refinement.tolerance;
    EXPECT_NEAR(tolerance, kInputTolerance, 1e-15);
    EXPECT_EQ(s.crease_snap.tolerance, tolerance);
    EXPECT_EQ(s.quality_polish.tolerance, tolerance);
    EXPECT_EQ(s.untangle.tolerance, tolerance);
    EXPECT_EQ(s.hausdorff_refinement.kappa_floor, kKappaFloorOnInput);
    EXPECT_EQ(s.crease_snap.kappa_floor, kKappaFloorOnInput);
    EXPECT_EQ(s.folded_pairs.kappa_floor, kKappaFloor);
    EXPECT_EQ(s.boundary_snap.min_kappa, kKappaFloor);
    EXPECT_EQ(s.untangle.kappa_floor, kKappaFloorUntangle);
    // A crossing undone is worth more than a fold undone, which is worth more than a vertex
    // moved onto a surface it is near already.
    EXPECT_LT(kKappaFloorUntangle, kKappaFloor);
    EXPECT_LT(kKappaFloor, kKappaFloorOnInput);
}

TEST(StepSettings, DistancesScaleWithTheSpacingAndCountsWithTheSites) {
    const StepSettings a = step_settings(0.01, 10.0, 6000), b = step_settings(0.02, 10.0, 12000);
    EXPECT_NEAR(b.hausdorff_refinement.tolerance, 2 * a.hausdorff_refinement.tolerance, 1e-15);
    EXPECT_NEAR(b.hausdorff_refinement.max_distance, 2 * a.hausdorff_refinement.max_distance, 1e-15);
    EXPECT_NEAR(b.hausdorff_refinement.sample_spacing, 2 * a.hausdorff_refinement.sample_spacing, 1e-15);
    EXPECT_NEAR(b.crease_snap.radius, 2 * a.crease_snap.radius, 1e-15);
    EXPECT_NEAR(b.hole_reach, 2 * a.hole_reach, 1e-15);
    EXPECT_EQ(b.patch_refinement.spacing, 0.02);
    // The tolerance lies below the crease snap's radius, and that below a corner's reach.
    EXPECT_LT(a.crease_snap.tolerance, a.crease_snap.radius);
    EXPECT_LT(a.crease_snap.radius, a.crease_snap.corner_radius);
    EXPECT_EQ(a.patch_refinement.max_added, 600);
    EXPECT_EQ(a.hausdorff_refinement.max_inserted, 60);
    EXPECT_EQ(b.hausdorff_refinement.max_inserted, 120);
}

TEST(StepSettings, EveryStepAcceptsThem) {
    const Mesh square = test::make_square(1.0, 8);
    const test::OwnedReference input(square);
    const StepSettings s = step_settings(0.125, 1.0, 81);
    Mesh m = square;
    EXPECT_NO_THROW(snap_boundary(m, input, s.boundary_snap));
    EXPECT_NO_THROW(refine_towards_input(m, input, s.hausdorff_refinement));
    EXPECT_NO_THROW(snap_to_acute_creases(m, input, s.crease_snap));
    EXPECT_NO_THROW(polish_quality(m, input, s.quality_polish));
    EXPECT_NO_THROW(collapse_folded_pairs(m, input, s.folded_pairs));
    EXPECT_NO_THROW(untangle(m, input, s.untangle));
    EXPECT_EQ(m.triangles.rows(), square.triangles.rows()); // the input itself: nothing to insert or remove
}
