// Vertices on a curved crease onto the curve its chords stand for. A CAD export tessellates a
// curved edge (a circle, a helix) by chords whose ends lie on the edge and whose middles lie up
// to the linear deflection inside it. The crease snap (crease_snap.h) and the held crease sites
// (cvt/crease_sites.h) put the output's vertices on those chords; where the output's edges are
// shorter than the chords, its vertices between two chord ends then lie off the CAD edge by as
// much as the chord does, and the output's crease runs along the input's polygon, not along the
// edge (issue 35 measures it against the B-rep: a thread's helices, 0.1 mm off at 0.36 mm edges).
//
// Along a chain of crease edges whose direction turns little at each vertex, and whose
// neighbouring chords are about as long as each other, as a tessellator's equal chords of one
// curve are, the curve through the chain's vertices is the cubic Hermite curve on each chord,
// with the tangent at each end that of the parabola through that end and its two neighbours
// (Bessel's tangent: a circle's own tangent when the two chords are equal). Where the chain has a
// corner, an end, or a chord much longer or shorter than the next (a straight edge meeting an arc),
// the tangent is taken on the chord's own side only, so that a straight crease stays straight up
// to its ends. Each output vertex within `near` of a crease chord moves to the curve's point at its
// own position along the chord, by at most `max_move` (the tolerance every step keeps to the input
// within), unless a triangle of its fan turns by more than 30 degrees, the fan's worst kappa
// (Eq. 26) falls below both the floor and what it was, more of its edges are folded shut
// (flip_rules.h: kCosFolded), or the fan crosses more triangles than it did
// (self_intersection.h): off the input, a vertex can meet another part of the surface that
// touches this one along the crease.
#pragma once

#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/mesh/mesh.h"

namespace liftremesh {

struct CreaseCurveParams {
    //! An input edge whose two triangles turn by more than this (degrees) is a crease: the
    //! pipeline's feature angle.
    double min_turn_deg = 30.0;
    //! Chains of crease edges shorter than this in all are left (creases.h). Not negative.
    double min_length = 0.0;
    //! Output vertices at most this far from a crease chord are moved onto its curve. Not
    //! negative; 0 moves none.
    double near = 0.0;
    //! No vertex moves farther than this. Not negative.
    double max_move = 0.0;
    //! A chain's vertex where its direction turns by less than this (degrees) lies inside a
    //! smooth curve: a tessellation of a curve at the usual angular deflection (0.5 rad) turns by
    //! at most about 29 degrees a vertex. In (0, 90).
    double smooth_turn_deg = 35.0;
    //! ... and where its two chords differ in length by at most this factor. At least 1.
    double max_chord_ratio = 1.5;
    //! See above.
    double kappa_floor = kKappaFloorOnInput;
};

struct CreaseCurveStats {
    long creases = 0; //!< input edges found to be creases
    long moved = 0;   //!< output vertices moved onto their curves
};

//! Moves vertices of `mesh` onto the curves of the creases of `input` (see above). Vertex moves
//! only: the mesh's connectivity is kept. Throws InvalidInput if a parameter is out of range.
CreaseCurveStats move_onto_crease_curves(Mesh& mesh, const Mesh& input, const CreaseCurveParams& params);

//! The same with the creases found already: `creases` must be AcuteCreases(input,
//! params.min_turn_deg, any spacing, params.min_length), as the crease snap's are (crease_snap.h).
CreaseCurveStats move_onto_crease_curves(Mesh& mesh, const Mesh& input, const AcuteCreases& creases,
                                         const CreaseCurveParams& params);

} // namespace liftremesh
