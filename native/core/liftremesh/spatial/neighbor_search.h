// Nearest-neighbour search in R^d (d = 3 or 6) with a kd-tree (nanoflann). The only file pair
// that includes nanoflann, through nanoflann_compat.h (Debian 12's 1.4.3 and Debian 13's 1.7.1).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

namespace liftremesh {

class KdTree {
public:
    //! Builds a tree over the rows of `points` (#P by d, row-major, d = 3 or 6), copied.
    explicit KdTree(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>& points);
    ~KdTree();
    KdTree(KdTree&&) noexcept;
    KdTree& operator=(KdTree&&) noexcept;

    int dimension() const;
    long size() const;

    //! The k nearest points to `query` (d values), closest first. Returns how many were found
    //! (less than k only if the tree has fewer points). Thread-safe.
    int knn(const double* query, int k, int32_t* indices, double* squared_distances) const;

    //! The same, warm-started by `hint`: `hint_count` indices of points believed near `query`
    //! (such as its neighbours a moment ago). If there are at least k, the farthest of them
    //! bounds the search from the start, so far fewer tree nodes are visited; the answer is the
    //! same (ties aside). A hint that names fewer than k distinct points costs a second search.
    int knn(const double* query, int k, int32_t* indices, double* squared_distances, const int32_t* hint,
            int hint_count) const;

    //! Index of the nearest point to `query`. Thread-safe.
    int32_t nearest(const double* query) const;

    //! All points within distance `radius` of `query` (unordered), appended to `out`. Thread-safe.
    void within(const double* query, double radius, std::vector<int32_t>& out) const;

    //! All points whose squared distance to `query` is at most `squared_radius`, closest first
    //! (equal distances by index), into `indices` and `squared_distances` (replaced). Returns
    //! how many. The distances are those knn() reports. Thread-safe.
    int within_sorted(const double* query, double squared_radius, std::vector<int32_t>& indices,
                      std::vector<double>& squared_distances) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace liftremesh
