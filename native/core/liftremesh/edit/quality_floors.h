// The quality floors of the local edits (kappa, Eq. 26): no edit makes a triangle below its
// floor unless the triangles it replaces were worse already. Each floor weighs what the edit
// buys against the sliver it may leave.
#pragma once

namespace liftremesh {

//! Undoing a crossing (repair/untangle.h), as a last resort after the edits that keep
//! kKappaFloor: two triangles passing through each other are what a tetrahedral mesher refuses,
//! so a poor triangle is the smaller defect.
inline constexpr double kKappaFloorUntangle = 0.2;

//! Undoing a fold, a folded pair or a boundary cut short (polish/, edit/edge_collapse.h,
//! snap/boundary_snap.h): the project's bound on the smallest kappa.
inline constexpr double kKappaFloor = 0.3;

//! Inserting or moving a vertex onto the input (polish/hausdorff_refinement.h,
//! snap/crease_snap.h): the surface there is near the input already, so only triangles as good
//! as those the optimisation leaves are worth the move.
inline constexpr double kKappaFloorOnInput = 0.45;
//! Inserting a vertex at a bend of a crease that the output's crease passes as a chord
//! (snap/crease_snap.h, pipeline.cpp): the crease is there already, cut short by a fraction of an
//! edge, so the vertex is worth less than one the output lacks.
inline constexpr double kKappaFloorBend = 0.5;
//! Flipping a chord across a curved surface for the diagonal along it (polish/quality_polish.h):
//! the chord is within the tolerance already, so the flip buys distance the output has to spare
//! and may only leave triangles of the shape the optimisation gives most of them.
inline constexpr double kKappaFloorChord = 0.55;

} // namespace liftremesh
