// Compressed rows (CSR): for each of n rows a list of int32 values, stored one after another.
// Used for vertex -> incident triangles and site -> nearby movers.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace liftremesh {

//! A run of int32 values [first, last), to walk with a range-for.
struct IndexRange {
    const int32_t *first, *last;
    const int32_t* begin() const { return first; }
    const int32_t* end() const { return last; }
};

//! Row r holds values[offsets[r]] .. values[offsets[r + 1] - 1].
struct CompressedRows {
    std::vector<int32_t> offsets; //!< rows + 1, non-decreasing, offsets[0] = 0
    std::vector<int32_t> values;
    const int32_t* begin(long row) const { return values.data() + offsets[row]; }
    const int32_t* end(long row) const { return values.data() + offsets[row + 1]; }
    IndexRange row(long r) const { return {begin(r), end(r)}; }
};

//! The rows of (row, value) pairs, row in [0, rows); each row keeps its values in pair order.
CompressedRows compress_rows(long rows, const std::vector<std::pair<int32_t, int32_t>>& pairs);

} // namespace liftremesh
