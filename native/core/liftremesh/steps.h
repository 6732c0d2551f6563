// The settings of the steps after the restricted Delaunay triangulation, all derived from one
// length: the spacing h, the edge length of an equilateral mesh with the vertices asked for
// (pipeline.cpp). One function makes them, so that a step's distances and floors are chosen in
// one place.
#pragma once

#include "liftremesh/edit/edge_collapse.h"
#include "liftremesh/polish/hausdorff_refinement.h"
#include "liftremesh/polish/quality_polish.h"
#include "liftremesh/repair/patch_refinement.h"
#include "liftremesh/repair/untangle.h"
#include "liftremesh/snap/boundary_snap.h"
#include "liftremesh/snap/crease_curves.h"
#include "liftremesh/snap/crease_snap.h"

namespace liftremesh {

//! How far from the input, in units of h, the steps may take the surface where it was nearer,
//! and how far the output may lie from an input point before it is inserted: a chamfer that
//! cuts off a sharp edge lies about 0.3 h deep, while the chord of a fillet of radius r is
//! h^2 / (8 r), below 0.15 h for r > 0.83 h, so that fillets keep their chords.
inline constexpr double kInputTolerance = 0.15;

//! Every step's settings for one run of the repair.
struct StepSettings {
    // In the unit ball (Section 5.1), where the repair runs until the surface goes back to the
    // input's coordinates:
    //! An output hole along the input's boundary within this is the input's: the pipeline's
    //! HoleFillingParams::should_fill, which needs the surface and the input, is made from it.
    double hole_reach = 0.0;
    PatchRefinementParams patch_refinement; //!< but `first`, which the caller sets
    ShortEdgeParams short_edges;            //!< collapse_short_edges' ratio
    // In the input's coordinates:
    BoundarySnapParams boundary_snap;
    HausdorffRefinementParams hausdorff_refinement;
    CreaseSnapParams crease_snap;
    //! The crease snap onto every crease over the feature angle (its min_turn_deg set from
    //! RemeshParams::feature_angle): a vertex moves wherever the crease is cut at all.
    CreaseSnapParams feature_snap;
    //! The vertices on the creases over the feature angle onto the curves their chords stand for
    //! (its min_turn_deg set as the feature snap's).
    CreaseCurveParams crease_curves;
    QualityPolishParams quality_polish;
    FoldedPairParams folded_pairs;
    UntangleParams untangle;
};

//! The settings for the spacing h = `spacing` in the unit ball, `scale` the input's units per
//! unit of the unit ball (UnitBallTransform::scale: h is spacing * scale in the input's units)
//! and `sites` the vertices asked for.
//! \pre spacing > 0 and scale > 0, finite; sites >= 0.
StepSettings step_settings(double spacing, double scale, long sites);

} // namespace liftremesh
