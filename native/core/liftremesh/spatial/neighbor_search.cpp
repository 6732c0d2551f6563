#include "liftremesh/spatial/neighbor_search.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/spatial/nanoflann_compat.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace liftremesh {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// nanoflann's dataset adaptor over a row-major matrix.
struct MatrixAdaptor {
    const RowMatrix* m;
    size_t kdtree_get_point_count() const { return static_cast<size_t>(m->rows()); }
    double kdtree_get_pt(size_t i, size_t d) const { return (*m)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(d)); }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
};

// The k nearest points strictly nearer than `bound`, closest first (equal distances in the order
// the tree meets them). Until k are held the bound prunes the search, so a bound from a hint
// cuts the nodes visited from the first step.
class NearestSet {
public:
    using DistanceType = double;
    using IndexType = int32_t;
    NearestSet(int k, int32_t* indices, double* squared_distances, double bound)
        : indices_(indices), dists_(squared_distances), capacity_(k) {
        dists_[capacity_ - 1] = bound; // the worst distance until the set holds k points
    }
    bool addPoint(double dist, int32_t index) {
        int i = count_;
        for (; i > 0 && dists_[i - 1] > dist; --i) {
            if (i < capacity_) {
                dists_[i] = dists_[i - 1];
                indices_[i] = indices_[i - 1];
            }
        }
        if (i < capacity_) {
            dists_[i] = dist;
            indices_[i] = index;
        }
        if (count_ < capacity_) ++count_;
        return true;
    }
    double worstDist() const { return dists_[capacity_ - 1]; }
    bool full() const { return count_ == capacity_; }
    size_t size() const { return static_cast<size_t>(count_); }
    void sort() {} // kept sorted as points arrive

private:
    int32_t* indices_;
    double* dists_;
    int capacity_;
    int count_ = 0;
};

// The points strictly nearer than a squared radius, with their squared distances, unordered.
class WithinSet {
public:
    using DistanceType = double;
    using IndexType = int32_t;
    WithinSet(double squared_radius, std::vector<std::pair<int32_t, double>>& found)
        : radius_(squared_radius), found_(found) {}
    bool addPoint(double dist, int32_t index) {
        if (dist < radius_) found_.emplace_back(index, dist);
        return true;
    }
    double worstDist() const { return radius_; }
    bool full() const { return true; }
    size_t size() const { return found_.size(); }
    void sort() {}

private:
    double radius_;
    std::vector<std::pair<int32_t, double>>& found_;
};

struct TreeBase {
    virtual ~TreeBase() = default;
    virtual int knn(const double* q, int k, int32_t* idx, double* d2) const = 0;
    virtual int knn_hinted(const double* q, int k, int32_t* idx, double* d2, const int32_t* hint,
                           int hint_count) const = 0;
    virtual void within(const double* q, double r, std::vector<int32_t>& out) const = 0;
    virtual void within_squared(const double* q, double r2, std::vector<std::pair<int32_t, double>>& found) const = 0;
};

// Fixed dimension D at compile time: nanoflann unrolls the distance loops.
template <int D>
struct Tree final : TreeBase {
    using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, MatrixAdaptor>,
                                                      MatrixAdaptor, D, int32_t>;
    MatrixAdaptor adaptor;
    Index index;
    explicit Tree(const RowMatrix* m)
        : adaptor{m}, index(D, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(12)) {} // builds the index
    int knn(const double* q, int k, int32_t* idx, double* d2) const override {
        NearestSet result(k, idx, d2, std::numeric_limits<double>::max());
        index.findNeighbors(result, q, nanoflann_compat::exact_search());
        return static_cast<int>(result.size());
    }
    int knn_hinted(const double* q, int k, int32_t* idx, double* d2, const int32_t* hint,
                   int hint_count) const override {
        // The hint's points bound the search: k of them lie within the farthest one's distance,
        // so no point beyond it is among the k nearest, and the tree prunes with that bound
        // from its first step instead of with infinity until k points are met.
        double bound = std::numeric_limits<double>::max();
        if (hint_count >= k) {
            bound = 0.0;
            for (int h = 0; h < hint_count; ++h) {
                double dist = 0.0; // summed as nanoflann's L2_Simple_Adaptor does: the value the search computes
                for (int c = 0; c < D; ++c) {
                    const double diff = q[c] - adaptor.kdtree_get_pt(static_cast<size_t>(hint[h]), static_cast<size_t>(c));
                    dist += diff * diff;
                }
                bound = std::max(bound, dist);
            }
            // nanoflann keeps points strictly nearer than the bound: one ulp above keeps the
            // farthest hinted point too.
            bound = std::nextafter(bound, std::numeric_limits<double>::max());
        }
        NearestSet result(k, idx, d2, bound);
        index.findNeighbors(result, q, nanoflann_compat::exact_search());
        // Fewer than k within the bound: the hint repeated a point. Search without it.
        if (static_cast<int>(result.size()) < k && bound < std::numeric_limits<double>::max())
            return knn(q, k, idx, d2);
        return static_cast<int>(result.size());
    }
    void within(const double* q, double r, std::vector<int32_t>& out) const override {
        std::vector<std::pair<int32_t, double>> found;
        within_squared(q, r * r, found); // nanoflann's L2 adaptor works in squared distances
        for (const auto& f : found) out.push_back(f.first);
    }
    // Points at squared distance < r2, unordered, with that distance.
    void within_squared(const double* q, double r2, std::vector<std::pair<int32_t, double>>& found) const override {
        WithinSet result(r2, found);
        index.findNeighbors(result, q, nanoflann_compat::exact_search());
    }
};

} // namespace

struct KdTree::Impl {
    RowMatrix points;
    std::unique_ptr<TreeBase> tree;
};

KdTree::KdTree(const Eigen::Ref<const RowMatrix>& points) : impl_(std::make_unique<Impl>()) {
    impl_->points = points;
    switch (points.cols()) {
    case 3: impl_->tree = std::make_unique<Tree<3>>(&impl_->points); break;
    case 6: impl_->tree = std::make_unique<Tree<6>>(&impl_->points); break;
    default: throw InvalidInput("kd-tree points have " + std::to_string(points.cols()) + " columns, expected 3 or 6");
    }
}

KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

int KdTree::dimension() const { return static_cast<int>(impl_->points.cols()); }
long KdTree::size() const { return static_cast<long>(impl_->points.rows()); }

int KdTree::knn(const double* query, int k, int32_t* indices, double* squared_distances) const {
    if (size() == 0 || k <= 0) return 0;
    return impl_->tree->knn(query, k, indices, squared_distances);
}

int KdTree::knn(const double* query, int k, int32_t* indices, double* squared_distances, const int32_t* hint,
                int hint_count) const {
    if (size() == 0 || k <= 0) return 0;
    return impl_->tree->knn_hinted(query, k, indices, squared_distances, hint, hint_count);
}

int32_t KdTree::nearest(const double* query) const {
    int32_t i = -1;
    double d2 = 0.0;
    knn(query, 1, &i, &d2);
    return i;
}

void KdTree::within(const double* query, double radius, std::vector<int32_t>& out) const {
    if (size() == 0) return;
    impl_->tree->within(query, radius, out);
}

int KdTree::within_sorted(const double* query, double squared_radius, std::vector<int32_t>& indices,
                          std::vector<double>& squared_distances) const {
    indices.clear();
    squared_distances.clear();
    if (size() == 0 || !(squared_radius >= 0.0)) return 0;
    std::vector<std::pair<int32_t, double>> found;
    // nanoflann keeps distances strictly below its bound: one ulp above keeps those equal to it.
    impl_->tree->within_squared(query, std::nextafter(squared_radius, std::numeric_limits<double>::max()), found);
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
        return a.second < b.second || (a.second == b.second && a.first < b.first);
    });
    for (const auto& [index, d2] : found) {
        indices.push_back(index);
        squared_distances.push_back(d2);
    }
    return static_cast<int>(indices.size());
}

} // namespace liftremesh
