#include "liftremesh/mesh/compressed_rows.h"

#include <cstddef>
#include <numeric>

namespace liftremesh {

CompressedRows compress_rows(long rows, const std::vector<std::pair<int32_t, int32_t>>& pairs) {
    CompressedRows c;
    c.offsets.assign(static_cast<size_t>(rows) + 1, 0);
    for (const auto& [row, value] : pairs) ++c.offsets[row + 1];
    std::partial_sum(c.offsets.begin(), c.offsets.end(), c.offsets.begin());
    c.values.resize(pairs.size());
    std::vector<int32_t> fill(c.offsets.begin(), c.offsets.end() - 1);
    for (const auto& [row, value] : pairs) c.values[fill[row]++] = value;
    return c;
}

} // namespace liftremesh
