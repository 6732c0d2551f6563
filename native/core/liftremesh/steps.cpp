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
    // twice the cost); at most 1% of the vertices asked for are inserted, and as many again for
    // the creases' junctions and for their bends (pipeline.cpp).
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
    // Beside a knife edge (an interior angle under 60 degrees) and at its junctions with other
    // creases the faces' acute angles leave poorer triangles, and an edge or a corner cut off
    // is the larger defect: there the project's floor holds (issue 35 asks kappa >= 0.3, every
    // crease within 0.1 h of an edge and every corner of a vertex), for the moves onto the edge
    // and for the junctions inserted after the snap (pipeline.cpp).
    s.crease_snap.knife_kappa_floor = kKappaFloor;
    s.crease_snap.knife_turn_deg = 120.0;
    // Every crease over the feature angle (issue 35): its row of vertices within 0.1 h of it,
    // so a vertex whose triangles cut it 0.02 h deep or more moves onto it, from up to h / 2
    // away (the rows of the faces next to a crease that is no sharper than 30 degrees lie nearer
    // than on a knife edge). A crease shorter than 2 h in all is no feature the output can
    // follow (a scan's noise, a facet's slip). The moves and their flips keep the surface within
    // 0.1 h of the input, not the repair's 0.15 h, and kappa >= 0.45 as the repair does (0.3 by
    // a knife edge): the creases are followed without the Hausdorff distance or kappa min of the
    // CAD meshes falling back.
    s.feature_snap = s.crease_snap;
    s.feature_snap.min_depth = 0.02 * spacing * scale;
    s.feature_snap.radius = 0.5 * spacing * scale;
    s.feature_snap.min_length = 2.0 * spacing * scale;
    s.feature_snap.tolerance = 0.1 * spacing * scale;
    // Issue 35 counts a crease kept where an output edge turning by 15 degrees runs within 0.1 h
    // of it. The rim of a hole an edge length or two across, tessellated by chords turning by
    // 20-40 degrees a vertex, is cut across by the output's chords up to 0.2 h inside its bends:
    // a bend that no such edge passes within 0.07 h of gets a vertex of its own.
    s.feature_snap.bend_turn_deg = 10.0;
    s.feature_snap.bend_distance = 0.07 * spacing * scale;
    // Where two creases converge, the one the output's row of vertices misses runs up to 0.33 h
    // from it (the thread's run-outs): points of it a quarter of an edge apart, a vertex each,
    // where the other runs within half an edge (twice that) across.
    s.feature_snap.gap_separation = 0.25 * spacing * scale;

    // The output's crease vertices are the snap's, on the chords, or within its 0.02 h depth of
    // them: those within 0.05 h move towards the curves by at most 0.05 h, so the output stays
    // that near the input's polygon (the report's Hausdorff distance is to the input) and lies
    // within 0.1 h of a curve up to 0.15 h outside its chords (a 0.1 mm deflection is 0.13 h on
    // the thread's helices at 0.36 mm edges).
    s.crease_curves.min_length = s.feature_snap.min_length;
    s.crease_curves.near = 0.05 * spacing * scale;
    s.crease_curves.max_move = 0.05 * spacing * scale;
    s.crease_curves.kappa_floor = s.hausdorff_refinement.kappa_floor;

    s.quality_polish.tolerance = tolerance;
    s.untangle.tolerance = tolerance;
    return s;
}

} // namespace liftremesh
