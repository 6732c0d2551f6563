#include "liftremesh/steps.h"

namespace liftremesh {

StepSettings step_settings(double spacing, double scale, long sites) {
    StepSettings s;
    // Section 5.2.2: an output hole mostly within 1.5 h of the input's boundary is that boundary.
    s.hole_reach = 1.5 * spacing;
    // Vertices inside the patches that fill holes, which the paper leaves empty: at most a
    // tenth of those asked for.
    s.patch_refinement.spacing = spacing;
    s.patch_refinement.max_added = sites / 10;
    // Interior edges under 0.35 times the median: the crowded sites at crease junctions.
    s.short_edges.ratio = 0.35;

    // The tolerance of every step that keeps the surface on the input (kInputTolerance).
    const double tolerance = kInputTolerance * spacing * scale;

    // Points of a chamfer are at most about h / 2 deep: farther ones are a part the output lost.
    // Samples h / 2 apart put two or more along a chamfer (h / 4 finds the same chamfers at
    // twice the cost); at most 1% of the vertices asked for are inserted.
    s.hausdorff_refinement.tolerance = tolerance;
    s.hausdorff_refinement.sample_spacing = 0.5 * spacing * scale;
    s.hausdorff_refinement.max_distance = spacing * scale;
    s.hausdorff_refinement.max_inserted = sites / 100;

    // The sites Eq. 10 leaves off a 30-degree edge lie 0.1-0.2 h from it, those of the faces'
    // first rows 0.5 h and more: 0.35 h takes the first and leaves the second. A corner of the
    // creases takes the vertex nearest to it within h.
    s.crease_snap.radius = 0.35 * spacing * scale;
    s.crease_snap.corner_radius = spacing * scale;
    s.crease_snap.tolerance = tolerance;
    s.crease_snap.kappa_floor = s.hausdorff_refinement.kappa_floor;

    s.quality_polish.tolerance = tolerance;
    s.untangle.tolerance = tolerance;
    return s;
}

} // namespace liftremesh
