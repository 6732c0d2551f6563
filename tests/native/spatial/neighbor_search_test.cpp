// KdTree: k nearest and radius queries against brute force, with and without a hint.
#include "liftremesh/spatial/neighbor_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

using namespace liftremesh;

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

RowMatrix random_points(long n, int d, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    RowMatrix p(n, d);
    for (long i = 0; i < n; ++i)
        for (int c = 0; c < d; ++c) p(i, c) = u(rng);
    return p;
}

// The k nearest rows of `p` to row q, closest first, by sorting all distances.
std::vector<int32_t> brute_knn(const RowMatrix& p, long q, int k) {
    std::vector<int32_t> order(p.rows());
    std::iota(order.begin(), order.end(), 0);
    const Eigen::RowVectorXd query = p.row(q);
    std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
        return (p.row(a) - query).squaredNorm() < (p.row(b) - query).squaredNorm();
    });
    order.resize(k);
    return order;
}

class KnnDimensions : public ::testing::TestWithParam<int> {};

TEST_P(KnnDimensions, MatchBruteForceWithOrWithoutAHint) {
    const int d = GetParam(), k = 24;
    const RowMatrix p = random_points(2000, d, 7);
    const KdTree tree(p);
    std::mt19937 rng(3);
    std::uniform_int_distribution<int32_t> any(0, static_cast<int32_t>(p.rows()) - 1);
    for (long q = 0; q < p.rows(); q += 37) {
        const std::vector<int32_t> expected = brute_knn(p, q, k);
        std::vector<int32_t> idx(k);
        std::vector<double> d2(k);
        ASSERT_EQ(tree.knn(p.row(q).data(), k, idx.data(), d2.data()), k);
        EXPECT_EQ(idx, expected);
        EXPECT_TRUE(std::is_sorted(d2.begin(), d2.end()));
        // Hints: the answer itself reversed, a part of it, far points only, a mix with repeats,
        // and k entries naming two points; none may change the answer or duplicate a point.
        std::vector<int32_t> reversed(expected.rbegin(), expected.rend());
        std::vector<int32_t> half(expected.begin(), expected.begin() + k / 2);
        std::vector<int32_t> far = brute_knn(p, q, 300);
        far.erase(far.begin(), far.begin() + 200);
        std::vector<int32_t> mixed = {expected[3], any(rng), expected[3], any(rng), expected[0]};
        // k entries, but not k points: their farthest is no bound on the k-th nearest.
        std::vector<int32_t> repeated(k, expected[1]);
        repeated[0] = expected[0];
        for (const std::vector<int32_t>* hint : {&reversed, &half, &far, &mixed, &repeated}) {
            std::vector<int32_t> hinted(k);
            std::vector<double> hinted_d2(k);
            ASSERT_EQ(tree.knn(p.row(q).data(), k, hinted.data(), hinted_d2.data(), hint->data(),
                               static_cast<int>(hint->size())),
                      k);
            EXPECT_EQ(hinted, expected);
            EXPECT_EQ(hinted_d2, d2); // the same distances, to the bit
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Dimensions, KnnDimensions, ::testing::Values(3, 6));

TEST(Knn, FewerPointsThanAskedReturnsThemAll) {
    const RowMatrix p = random_points(5, 3, 1);
    const KdTree tree(p);
    std::vector<int32_t> idx(8), hint = {4, 2};
    std::vector<double> d2(8);
    EXPECT_EQ(tree.knn(p.row(0).data(), 8, idx.data(), d2.data()), 5);
    EXPECT_EQ(tree.knn(p.row(0).data(), 8, idx.data(), d2.data(), hint.data(), 2), 5);
    std::sort(idx.begin(), idx.begin() + 5);
    EXPECT_EQ(std::vector<int32_t>(idx.begin(), idx.begin() + 5), (std::vector<int32_t>{0, 1, 2, 3, 4}));
}

TEST(Within, FindsExactlyThePointsInsideTheRadius) {
    const RowMatrix p = random_points(1500, 3, 11);
    const KdTree tree(p);
    for (long q = 0; q < p.rows(); q += 101) {
        std::vector<int32_t> found;
        tree.within(p.row(q).data(), 0.3, found);
        std::sort(found.begin(), found.end());
        std::vector<int32_t> expected;
        for (long i = 0; i < p.rows(); ++i)
            if ((p.row(i) - p.row(q)).norm() < 0.3) expected.push_back(static_cast<int32_t>(i));
        EXPECT_EQ(found, expected);
    }
}

// within_sorted: the points at most the radius away, closest first, with the distances knn()
// reports; a point exactly at the squared radius is in (the security radius test of rvd.cpp
// stops only past it).
TEST(Within, SortedListsEveryPointUpToTheRadiusClosestFirst) {
    for (int d : {3, 6}) {
        const RowMatrix p = random_points(1500, d, 12);
        const KdTree tree(p);
        for (long q = 0; q < p.rows(); q += 97) {
            std::vector<int32_t> found;
            std::vector<double> d2;
            const int n = tree.within_sorted(p.row(q).data(), 0.35 * 0.35, found, d2);
            ASSERT_EQ(n, static_cast<int>(found.size()));
            ASSERT_EQ(found.size(), d2.size());
            std::vector<int32_t> expected;
            for (long i = 0; i < p.rows(); ++i)
                if ((p.row(i) - p.row(q)).squaredNorm() <= 0.35 * 0.35) expected.push_back(static_cast<int32_t>(i));
            std::vector<int32_t> sorted_found = found;
            std::sort(sorted_found.begin(), sorted_found.end());
            EXPECT_EQ(sorted_found, expected) << "d " << d << " query " << q;
            EXPECT_TRUE(std::is_sorted(d2.begin(), d2.end()));
            // The same distances as the k nearest, in the same order.
            std::vector<int32_t> knn(n);
            std::vector<double> knn_d2(n);
            ASSERT_EQ(tree.knn(p.row(q).data(), n, knn.data(), knn_d2.data()), n);
            EXPECT_EQ(knn_d2, d2);
            EXPECT_EQ(knn, found);
        }
        // A point exactly at the radius is found.
        std::vector<int32_t> found;
        std::vector<double> d2;
        std::vector<int32_t> all(p.rows());
        std::vector<double> all_d2(p.rows());
        tree.knn(p.row(0).data(), static_cast<int>(p.rows()), all.data(), all_d2.data());
        const size_t at = static_cast<size_t>(std::find(all.begin(), all.end(), 1) - all.begin());
        tree.within_sorted(p.row(0).data(), all_d2[at], found, d2); // row 1's distance, as the tree sums it
        EXPECT_NE(std::find(found.begin(), found.end(), 1), found.end()) << "d " << d;
    }
}

} // namespace
