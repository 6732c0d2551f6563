#include "liftremesh/cvt/crease_sites.h"

#include "liftremesh/cvt/sampling.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/neighbor_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

namespace liftremesh {

namespace {

// A site on a crease: where, lifted, and the spacing the free sites reach there.
struct Candidate {
    Eigen::RowVectorXd lifted;
    double spacing = 0.0;
};

// The chains of crease edges: from each corner along each of its edges to the next corner, then
// the closed loops (first vertex repeated last), each from its smallest vertex.
std::vector<std::vector<int32_t>> crease_chains(const std::map<int32_t, std::vector<int32_t>>& next) {
    std::set<std::pair<int32_t, int32_t>> walked;
    auto walk = [&](int32_t from, int32_t to) {
        std::vector<int32_t> chain{from};
        int32_t prev = from, at = to;
        walked.insert(std::minmax(from, to));
        while (true) {
            chain.push_back(at);
            const std::vector<int32_t>& out = next.at(at);
            if (out.size() != 2 || at == from) break; // a corner, or round a loop
            const int32_t ahead = out[0] == prev ? out[1] : out[0];
            if (!walked.insert(std::minmax(at, ahead)).second) break;
            prev = at;
            at = ahead;
        }
        return chain;
    };
    std::vector<std::vector<int32_t>> chains;
    for (const auto& [v, out] : next)
        if (out.size() != 2)
            for (int32_t w : out)
                if (!walked.count(std::minmax(v, w))) chains.push_back(walk(v, w));
    for (const auto& [v, out] : next)
        if (out.size() == 2 && !walked.count(std::minmax(v, out[0]))) chains.push_back(walk(v, out[0]));
    return chains;
}

} // namespace

CreaseSites::CreaseSites(const LiftedSurface& surface, const std::vector<CreaseEdge>& creases,
                         long sites, const CreaseSitesParams& params)
    : creases_(creases), params_(params) {
    if (!(params_.min_separation >= 0.0) || !(params_.max_fraction >= 0.0 && params_.max_fraction <= 1.0) ||
        !(params_.clearance >= 0.0) || !(params_.crowded >= 0.0))
        throw InvalidInput("crease_sites: the separation, clearance and crowding must not be negative, the "
                           "fraction held must be between 0 and 1");
    const Eigen::Index nv = surface.points.rows();
    const int d = surface.dimension();
    auto xyz = [&surface](int32_t v) -> Eigen::Vector3d { return surface.points.row(v).leftCols<3>().transpose(); };
    held_.resize(0, d);
    std::map<int32_t, std::vector<int32_t>> next; // each crease vertex's neighbours along the creases
    for (const auto& [a, b, left, right, turn] : creases_) {
        if (a < 0 || b < 0 || a >= nv || b >= nv || a == b)
            throw InvalidInput("crease_sites: a crease edge's vertex index is out of range");
        next[a].push_back(b);
        next[b].push_back(a);
    }
    if (next.empty() || sites <= 0) return;

    // The site density at each crease vertex: the mean of sqrt(w_p) over its triangles (see the
    // header), not weighted by their areas: on a CAD tessellation a crease vertex's triangles
    // include slivers reaching far across a face, whose weight is that of places far away.
    Eigen::VectorXd count = Eigen::VectorXd::Zero(nv), mass = Eigen::VectorXd::Zero(nv);
    for (const int32_t f : surface.row_of) { // as given: the sums do not depend on the surface's order
        if (!surface.valid[f]) continue;
        const double w = surface.weights.size() > 0 ? std::sqrt(surface.weights[f]) : 1.0;
        for (int j = 0; j < 3; ++j) {
            count[surface.triangles(f, j)] += 1.0;
            mass[surface.triangles(f, j)] += w;
        }
    }
    const double per_site = sampling_mass(surface) / static_cast<double>(sites);
    if (!(per_site > 0.0) || !std::isfinite(per_site)) return; // no area to hold sites on
    spacing_ = Eigen::VectorXd::Zero(nv);
    double largest = 0.0, smallest = std::numeric_limits<double>::infinity();
    for (const auto& [v, out] : next) {
        const double density = count[v] > 0.0 && mass[v] > 0.0 ? mass[v] / count[v] : 1.0;
        spacing_[v] = std::sqrt(per_site / (std::sqrt(3.0) / 2.0 * density));
        largest = std::max(largest, spacing_[v]);
        smallest = std::min(smallest, spacing_[v]);
    }
    auto at = [&](int32_t v) { return Candidate{surface.points.row(v), spacing_[v]}; };

    std::vector<Candidate> candidates;
    for (const auto& [v, out] : next)
        if (out.size() != 2) candidates.push_back(at(v));
    const size_t corners = candidates.size();
    std::vector<int32_t> chain_of(corners, -1); // per candidate; -1 for the corners
    std::map<std::pair<int32_t, int32_t>, int32_t> chain_of_pair; // per crease edge's ends
    int32_t chain_index = -1;
    for (const std::vector<int32_t>& chain : crease_chains(next)) {
        ++chain_index;
        for (size_t i = 1; i < chain.size(); ++i) chain_of_pair[std::minmax(chain[i - 1], chain[i])] = chain_index;
        // Length along the chain in local spacings, tau; n pieces of equal tau.
        std::vector<double> tau{0.0};
        for (size_t i = 1; i < chain.size(); ++i) {
            const double step = (xyz(chain[i]) - xyz(chain[i - 1])).norm();
            tau.push_back(tau.back() + step / (0.5 * (spacing_[chain[i]] + spacing_[chain[i - 1]])));
        }
        const bool loop = chain.front() == chain.back();
        const double total = tau.back();
        const long pieces = loop ? std::max(3L, std::lround(total)) : std::max(1L, std::lround(total));
        size_t i = 0;
        for (long k = loop ? 0 : 1; k < pieces; ++k) {
            const double target = total * static_cast<double>(k) / static_cast<double>(pieces);
            while (i + 2 < tau.size() && tau[i + 1] < target) ++i;
            const double span = tau[i + 1] - tau[i];
            const double t = span > 0.0 ? std::clamp((target - tau[i]) / span, 0.0, 1.0) : 0.0;
            const Candidate a = at(chain[i]), b = at(chain[i + 1]);
            candidates.push_back({(1.0 - t) * a.lifted + t * b.lifted, (1.0 - t) * a.spacing + t * b.spacing});
            chain_of.push_back(chain_index);
        }
    }

    // Taken in order unless one taken before is nearer than min_separation spacings.
    Points where(static_cast<Eigen::Index>(candidates.size()), 3);
    for (size_t c = 0; c < candidates.size(); ++c) where.row(static_cast<Eigen::Index>(c)) = candidates[c].lifted.leftCols<3>();
    const KdTree tree(where);
    std::vector<char> taken(candidates.size(), 0);
    std::vector<int32_t> near;
    long taken_corners = 0, taken_all = 0;
    for (size_t c = 0; c < candidates.size(); ++c) {
        near.clear();
        tree.within(where.row(static_cast<Eigen::Index>(c)).data(), params_.min_separation * candidates[c].spacing, near);
        if (std::any_of(near.begin(), near.end(), [&](int32_t o) { return static_cast<size_t>(o) < c && taken[o]; })) continue;
        taken[c] = 1;
        ++taken_all;
        if (c < corners) ++taken_corners;
    }
    const double most = params_.max_fraction * static_cast<double>(sites);
    const size_t last = static_cast<double>(taken_all) <= most        ? candidates.size()
                        : static_cast<double>(taken_corners) <= most ? corners
                                                                     : 0;
    std::vector<Eigen::Index> rows;
    for (size_t c = 0; c < last; ++c)
        if (taken[c]) rows.push_back(static_cast<Eigen::Index>(c));
    // The crease edges in 3D, indexed (sampled a quarter of the smallest spacing apart) for the
    // crowded parts below and for crowds() once a site is held.
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
    for (const CreaseEdge& e : creases_) segments.emplace_back(xyz(e.a), xyz(e.b));
    if (last == corners && corners < candidates.size() && params_.crowded > 0.0) {
        // The chains' crowded parts (CreaseSitesParams::crowded), if they fit with the corners.
        std::vector<int32_t> chain_of_crease;
        for (const CreaseEdge& e : creases_) {
            const auto found = chain_of_pair.find(std::minmax(e.a, e.b));
            chain_of_crease.push_back(found == chain_of_pair.end() ? -1 : found->second);
        }
        std::vector<Eigen::Index> crowded;
        const SegmentIndex& index = edges_.emplace(segments, 0.25 * smallest);
        std::optional<KdTree> corner_tree;
        if (corners > 0) corner_tree.emplace(where.topRows(static_cast<Eigen::Index>(corners)));
        std::vector<int32_t> near_edges;
        for (size_t c = corners; c < candidates.size(); ++c) {
            if (!taken[c]) continue;
            const Eigen::Vector3d p = where.row(static_cast<Eigen::Index>(c)).transpose();
            const double spacing = candidates[c].spacing, reach = params_.crowded * spacing;
            const auto corner = static_cast<Eigen::Index>(corner_tree ? corner_tree->nearest(p.data()) : -1);
            if (corner >= 0 && (where.row(corner).transpose() - p).norm() < 2.0 * spacing) continue;
            index.near(p, reach, near_edges);
            if (std::any_of(near_edges.begin(), near_edges.end(), [&](int32_t e) {
                    const auto& [a, b] = segments[e];
                    return chain_of_crease[e] != chain_of[c] && (closest_point_on_segment(p, a, b) - p).norm() < reach;
                }))
                crowded.push_back(static_cast<Eigen::Index>(c));
        }
        // A lone crowded candidate is where two chains meet at a narrow angle near a corner (a
        // knife edge's tip), whose strip is shorter than a cell: held, its site leaves thin
        // triangles at the tip. A strip along two or more is held.
        std::vector<Eigen::Index> runs;
        for (size_t i = 0; i < crowded.size();) {
            size_t j = i + 1;
            while (j < crowded.size() && crowded[j] == crowded[j - 1] + 1 && chain_of[crowded[j]] == chain_of[crowded[i]])
                ++j;
            if (j - i >= 2)
                for (; i < j; ++i) runs.push_back(crowded[i]);
            i = j;
        }
        crowded.swap(runs);
        if (static_cast<double>(rows.size() + crowded.size()) <= most)
            rows.insert(rows.end(), crowded.begin(), crowded.end());
    }
    held_.resize(static_cast<Eigen::Index>(rows.size()), d);
    for (size_t r = 0; r < rows.size(); ++r) held_.row(static_cast<Eigen::Index>(r)) = candidates[rows[r]].lifted;
    rows_held_ = last == candidates.size() && last > corners;
    // With no whole chain held (a part all creases, as a thread), the free sites are still kept
    // off the creases: the snap after the triangulation (crease_snap.h) then finds the vertices
    // next to a crease far enough from it that its moves keep their triangles whole.
    if (held_.rows() == 0) {
        edges_.reset(); // nothing crowds a crease
        return;
    }

    // The crease edges for crowds(), indexed and lifted.
    for (const CreaseEdge& e : creases_) lifted_ends_.emplace_back(surface.points.row(e.a), surface.points.row(e.b));
    if (!edges_) edges_.emplace(segments, 0.25 * smallest);
    double widest = 0.0; // the largest clearance, at the most acute crease
    for (const CreaseEdge& e : creases_) widest = std::max(widest, clearance(e.turn_deg));
    reach_ = widest * largest;
}

// The clearance over sin(alpha) for an interior angle alpha under 90 degrees (see the header),
// at most twice the clearance (alpha = 30 degrees): 1 / sin(alpha) grows without bound on a
// sharper wedge, and would empty a band round its knife edge of free sites, many spacings wide,
// that the held row's triangles alone then span.
double CreaseSites::clearance(double turn_deg) const {
    const double interior = std::clamp(180.0 - turn_deg, 30.0, 90.0) * M_PI / 180.0;
    return params_.clearance / std::sin(interior);
}

bool CreaseSites::crowds(const Eigen::Ref<const Eigen::RowVectorXd>& site, std::vector<int32_t>& found) const {
    if (!edges_) return false;
    edges_->near(site.leftCols<3>().transpose(), reach_, found); // 3D distances are at most the lifted ones
    for (int32_t e : found) {
        const auto& [a, b, left, right, turn] = creases_[e];
        const Eigen::RowVectorXd& la = lifted_ends_[e].first;
        const Eigen::RowVectorXd along = lifted_ends_[e].second - la;
        const double len2 = along.squaredNorm();
        const double t = len2 > 0.0 ? std::clamp((site - la).dot(along) / len2, 0.0, 1.0) : 0.0;
        if ((site - la - t * along).norm() < clearance(turn) * ((1.0 - t) * spacing_[a] + t * spacing_[b])) return true;
    }
    return false;
}

LiftedPoints CreaseSites::free_sites(const LiftedSurface& surface, long count, std::uint64_t seed) const {
    if (!edges_ || count <= 0) return random_sites(surface, count, seed);
    // Drawn as random_sites draws, twice as many as wanted: those that crowd a crease are the
    // last taken, and of the others `count` at random, kept in the draw's (Morton) order.
    const LiftedPoints drawn = random_sites(surface, 2 * count + 16, seed);
    std::vector<char> crowding(static_cast<size_t>(drawn.rows()));
    std::vector<int32_t> found;
    for (Eigen::Index k = 0; k < drawn.rows(); ++k) crowding[k] = crowds(drawn.row(k), found);
    std::vector<Eigen::Index> order(static_cast<size_t>(drawn.rows()));
    for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<Eigen::Index>(k);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(seed ^ 0x9e3779b97f4a7c15ULL));
    std::stable_partition(order.begin(), order.end(), [&](Eigen::Index k) { return !crowding[k]; });
    order.resize(static_cast<size_t>(count));
    std::sort(order.begin(), order.end());
    LiftedPoints out(count, drawn.cols());
    for (long k = 0; k < count; ++k) out.row(k) = drawn.row(order[k]);
    return out;
}

long CreaseSites::reseat_crowding_sites(const LiftedSurface& surface, LiftedPoints& sites, long first,
                                        std::uint64_t seed) const {
    std::vector<int32_t> found;
    std::vector<Eigen::Index> crowding;
    for (Eigen::Index k = first; k < sites.rows(); ++k)
        if (crowds(sites.row(k), found)) crowding.push_back(k);
    if (crowding.empty()) return 0;
    const LiftedPoints fresh = free_sites(surface, static_cast<long>(crowding.size()), seed);
    for (size_t i = 0; i < crowding.size(); ++i) sites.row(crowding[i]) = fresh.row(static_cast<Eigen::Index>(i));
    return static_cast<long>(crowding.size());
}

} // namespace liftremesh
