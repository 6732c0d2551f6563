// The tests that decide whether an edge flip may be made on a surface that must stay on the
// input: the rules the repair's steps (crease snap, Hausdorff refinement, quality polish,
// untangling) share, each weighing a quad of EditableMesh against the input's tree. A flip
// changes which diagonal splits the quad; the rules ask that the new triangles be no worse
// (kappa, Eq. 26), not turned over, and no farther from the input than the old ones, measured
// at the diagonals' midpoints or at seven points of each triangle.
#pragma once

#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/editable_mesh.h"
#include "liftremesh/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

namespace liftremesh {

//! The cosine of a cap's angle at its apex: a cap has an angle of 150 degrees or more.
inline const double kCosCap = -std::sqrt(3.0) / 2.0;

//! Distances from the input of the midpoints of the quad's edge a-b (`before`) and of its other
//! diagonal c-d (`after`): what the rules below weigh.
struct DiagonalDistances {
    double before, after;
};
DiagonalDistances diagonal_distances(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input);

//! Whether flipping the quad's edge is a quality flip that keeps the surface on the input
//! (quality_polish.h: the flips); `input` is the input's tree, `tolerance` > 0.
bool quality_flip_keeps_surface(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                                double tolerance);
//! The same rule for a caller that measured the distances from the input of the midpoints of
//! the quad's edge (`before`) and of the other diagonal (`after`) already.
bool quality_flip_keeps_surface(const EditableMesh& mesh, const EditableMesh::Quad& quad, double before, double after,
                                double tolerance);

//! Whether flipping the quad's edge undoes a fold (quality_polish.h: the flips): its two triangles turn
//! by more than 90 degrees and one of them is farther than `tolerance` from the input, both new
//! ones lie on the input, their worse kappa at least the old pair's or kKappaFloor. A pair folded
//! shut (kCosFolded) one of whose triangles does not lie on the input is flipped however near
//! it lies and whatever the new kappa: the two lie on each other. A triangle's
//! distance is the largest of seven of its points (centroid, edge midpoints, halfway from the
//! centroid to each corner); it lies on the input when that is within `tolerance` and its
//! normal within 30 degrees of the input's triangle nearest to its centroid.
bool fold_flip_fits_input(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                          double tolerance);

//! Whether flipping the quad's edge removes a cap (the rule above, but for the turn from the
//! cap's other neighbours, which the quad does not see): one of its two triangles, not both, has
//! an angle of 150 degrees or more opposite the edge; both new ones lie on the input (as for a
//! fold; within twice the tolerance when the cap is turned over onto the other triangle, by
//! more than 90 degrees) and their worse kappa is above the old pair's.
bool cap_flip_fits_input(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                         double tolerance);

//! Largest distance from the input of seven points of the triangle: its centroid, its edges'
//! midpoints and the points halfway from the centroid to its corners.
double triangle_distance_from_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input);

//! triangle_distance_from_input, with the input's triangle nearest to the triangle's centroid
//! (-1 if the input has none), whose query the distance shares.
struct TriangleNearInput {
    double distance;
    int32_t nearest_to_centroid;
};
TriangleNearInput triangle_near_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input);

//! Whether triangle t lies turned over on the input: its normal turned by more than 150 degrees
//! (kCosCap) from that of the input's triangle nearest to its centroid. A vertex inserted a
//! little off the plane of the triangle it splits, beside an edge (a crease point over the rim of
//! a step lower than the edge is long), stands the triangle on that edge up over the step's wall,
//! facing into the part: its parent's side alone does not show it. A triangle across a feature
//! smaller than itself leans against the facets it passes by less (a scan's antenna, the top rim
//! of such a step).
bool faces_against_input(const EditableMesh& mesh, const EditableMesh::Tri& t, const AabbTree& input);

//! The cosine of the turn past which two triangles on an edge are folded onto each other: 170
//! degrees, as the report counts folded edges (measure/quality.h).
inline const double kCosFolded = std::cos(170.0 * M_PI / 180.0);

//! Whether two triangles with normals u and v (of any length) on an edge are folded so.
inline bool folded(const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return u.dot(v) < kCosFolded * u.norm() * v.norm(); }

//! A vertex's triangles: [first, second) of its indices.
using TrianglesOf = std::function<std::pair<const int32_t*, const int32_t*>(int32_t)>;
//! The rows of `fans` (a point's triangles, as EditableMesh::fans() gives them) as TrianglesOf;
//! `fans` must outlive it.
inline TrianglesOf fans_of(const CompressedRows& fans) {
    return [&fans](int32_t v) { return std::make_pair(fans.begin(v), fans.end(v)); };
}

//! How many edges of the triangles `tris` (repeats allowed) are folded (kCosFolded), each
//! counted once; `triangles_of` gives each vertex's triangles as the mesh has them now.
int folded_edges_among(const EditableMesh& mesh, const std::vector<int>& tris, const TrianglesOf& triangles_of);

//! The same on any triangle mesh, possibly one an edit has not made yet: `corners(t)` gives
//! triangle t's three vertices, `normal(t)` its normal (of any length), and `triangles_of(v)`
//! the triangles round vertex v (any range of indices) as the mesh would have them.
template <class Tris, class Corners, class Normal, class TrianglesOfVertex>
int count_folded_edges(const Tris& tris, const Corners& corners, const Normal& normal,
                       const TrianglesOfVertex& triangles_of) {
    std::vector<std::pair<int32_t, int32_t>> seen;
    for (const auto t : tris) {
        const auto c = corners(t);
        const Eigen::Vector3d n = normal(t);
        for (int j = 0; j < 3; ++j) {
            const int32_t a = c[j], b = c[(j + 1) % 3];
            for (const auto s : triangles_of(a)) {
                if (s == t) continue;
                const auto x = corners(s);
                if (std::find(x.begin(), x.end(), b) == x.end()) continue;
                if (folded(n, normal(s))) seen.emplace_back(std::min(a, b), std::max(a, b));
            }
        }
    }
    std::sort(seen.begin(), seen.end());
    return static_cast<int>(std::unique(seen.begin(), seen.end()) - seen.begin());
}

//! Whether flipping the quad's edge folds one of the new triangles onto the triangle across
//! the quad's rim (their normals turned by more than 170 degrees, as the report counts folded
//! edges) where the old one on that rim edge was not folded so. `fans` gives the quad's corners'
//! triangles, possibly as they were before other flips of the same pass (fans_of(mesh.fans()),
//! EditableMesh::fans_near): a triangle flipped since keeps two of its corners, so the triangle
//! across a rim edge is looked for among both its end points' triangles. A flip beside a knife
//! edge can turn a triangle that leaned over the edge onto its other face.
bool flip_folds_rim(const EditableMesh& mesh, const EditableMesh::Quad& quad, const TrianglesOf& fans);

//! How many pairs of the triangles `tris` (each given once; made or not, on the mesh's points)
//! cross (self_intersection.h: triangles_cross).
long crossings_among(const EditableMesh& mesh, const std::vector<EditableMesh::Tri>& tris);
//! The same for the mesh's triangles numbered in `tris` (repeats allowed, each taken once), as
//! the mesh has them now.
long crossings_among(const EditableMesh& mesh, std::vector<int> tris);

//! Whether flipping the quad's edge makes its two triangles cross more of the triangles round
//! the quad's corners (self_intersection.h: triangles_cross) than the old two do. `fans` as in
//! flip_folds_rim; a triangle flipped since is taken as it is now. Beside a knife edge a flip
//! for distance can lay a triangle through its neighbours on the other face.
bool flip_crosses_fans(const EditableMesh& mesh, const EditableMesh::Quad& quad, const TrianglesOf& fans);

//! Whether flipping the quad's edge takes it off a crease it cuts across (the Hausdorff
//! refinement's distance rule): the midpoint of the edge is farther than `tolerance` from the
//! input (`before`) and that of the other diagonal at most half as far (`after`), neither new
//! triangle turns against the old pair's mean normal, and the worse kappa of the new pair is at
//! least that of the old pair or `kappa_floor`.
bool crease_flip_fits(const EditableMesh& mesh, const EditableMesh::Quad& quad, double before, double after,
                      double tolerance, double kappa_floor);

//! Whether flipping the quad's edge takes a chord across a curved part of the input onto the
//! diagonal along it (quality_polish.h: the chords): crease_flip_fits with half the tolerance
//! and kKappaFloorChord, and both new triangles lie on the input (within `tolerance`, each
//! normal within 30 degrees of the input's triangle nearest to its centroid), so that a flip
//! never folds a new triangle onto the input's other side of a crease.
bool chord_flip_fits_input(const EditableMesh& mesh, const EditableMesh::Quad& quad, double before, double after,
                           const AabbTree& input, double tolerance);

} // namespace liftremesh
