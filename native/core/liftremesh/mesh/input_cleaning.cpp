#include "liftremesh/mesh/input_cleaning.h"

#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/mesh/orientation.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {

using Tri = std::array<int32_t, 3>;

// The facet's corners from its smallest index on: equal for the same facet listed from another
// corner, different for the other winding.
Tri rotated(Tri t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
}

// Step 3: drops the repeats of each facet and returns the pairs (first, first other way round)
// of the facets listed in both windings, for the sheet test.
long drop_repeats(const std::vector<Tri>& tris, std::vector<char>& live, std::vector<std::pair<int, int>>& both) {
    // The live facets by their sorted corners, each set of corners in the facets' order: a sort,
    // where a hash map of a million facets spends its time allocating.
    std::vector<std::pair<Tri, int>> keyed;
    keyed.reserve(tris.size());
    for (size_t f = 0; f < tris.size(); ++f) {
        if (!live[f]) continue;
        Tri key = tris[f];
        std::sort(key.begin(), key.end());
        keyed.emplace_back(key, static_cast<int>(f));
    }
    std::sort(keyed.begin(), keyed.end());
    long dropped = 0;
    for (size_t i = 0; i < keyed.size();) {
        size_t end = i + 1;
        while (end < keyed.size() && keyed[end].first == keyed[i].first) ++end;
        const int first = keyed[i].second; // the first listed of these corners
        int other = -1;                     // the first listed the other way round
        for (size_t k = i + 1; k < end; ++k) {
            const int f = keyed[k].second;
            if (other < 0 && rotated(tris[f]) != rotated(tris[first])) {
                other = f; // kept until the sheet test decides
                both.emplace_back(first, f);
                continue;
            }
            live[f] = 0;
            ++dropped;
        }
        i = end;
    }
    // In the order of the second facet of each pair, as a pass over the facets finds them.
    std::sort(both.begin(), both.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
    return dropped;
}

// Step 3's exception: which of the pairs `both` are the two sides of a two-sided sheet. Pairs
// sharing a side form patches; a patch is a sheet when no other facet uses its sides and one of
// its sides is used by one pair alone (a free border: a closed surface listed twice has none).
std::vector<char> two_sided(const std::vector<Tri>& tris, const std::vector<char>& live,
                            const std::vector<std::pair<int, int>>& both) {
    std::vector<int> pair_of(tris.size(), -1);
    for (size_t k = 0; k < both.size(); ++k) pair_of[both[k].first] = pair_of[both[k].second] = static_cast<int>(k);
    const EdgeUses edges = edge_uses(tris.empty() ? nullptr : tris[0].data(), static_cast<long>(tris.size()), live);
    std::vector<std::pair<int, int>> links; // pairs sharing a side
    std::vector<char> touched(both.size(), 0), free_border(both.size(), 0);
    std::vector<int> pairs;
    for (long e = 0; e < edges.size(); ++e) {
        pairs.clear();
        bool other = false;
        for (const int32_t* use = edges.uses.begin(e); use != edges.uses.end(e); ++use) {
            const int k = pair_of[*use / 3];
            if (k < 0) other = true;
            else pairs.push_back(k);
        }
        if (pairs.empty()) continue;
        for (size_t i = 1; i < pairs.size(); ++i) links.emplace_back(pairs[0], pairs[i]);
        for (int k : pairs) touched[k] |= other;
        if (!other && edges.count(e) == 2 && pairs[0] == pairs[1]) free_border[pairs[0]] = 1;
    }
    std::vector<int> patch;
    const int count = connected_components(static_cast<int>(both.size()), links, patch);
    std::vector<char> patch_touched(count, 0), patch_free(count, 0);
    for (size_t k = 0; k < both.size(); ++k) {
        patch_touched[patch[k]] |= touched[k];
        patch_free[patch[k]] |= free_border[k];
    }
    std::vector<char> sheet(both.size());
    for (size_t k = 0; k < both.size(); ++k) sheet[k] = !patch_touched[patch[k]] && patch_free[patch[k]];
    return sheet;
}

// Step 4: the zero-area facets whose sides all keep two facets or more, or none, without them.
long drop_zero_area(const Points& points, const std::vector<Tri>& tris, std::vector<char>& live) {
    std::vector<size_t> flat; // the live facets of zero area, in order
    for (size_t f = 0; f < tris.size(); ++f)
        if (live[f] && zero_area(points.row(tris[f][0]).transpose(), points.row(tris[f][1]).transpose(),
                                 points.row(tris[f][2]).transpose()))
            flat.push_back(f);
    if (flat.empty()) return 0;
    const EdgeUses edges = edge_uses(tris[0].data(), static_cast<long>(tris.size()), live);
    const std::vector<int32_t> edge_of = edges.edge_of_sides(static_cast<long>(tris.size()));
    std::vector<int> uses(static_cast<size_t>(edges.size()));
    for (long e = 0; e < edges.size(); ++e) uses[e] = static_cast<int>(edges.count(e));
    long dropped = 0;
    for (const size_t f : flat) {
        bool closes = false; // a side that has this facet and one other only
        for (int j = 0; j < 3; ++j) closes |= uses[edge_of[3 * f + j]] == 2;
        if (closes) continue;
        for (int j = 0; j < 3; ++j) --uses[edge_of[3 * f + j]];
        live[f] = 0;
        ++dropped;
    }
    return dropped;
}

} // namespace

InputCleaning clean_input(Mesh& mesh) {
    weld_exact(mesh); // step 1 (checks the indices)
    InputCleaning done;
    std::vector<Tri> tris(static_cast<size_t>(mesh.triangles.rows()));
    std::vector<char> live(tris.size(), 1);
    for (size_t f = 0; f < tris.size(); ++f) {
        for (int j = 0; j < 3; ++j) tris[f][j] = mesh.triangles(static_cast<Eigen::Index>(f), j);
        const Tri& t = tris[f];
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) { // step 2
            live[f] = 0;
            ++done.degenerate_removed;
        }
    }
    std::vector<std::pair<int, int>> both; // step 3
    done.duplicates_removed = drop_repeats(tris, live, both);
    const std::vector<char> sheet = two_sided(tris, live, both);
    for (size_t k = 0; k < both.size(); ++k)
        if (!sheet[k]) {
            live[both[k].second] = 0;
            ++done.duplicates_removed;
        }
    done.degenerate_removed += drop_zero_area(mesh.points, tris, live); // step 4
    const std::vector<char> turned = orient_components(mesh.points, tris, live); // step 5
    done.facets_turned = std::count(turned.begin(), turned.end(), 1);

    Triangles kept(std::count(live.begin(), live.end(), 1), 3);
    Eigen::Index row = 0;
    for (size_t f = 0; f < tris.size(); ++f)
        if (live[f]) kept.row(row++) << tris[f][0], tris[f][1], tris[f][2];
    mesh.triangles = std::move(kept);
    return done;
}

} // namespace liftremesh
