// Consistent orientation of a triangle soup: the "harmonize normals" of a mesh repair, shared by
// the input's cleaning (input_cleaning.h) and the manifold repair of the output (repair.h).
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace liftremesh {

//! Orients every connected component of the live triangles (connected through edges with
//! exactly two live triangles: a non-manifold edge joins nothing) consistently, by breadth-first
//! search, then keeps the orientation the larger area of the component already had: two
//! neighbours agree when they run their common edge in opposite directions. Turns triangles in
//! place (swapping corners 1 and 2) and returns a flag per triangle, 1 for those turned. On a
//! non-orientable component (a Moebius band) the search tree decides and some edges stay
//! inconsistent. `live` has a flag per triangle, or is empty (all live).
std::vector<char> orient_components(const Points& points, std::vector<std::array<int32_t, 3>>& triangles,
                                    const std::vector<char>& live = {});

//! Whether triangle t runs its side a -> b (as opposed to b -> a, or not having it).
inline bool traverses(const std::array<int32_t, 3>& t, int32_t a, int32_t b) {
    for (int j = 0; j < 3; ++j)
        if (t[j] == a && t[j == 2 ? 0 : j + 1] == b) return true;
    return false;
}

} // namespace liftremesh
