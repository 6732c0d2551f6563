// The one place that knows which nanoflann it is built with. Private to neighbor_search.cpp.
//
// Debian 12 ships nanoflann 1.4.3 and Debian 13 ships 1.7.1. Between them:
// - 1.5 renamed the search options `SearchParams` to `SearchParameters`;
// - 1.5 made radiusSearch fill a vector of `ResultItem` instead of `std::pair`, and 1.6 changed
//   KNNResultSet so that a bound written before the search no longer prunes it.
// neighbor_search.cpp therefore brings its own result sets (only `findNeighbors`, which is the
// same in both, sees them), and needs from here the options type alone.
// Both versions build the index in the tree's constructor (1.4.3 onwards): no buildIndex() call.
#pragma once

#include <nanoflann.hpp>

namespace liftremesh::nanoflann_compat {

#if NANOFLANN_VERSION >= 0x150
using SearchOptions = nanoflann::SearchParameters;
#else
using SearchOptions = nanoflann::SearchParams;
#endif

//! Options for an exact search whose results need no sorting by nanoflann (the result sets of
//! neighbor_search.cpp keep their own order).
inline SearchOptions exact_search() {
    SearchOptions options;
    options.eps = 0.0f;
    options.sorted = false;
    return options;
}

} // namespace liftremesh::nanoflann_compat
