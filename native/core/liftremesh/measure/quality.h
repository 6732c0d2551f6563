// Quality metrics of a triangle mesh: aspect ratio kappa (Eq. 26), angles, topology counts,
// sharp-edge length, and the two-sided Hausdorff distance between two meshes.
#pragma once

#include "liftremesh/mesh/components.h"
#include "liftremesh/mesh/mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace liftremesh {

struct MeshQuality {
    long vertices = 0;                     //!< referenced vertices
    long triangles = 0;
    double kappa_min = 0.0;                //!< Eq. 26 over all triangles
    double kappa_mean = 0.0;
    std::array<long, 10> kappa_histogram{}; //!< counts in [0, 0.1), [0.1, 0.2), ..., [0.9, 1.0]
    double min_angle_deg = 0.0;            //!< smallest interior angle of any triangle
    double edge_length_min = 0.0;          //!< the shortest edge (mesh units)
    double edge_length_max = 0.0;          //!< the longest edge
    long boundary_edges = 0;               //!< edges used by exactly one triangle
    //! Connected components of the boundary edges: the holes and open borders (a border that
    //! passes a vertex twice counts once).
    long boundary_loops = 0;
    long nonmanifold_edges = 0;            //!< edges used by three or more triangles
    long nonmanifold_vertices = 0;         //!< vertices whose triangle fan is not one disk/half-disk
    //! The fans beyond the first, summed over the non-manifold vertices (two cones touching at
    //! their apex: 1): how many more vertices a manifold copy of the mesh has, a vertex per fan,
    //! and so how much higher its Euler characteristic is.
    long extra_vertex_fans = 0;
    //! Every manifold edge is used once in each direction: neighbours agree, which says nothing
    //! of whether a closed component faces outward (inward_components does).
    bool oriented = true;
    //! Connected components (joined through edges: components.h), the closed ones among
    //! them, the closed ones facing inward (negative signed volume), and of those the cavities
    //! (inside another closed component, as a hollowed solid's inner wall).
    long components = 0;
    long closed_components = 0;
    long inward_components = 0;
    long cavities = 0;
    //! The kListedComponents largest components by area, largest first, each with its triangle
    //! count, area, closedness, signed volume and cavity flag.
    std::vector<MeshComponent> component_list;
    int euler_characteristic = 0;          //!< V - E + F
    double sharp_edge_length = 0.0;        //!< total length of the edges SharpEdgeCriterion counts
    //! Manifold edges whose two triangles turn by more than kFoldedTurnDeg, and their total
    //! length: a knife edge of under 10 degrees, or two triangles folded onto each other (a flap
    //! laid back flat, a patch facing against its neighbours). Folded, they overlap, which a
    //! tetrahedral mesher refuses, though neighbours agree and no side passes through the other.
    long folded_edges = 0;
    double folded_edge_length = 0.0;
    //! Pairs of triangles passing through each other or touching (count_self_intersections,
    //! which needs an AABB tree: measure_quality leaves 0 here, the pipeline counts them for
    //! input and output).
    long self_intersections = 0;
};

//! The turn of an edge's two triangles, in degrees, past which MeshQuality counts it folded.
constexpr double kFoldedTurnDeg = 170.0;

//! How many components MeshQuality::component_list lists at most.
constexpr int kListedComponents = 20;

//! Which edges MeshQuality::sharp_edge_length counts.
struct SharpEdgeCriterion {
    //! The angle between the two face normals above which an edge counts as sharp, in degrees
    //! (60 in the project's acceptance criteria).
    double angle_deg = 60.0;
    //! An edge of a triangle narrower than this (its smallest altitude, in the mesh's units)
    //! does not count: a crease of a tessellation's sliver (a ring of them joining two facetings
    //! of one cylinder) stands for no feature a mesh of well-shaped triangles of the target size
    //! can have. 0 counts every edge.
    double min_width = 0.0;
};

//! Measures `mesh`, its sharp edges as `sharp` says.
//! Details: a non-manifold vertex is one whose incident triangles form two or more groups not
//! connected through edges at the vertex (a non-manifold edge alone does not make its vertices
//! non-manifold). The sharp-edge angle does not depend on orientation: where the two triangles
//! of an edge disagree in orientation one normal is flipped first. Empty meshes give zeros.
//! Throws InvalidInput if a triangle index is out of range.
MeshQuality measure_quality(const Mesh& mesh, const SharpEdgeCriterion& sharp = {});

class AabbTree;

//! Default sample count per side and seed of hausdorff_distance (100k, as in PEERS.md).
constexpr int kDistanceSamples = 100000;
constexpr std::uint64_t kDistanceSeed = 7;

struct DistanceStats {
    double hausdorff = 0.0; //!< max of the two one-sided maxima (absolute units)
    double a_to_b = 0.0;    //!< max over samples of a of the distance to b
    double b_to_a = 0.0;    //!< max over samples of b of the distance to a
    double mean = 0.0;      //!< mean of all sampled distances, both directions
};

//! Two-sided Hausdorff distance, exact point-to-triangle distances from `samples` points on
//! each mesh (all its vertices first, then area-uniform random points stratified by triangle,
//! fixed `seed`).
//! Every referenced vertex is used even when there are more than `samples`. The queries run in
//! parallel with OpenMP (default thread count; set it with omp_set_num_threads); the result
//! does not depend on the thread count. Throws InvalidInput (via check_mesh) for an empty mesh,
//! a non-finite coordinate or an index out of range.
DistanceStats hausdorff_distance(const Mesh& a, const Mesh& b, int samples = kDistanceSamples,
                                 std::uint64_t seed = kDistanceSeed);
//! The same, with the AABB tree of `a` that the caller has built already (made from `a`).
DistanceStats hausdorff_distance(const Mesh& a, const AabbTree& a_tree, const Mesh& b, int samples = kDistanceSamples,
                                 std::uint64_t seed = kDistanceSeed);
//! The same, with the AABB trees of both (made from `a` and from `b`).
DistanceStats hausdorff_distance(const Mesh& a, const AabbTree& a_tree, const Mesh& b, const AabbTree& b_tree,
                                 int samples = kDistanceSamples, std::uint64_t seed = kDistanceSeed);

} // namespace liftremesh
