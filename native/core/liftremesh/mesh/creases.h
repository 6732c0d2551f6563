// The input's creases: its edges whose two triangles turn by more than a given angle. The
// repair steps move vertices onto the acute ones (edit/acute_creases.h), and every one over the
// feature angle gets sites held on it (cvt/crease_sites.h).
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace liftremesh {

//! An input edge (a, b) whose two triangles turn by `turn_deg` degrees.
struct CreaseEdge {
    int32_t a = -1, b = -1;
    int32_t left = -1, right = -1; //!< its two triangles
    double turn_deg = 0.0;
};

//! The crease edges of `input`: those whose two triangles, a consistently oriented pair, turn by
//! more than `min_turn_deg`; in the order of edge_uses().
std::vector<CreaseEdge> crease_edges(const Mesh& input, double min_turn_deg);

//! Of `creases`, those of the chains (crease edges joined at their ends) at least `min_length`
//! long in all, in their order: a shorter chain is a scan's noise or a facet's slip, not a feature.
std::vector<CreaseEdge> long_crease_chains(const Mesh& input, const std::vector<CreaseEdge>& creases, double min_length);

//! long_crease_chains(input, crease_edges(input, min_turn_deg), min_length).
std::vector<CreaseEdge> crease_edges(const Mesh& input, double min_turn_deg, double min_length);

} // namespace liftremesh
