// The worst triangles raised by local edits that keep the surface on the input: the last step of
// the repair. The restricted Delaunay triangulation of the optimised sites is Delaunay in the
// lifted space, not in the output's planes, and a finite optimisation leaves a few sites short
// of centroidal: some flat quads come out split along their longer diagonal and some flat
// triangles obtuse. As Gmsh, MMG and CGAL do after their own steps:
// - folds: an edge whose two triangles turn by more than 90 degrees and reach farther from the
//   input than the tolerance (a triangle across the end of a wall thinner than the edge length,
//   folded onto its neighbour) is flipped when both new triangles lie on it
//   (fold_flip_fits_input, flip_rules.h); a crease of the input, followed, is near it and left
//   alone. A pair folded shut (by more than 170 degrees), one of its triangles off the input's
//   faces, is flipped however near the input and whatever the new triangles' shape: the mending
//   of the triangles under kappa 0.3 comes after (edge_collapse.h);
// - caps, first: a triangle with an angle of 150 degrees or more, its apex near the opposite edge
//   (three vertices along a crease joined across it), has that edge flipped when both new
//   triangles lie on the input (as for folds), are better than the worse old one, and neither
//   turns by more than 120 degrees from the cap's neighbour it then borders. The crease then runs
//   through the apex. A cap turned over onto the triangle across its edge, its apex beyond that
//   edge (a crease bending towards a face a step lower, with no row of its own), may leave the
//   new triangles twice as far from the input: they cross the step, as it did, without folding.
//   The cap's normal, near zero, is not weighed, as the flips below would. A cap on the rim of a
//   plate thinner than the edge length stands for that rim and is kept: flipped, the plate would
//   fold onto itself;
// - flips: an edge is flipped when its quad is nearly planar and the worse kappa (Eq. 26) of its
//   two triangles goes up (EditableMesh::flip_improves_quality: never across a sharp edge, whose
//   triangles turn by more than 30 degrees), and the new diagonal's midpoint is no farther from
//   the input than the old one's, or within half the tolerance;
// - chords: an edge across a curved part of the input (a hole's wall, a fillet) whose midpoint
//   lies farther than half the tolerance from it is flipped when the other diagonal, along the
//   surface, lies at most half as far, both new triangles lie on the input and neither is below
//   kKappaFloorChord (chord_flip_fits_input, flip_rules.h). A chord's sagitta is what a curved
//   FEM element bends back onto the part, and what the Hausdorff distance measures there;
// - relaxation: a vertex of a triangle below `relax_below`, inside the surface (no boundary
//   edge) and on a flat fan (its triangles within `flat_angle_deg` of their mean normal: not on
//   a crease), moves to whichever of a few targets on the input raises the worst kappa of its
//   fan most, if any does and no triangle of the fan turns by more than 30 degrees. So does a
//   vertex of a triangle turned over onto the fan (within `flat_angle_deg` of the opposite of
//   the mean normal: it overlaps its neighbours, however well shaped, and the repair counts its
//   edges folded shut), but its move must turn that triangle back within 30 degrees of the
//   mean normal; the targets
//   are the centroid of its neighbours moved within the fan's plane, and points a quarter, half
//   and three quarters of the way to the apex of the equilateral triangle on the far edge of
//   each of its bad triangles, each then put on the input (closest point);
// - flips again, around the vertices moved.
// No vertex is added or removed and the topology and orientation are kept.
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/reference.h"

#include <cstdint>
#include <vector>

namespace liftremesh {

struct QualityPolishParams {
    //! Distance from the input that a flip may give a new diagonal (half of it; the pipeline's:
    //! kInputTolerance, steps.h). Positive and finite.
    double tolerance = 0.0;
    //! Passes of flips (the first over every edge, each next one around the last one's flips).
    int flip_passes = 8;
    //! Passes of relaxation over the vertices of the triangles below relax_below.
    int relax_passes = 3;
    double relax_below = 0.6;
    //! A fan whose triangles turn from their mean normal by more than this is not moved (a
    //! crease, or a strongly curved part). Degrees.
    double flat_angle_deg = 8.0;
};

struct QualityPolishStats {
    long flipped = 0;  //!< edge flips, folds undone included
    long unfolded = 0; //!< of those, the flips that undid a fold
    long moved = 0;    //!< vertex moves
};

//! Flips, relaxes and flips again (see above). Throws InvalidInput if the tolerance is not
//! positive and finite, a pass count is negative, or an index is out of range.
QualityPolishStats polish_quality(Mesh& mesh, const Reference& input, const QualityPolishParams& params);

//! The flips of polish_quality (folds, chords, quality), as after its relaxation: over the edges
//! of the triangles around `vertices`, then around those the last pass changed. For vertices an
//! edit after the polish added (the mending's splits, edge_collapse.h), whose triangles no flip
//! has weighed: a split of a quad's edge can leave a triangle that the flip of its next edge
//! would lift. Returns the flips; throws as polish_quality does.
long flip_around(Mesh& mesh, const Reference& input, const QualityPolishParams& params,
                 const std::vector<int32_t>& vertices);

} // namespace liftremesh
