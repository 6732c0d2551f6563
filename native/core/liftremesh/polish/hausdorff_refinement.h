// Inserting the input's farthest points into the output: the repair of "edge crunching"
// (Section 6.2.2). The feature term can settle in a local minimum where two restricted cells
// meet along a sharp edge instead of a site sitting on it; the restricted Delaunay
// triangulation then joins the two sites across the edge and cuts it off by a chamfer about a
// third of an edge length deep. The paper proposes post-processing as future work and notes
// that tagging the features is unreliable on CAD tessellations; this finds the chamfers by
// distance alone, as a Hausdorff-bounded remesher (MMG's -hausd) would, with no tagging:
// - the input is sampled at its vertices and along its edges (a sharp edge or corner of a
//   triangulated surface lies on its edges); a sample farther than `tolerance` from the
//   output is a witness of a chamfer, and the farthest of them is the crease point;
// - each witness, farthest first, is inserted where it is nearest to the output: splitting
//   that triangle or one of its edges, whichever leaves the best triangles, and only if no
//   triangle made is worse than kappa_floor (Eq. 26), turned over from the one it comes from,
//   turned over on the input (flip_rules.h: faces_against_input), or folded onto the triangle
//   across its outer edge where the old one was not;
// - edges near the insertions are then flipped where the other diagonal of their quad lies
//   at most half as far from the input (the edge that cut across the crease), or where a
//   quality flip of a nearly planar quad raises the worse kappa without moving the surface away
//   from the input (quality_polish.h), unless it folds a triangle onto the one across the
//   quad's rim or lays one through a triangle round its corners (flip_rules.h);
// repeated for a few rounds. Smooth surfaces at the method's sampling mostly have chords within
// the tolerance; where a strongly curved part does not, the points inserted bring it closer too.
// The same splits and flips insert given points of the input (insert_input_points): the
// junctions of the creases that no vertex could move onto, and the bends the output's creases
// cut across.
#pragma once

#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/reference.h"

#include <limits>
#include <vector>

namespace liftremesh {

struct HausdorffRefinementParams {
    //! Input points farther than this from the output are inserted (the pipeline's:
    //! kInputTolerance, steps.h). Positive and finite.
    double tolerance = 0.0;
    //! Input points farther than this are not a chamfer's but a part the output lost (too
    //! coarse for thin parts, a broken input) and are left alone: inserting them only adds poor
    //! triangles. Positive.
    double max_distance = std::numeric_limits<double>::infinity();
    //! Most points inserted in all. Not negative.
    long max_inserted = std::numeric_limits<long>::max();
    //! Spacing of the samples along the input's edges. Positive and finite.
    double sample_spacing = 0.0;
    //! No insertion makes a triangle with a lower kappa, nor does a flip for distance unless
    //! the triangles it replaces were worse: an inserted point is on the input already, so it
    //! may not make the worst triangle worse than the optimisation leaves it.
    double kappa_floor = kKappaFloorOnInput;
    //! Rounds of sampling, insertion and flips (each inserts at most one point per triangle).
    int rounds = 4;
};

struct HausdorffRefinementStats {
    long inserted = 0; //!< points inserted (vertices added, appended to mesh.points)
    long flipped = 0;  //!< edges flipped
};

//! Inserts the points of `input` farther than params.tolerance (and not farther than
//! params.max_distance) from `mesh` (see above).
//! The mesh keeps its orientation, manifoldness and Euler characteristic (splits and flips
//! only; a flip never makes an edge the mesh has). Triangles that are not part of an
//! oriented manifold quad are split but never flipped. Throws InvalidInput if a parameter is
//! not positive (kappa_floor and max_inserted may be 0) or an index is out of range.
HausdorffRefinementStats refine_towards_input(Mesh& mesh, const Reference& input,
                                              const HausdorffRefinementParams& params);

//! Inserts each of `points` (points of the input: the creases' junctions and bends) that has no
//! vertex of `mesh` within `gap` and lies no farther than params.max_distance from it, where it
//! is nearest to the output, splitting as above. The split is followed by flips as above and,
//! while the worst triangle it made is under params.kappa_floor, by at most three insertions of
//! the input's point nearest to the middle of that triangle's longest edge (splitting the
//! triangle or one of its edges, as above), each with its flips: a point a quarter of an edge
//! from a vertex needs edges that short round it. The point stands if every triangle made is at
//! least the floor; otherwise the mesh is left as it was. The points are taken in passes,
//! farthest from a vertex first within each; one that an insertion came near (its triangles as
//! near as the point's closest, or within `gap`) waits for the next pass, against the mesh as
//! it is then. At most 64 points are tried in all (each try passes over the whole mesh), and
//! none once params.max_inserted vertices were added (a try may add up to four). `floors`, if
//! not empty, gives each point the floor its try keeps instead of params.kappa_floor (for the
//! flips too). The guarantees are refine_towards_input's; stats.inserted counts the vertices
//! added. Throws InvalidInput for a gap that is negative or not finite, a tolerance or largest
//! distance that is not positive, a negative floor or max_inserted, `floors` of another length
//! than `points`, or an index out of range.
HausdorffRefinementStats insert_input_points(Mesh& mesh, const Reference& input,
                                             const std::vector<Eigen::Vector3d>& points, double gap,
                                             const HausdorffRefinementParams& params,
                                             const std::vector<double>& floors = {});

} // namespace liftremesh
