// Axis-aligned bounding-box tree over the triangles of a 3D mesh: closest-point queries, used
// for distances (quality) and for projecting points back onto the input.
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <functional>
#include <memory>
#include <vector>

namespace liftremesh {

struct ClosestPoint {
    Eigen::Vector3d point;   //!< closest point on the mesh
    double squared_distance; //!< squared distance from the query
    int32_t triangle;        //!< index of the triangle it lies on
};

class AabbTree {
public:
    //! Builds the tree over mesh.triangles (the mesh is copied; the tree owns what it needs).
    //! Median split on the longest axis of the triangle centroids, at most 4 triangles a leaf.
    //! From 4096 triangles on, built on OpenMP's default number of threads; the tree is the
    //! same on any number.
    //! Throws InvalidInput if a triangle index is out of range. A mesh without triangles is
    //! allowed: every query then returns triangle -1 at infinite distance.
    explicit AabbTree(const Mesh& mesh);
    ~AabbTree();
    AabbTree(AabbTree&&) noexcept;
    AabbTree& operator=(AabbTree&&) noexcept;

    //! Closest point of the mesh to q (exact, via closest_point_on_triangle). Thread-safe (const).
    //! Where several triangles are equally near, which one is reported is unspecified.
    ClosestPoint closest(const Eigen::Vector3d& q) const;

    //! The same, warm-started by `on_mesh`, any point known to lie on the mesh (such as the
    //! answer for a nearby query): its distance bounds the search and prunes most of the tree.
    //! If no triangle is strictly nearer, the answer is `on_mesh` itself with triangle -1.
    ClosestPoint closest(const Eigen::Vector3d& q, const Eigen::Vector3d& on_mesh) const;

    //! A triangle strictly nearer to q than r, or -1 if there is none: a search bounded by r
    //! that stops at the first such triangle, far cheaper than closest() when r is small.
    int32_t any_within(const Eigen::Vector3d& q, double r) const;

    //! Triangles that face against one of `directions`: their unit normal n has
    //! n.dot(m) < max_dot for at least one m of them (with max_dot < 0, turned more than
    //! acos(max_dot) from it). The tree bounds the normals under each node, so a query
    //! restricted so skips whole subtrees that face elsewhere.
    struct FacingAgainst {
        const std::vector<Eigen::Vector3d>& directions;
        double max_dot;
    };

    //! The closest point within r of q on a triangle that faces as `facing` asks and for which
    //! `accept` (given the triangle's index and its point closest to q) is true; triangle -1 at
    //! squared distance r^2 if there is none. `accept` is asked only about triangles that face
    //! so and are nearer than the best found so far. Thread-safe if `accept` is.
    ClosestPoint closest_where(const Eigen::Vector3d& q, double r, const FacingAgainst& facing,
                               const std::function<bool(int32_t, const Eigen::Vector3d&)>& accept) const;

    //! Appends to `out` the triangles strictly nearer to q than r (exact distances), in the order
    //! the tree holds them. Thread-safe (const).
    void triangles_within(const Eigen::Vector3d& q, double r, std::vector<int32_t>& out) const;

    //! Triangles whose unit normal n has n.dot(direction) >= min_dot: those a ball's `facing`
    //! sum counts (BallNormalSums).
    struct FacingWith {
        Eigen::Vector3d direction;
        double min_dot;
    };

    //! Sums over the triangles t strictly nearer to q than r of w_t n_t: n_t the unit normal,
    //! w_t the area of t inside the ball of radius r about q. `facing` sums those that face as
    //! `facing` asks, `against` the others.
    struct BallNormalSums {
        Eigen::Vector3d facing, against;
    };

    //! What the ball sums add up, in the tree's order: per triangle its unit normal and its area
    //! times it, per node the latter's sum over its triangles. About 80 bytes a triangle, so
    //! made by the caller for a run of queries and dropped after it.
    struct NormalSums {
        std::vector<Eigen::Vector3d> normals, weighted, nodes;
    };
    NormalSums normal_sums() const;

    //! Both sums, from `normal_sums` (this tree's). A triangle wholly inside the ball weighs its
    //! whole area, and a subtree wholly inside whose normals all fall on one side adds its node's
    //! sum: only the triangles crossing the sphere are clipped to it
    //! (triangle_ball_intersection_area). The terms are added in the tree's order, the same on
    //! any number of threads. Thread-safe (const).
    BallNormalSums area_weighted_normals_in_ball(const NormalSums& normal_sums, const Eigen::Vector3d& q, double r,
                                                 const FacingWith& facing) const;

    //! Appends to `out` the triangles whose bounding boxes meet the closed box [lo, hi], in the
    //! order the tree holds them. Thread-safe (const).
    void triangles_meeting_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int32_t>& out) const;

    //! Calls visit(s, t) once for each pair of triangles s != t (the mesh's indices, in either
    //! order) whose bounding boxes meet, until it returns false: the tree against itself, node
    //! pairs whose boxes are apart skipped whole. Single-threaded.
    void overlapping_pairs(const std::function<bool(int32_t, int32_t)>& visit) const;

    //! Unit normal of the mesh's triangle `triangle` (as ClosestPoint::triangle numbers it),
    //! in its orientation; zero for a degenerate triangle.
    Eigen::Vector3d triangle_normal(int32_t triangle) const;

private:
    //! best: initial bound; first_hit: return as soon as a triangle beats it; facing, accept:
    //! if not null, only the triangles that face so and that `accept` accepts (asked with their
    //! closest point) count.
    ClosestPoint search(const Eigen::Vector3d& q, ClosestPoint best, bool first_hit = false,
                        const FacingAgainst* facing = nullptr,
                        const std::function<bool(int32_t, const Eigen::Vector3d&)>* accept = nullptr) const;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace liftremesh
