#include "liftremesh/neighbor_search.h"

#include "liftremesh/exceptions.h"

#include <nanoflann.hpp>

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

// nanoflann's k-nearest result set, which may start filled (from a hint): a point the search
// meets again is not added twice. A point dropped from the set cannot come back (its distance
// is not below the k-th any more), so "added before" is "in the set".
class HintedKnnResult {
public:
    HintedKnnResult(int32_t* idx, double* d2, int capacity) : idx_(idx), set_(static_cast<size_t>(capacity)) {
        set_.init(idx, d2);
    }
    size_t size() const { return set_.size(); }
    bool full() const { return set_.full(); }
    double worstDist() const { return set_.worstDist(); }
    bool addPoint(double dist, int32_t index) {
        for (size_t i = 0; i < set_.size(); ++i)
            if (idx_[i] == index) return true; // go on searching
        return set_.addPoint(dist, index);
    }

private:
    const int32_t* idx_;
    nanoflann::KNNResultSet<double, int32_t> set_;
};

struct TreeBase {
    virtual ~TreeBase() = default;
    virtual int knn(const double* q, int k, int32_t* idx, double* d2) const = 0;
    virtual int knn_hinted(const double* q, int k, int32_t* idx, double* d2, const int32_t* hint,
                           int hint_count) const = 0;
    virtual void within(const double* q, double r, std::vector<int32_t>& out) const = 0;
};

// Fixed dimension D at compile time: nanoflann unrolls the distance loops.
template <int D>
struct Tree final : TreeBase {
    using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, MatrixAdaptor>,
                                                      MatrixAdaptor, D, int32_t>;
    MatrixAdaptor adaptor;
    Index index;
    explicit Tree(const RowMatrix* m)
        : adaptor{m}, index(D, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(12)) {
        index.buildIndex();
    }
    int knn(const double* q, int k, int32_t* idx, double* d2) const override {
        nanoflann::KNNResultSet<double, int32_t> result(static_cast<size_t>(k));
        result.init(idx, d2);
        index.findNeighbors(result, q, nanoflann::SearchParams());
        return static_cast<int>(result.size());
    }
    int knn_hinted(const double* q, int k, int32_t* idx, double* d2, const int32_t* hint,
                   int hint_count) const override {
        HintedKnnResult result(idx, d2, k);
        for (int h = 0; h < hint_count; ++h) {
            double dist = 0.0; // summed as nanoflann's L2_Simple_Adaptor does: a point met again compares equal
            for (int c = 0; c < D; ++c) {
                const double diff = q[c] - adaptor.kdtree_get_pt(static_cast<size_t>(hint[h]), static_cast<size_t>(c));
                dist += diff * diff;
            }
            if (dist < result.worstDist()) result.addPoint(dist, hint[h]);
        }
        index.findNeighbors(result, q, nanoflann::SearchParams());
        return static_cast<int>(result.size());
    }
    void within(const double* q, double r, std::vector<int32_t>& out) const override {
        std::vector<std::pair<int32_t, double>> found;
        nanoflann::SearchParams params;
        params.sorted = false;
        index.radiusSearch(q, r * r, found, params); // nanoflann's L2 adaptor works in squared distances
        for (const auto& f : found) out.push_back(f.first);
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

} // namespace liftremesh
