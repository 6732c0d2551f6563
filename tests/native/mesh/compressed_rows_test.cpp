#include "liftremesh/mesh/compressed_rows.h"

#include <gtest/gtest.h>

#include <vector>

using namespace liftremesh;

TEST(CompressedRows, KeepEachRowsValuesInPairOrderAndEmptyRowsEmpty) {
    const std::vector<std::pair<int32_t, int32_t>> pairs = {{2, 7}, {0, 1}, {2, 3}, {0, 9}, {4, 5}, {2, 8}};
    const CompressedRows c = compress_rows(5, pairs);
    ASSERT_EQ(c.offsets.size(), 6u);
    auto row = [&](long r) { return std::vector<int32_t>(c.begin(r), c.end(r)); };
    EXPECT_EQ(row(0), (std::vector<int32_t>{1, 9}));
    EXPECT_TRUE(row(1).empty());
    EXPECT_EQ(row(2), (std::vector<int32_t>{7, 3, 8}));
    EXPECT_TRUE(row(3).empty());
    EXPECT_EQ(row(4), (std::vector<int32_t>{5}));
    EXPECT_EQ(c.values.size(), pairs.size());
    EXPECT_TRUE(compress_rows(3, {}).values.empty());
    EXPECT_EQ(compress_rows(3, {}).offsets, (std::vector<int32_t>{0, 0, 0, 0}));
}
