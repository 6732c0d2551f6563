#include "liftremesh/snap/crease_snap.h"

#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/creases.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/segment_index.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace liftremesh {

namespace {

// An output edge whose triangles turn by more than this (degrees) stands for a crease: issue 35's
// check counts a crease kept where such an edge runs near it.
constexpr double kMeshCreaseDeg = 15.0;

using Tri = EditableMesh::Tri;

// The edges of a mesh that stand for creases (kMeshCreaseDeg), as issue 35's check counts them,
// and how near a point one of them passes.
class MeshCreases {
public:
    // Sampled as sparsely as the snap's creases (AcuteCreases at half its radius), or every
    // bend_distance if that is sparser: the index only narrows the search, the distances decide.
    MeshCreases(const Mesh& mesh, const CreaseSnapParams& params) {
        for (const CreaseEdge& e : crease_edges(mesh, kMeshCreaseDeg))
            edges_.emplace_back(mesh.points.row(e.a).transpose(), mesh.points.row(e.b).transpose());
        if (!edges_.empty()) index_.emplace(edges_, std::max(params.bend_distance, 0.5 * params.radius));
    }

    // The distance from p to the nearest of the edges if one passes within r, else more than r.
    double distance(const Eigen::Vector3d& p, double r) const {
        double nearest = std::numeric_limits<double>::infinity();
        if (!index_) return nearest;
        index_->near(p, r, near_);
        for (const int32_t k : near_)
            nearest = std::min(nearest, (closest_point_on_segment(p, edges_[k].first, edges_[k].second) - p).norm());
        return nearest;
    }

private:
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> edges_;
    std::optional<SegmentIndex> index_;
    mutable std::vector<int32_t> near_;
};

// The mesh under moves and flips, with each vertex's triangles kept current.
class Snapper {
public:
    Snapper(Mesh& mesh, const AabbTree& input, const CreaseSnapParams& params)
        : mesh_(mesh), input_(input), params_(params), cos_off_(std::cos(60.0 * M_PI / 180.0)) {
        mesh_.keep_fans();
    }

    const EditableMesh& mesh() const { return mesh_; }

    // Moves v to x with the flips that follow, or leaves everything as it was (see the header),
    // where the fan of v lies farther than `depth` from x; the move and its flips keep `floor`.
    bool snap(int32_t v, const Eigen::Vector3d& x, double depth, long& flips, double floor) {
        if (mesh_.fan(v).empty()) return false; // not a vertex of the surface
        // Only where the crease is cut deeper than the tolerance: the fan of v, which is all the
        // mesh there, lies farther from x than that.
        double cut2 = std::numeric_limits<double>::infinity();
        for (int t : mesh_.fan(v)) {
            const Tri& f = mesh_.tris[t];
            const Eigen::Vector3d near = closest_point_on_triangle(x, mesh_.points[f[0]], mesh_.points[f[1]], mesh_.points[f[2]]);
            cut2 = std::min(cut2, (near - x).squaredNorm());
        }
        if (!(cut2 > depth * depth)) return false;
        saved_.clear();
        for (int t : mesh_.fan(v)) save(t);
        const Eigen::Vector3d was = mesh_.points[v];
        const Measure before = measure_saved(); // the fan's originals, v where it was
        // The triangles round the fan, whose edges a move and its flips may fold, and which
        // they may lay through each other beside a knife edge.
        std::vector<int> region;
        for (int t : mesh_.fan(v))
            for (int32_t w : mesh_.tris[t]) region.insert(region.end(), mesh_.fan(w).begin(), mesh_.fan(w).end());
        const int folded_before = folded_edges(region);
        const long crossed_before = crossings_among(mesh_, region);
        mesh_.points[v] = x;
        long made = 0;
        for (int pass = 0; pass < 4; ++pass) {
            long pass_flips = 0;
            const std::vector<int> around = touched();
            for (int t : around)
                for (int j = 0; j < 3; ++j) pass_flips += try_flip(t, j, before, floor);
            made += pass_flips;
            if (pass_flips == 0) break;
        }
        const Measure after = measure(touched());
        for (int t : touched()) region.push_back(t);
        const bool ok = after.off <= before.off && folded_edges(region) <= folded_before &&
                        after.worst_kappa >= floor &&
                        after.farthest <= std::max(params_.tolerance, before.farthest) &&
                        crossings_among(mesh_, region) <= crossed_before;
        if (ok) {
            flips += made;
            return true;
        }
        mesh_.points[v] = was;
        for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) mesh_.set_tri(it->first, it->second);
        return false;
    }

private:
    struct Measure {
        double worst_kappa = 2.0;
        double farthest = 0.0;
        int off = 0; // triangles turned from the input by more than 60 degrees
    };

    // Whether t turns by more than 60 degrees from the input's triangle `nearest` to its centroid.
    bool is_off(const Tri& t, int32_t nearest) const {
        const Eigen::Vector3d n = mesh_.normal(t);
        const double norm = n.norm();
        return nearest < 0 || !(norm > 0.0) || !(n.dot(input_.triangle_normal(nearest)) >= cos_off_ * norm);
    }
    bool is_off(const Tri& t) const {
        return is_off(t, input_.closest((mesh_.points[t[0]] + mesh_.points[t[1]] + mesh_.points[t[2]]) / 3.0).triangle);
    }
    void add(Measure& m, const Tri& t) const {
        const TriangleNearInput near = triangle_near_input(mesh_, t, input_); // one query of the centroid for both
        m.worst_kappa = std::min(m.worst_kappa, mesh_.kappa(t));
        m.farthest = std::max(m.farthest, near.distance);
        m.off += is_off(t, near.nearest_to_centroid) ? 1 : 0;
    }
    Measure measure_saved() const {
        Measure m;
        for (const auto& [t, tri] : saved_) add(m, tri);
        return m;
    }
    Measure measure(const std::vector<int>& tris) const {
        Measure m;
        for (int t : tris) add(m, mesh_.tris[t]);
        return m;
    }

    // The edges of `tris` folded, each once (flip_rules.h). A move onto a knife edge may fold a
    // triangle of its fan onto one beyond it that no flip of the fan sees.
    int folded_edges(const std::vector<int>& tris) const {
        return folded_edges_among(mesh_, tris, [this](int32_t v) {
            const std::vector<int32_t>& fan = mesh_.fan(v);
            return std::make_pair(fan.data(), fan.data() + fan.size());
        });
    }

    // The triangles changed or moved so far in this snap.
    std::vector<int> touched() const {
        std::vector<int> out;
        for (const auto& s : saved_) out.push_back(s.first);
        return out;
    }
    void save(int t) {
        for (const auto& s : saved_)
            if (s.first == t) return;
        saved_.emplace_back(t, mesh_.tris[t]);
    }

    // A quality flip (EditableMesh::flip_improves_quality) of a pair the move left under the
    // floor, its new diagonal within the tolerance of the input (see the header).
    bool lifts_under_floor(const EditableMesh::Quad& q, double d_after, double floor) const {
        return std::min(mesh_.kappa(mesh_.tris[q.t1]), mesh_.kappa(mesh_.tris[q.t2])) < floor &&
               d_after <= params_.tolerance && mesh_.flip_improves_quality(q);
    }
    long try_flip(int t, int j, const Measure& before, double floor) {
        const auto q = mesh_.quad_at(t, j);
        if (!q || q->c == q->d || mesh_.joined(q->c, q->d)) return 0;
        const auto [d_before, d_after] = diagonal_distances(mesh_, *q, input_);
        if (!crease_flip_fits(mesh_, *q, d_before, d_after, params_.tolerance,
                              std::min(floor, before.worst_kappa)) &&
            !quality_flip_keeps_surface(mesh_, *q, d_before, d_after, params_.tolerance) &&
            !lifts_under_floor(*q, d_after, floor))
            return 0;
        const auto [n1, n2] = EditableMesh::flipped(*q);
        if (is_off(n1) || is_off(n2)) return 0;
        save(q->t1);
        save(q->t2);
        mesh_.set_tri(q->t1, n1);
        mesh_.set_tri(q->t2, n2);
        return 1;
    }

    EditableMesh mesh_;
    const AabbTree& input_;
    const CreaseSnapParams& params_;
    const double cos_off_;
    std::vector<std::pair<int, Tri>> saved_; // per triangle changed in this snap, what it was
};

bool bend_params_valid(const CreaseSnapParams& params) {
    return params.bend_turn_deg >= 0.0 && params.bend_turn_deg <= 180.0 && params.bend_distance >= 0.0 &&
           std::isfinite(params.bend_distance);
}

// Throws InvalidInput, naming the step, if an index or a parameter is out of range.
void check_snap(const Mesh& mesh, const Mesh& input, const CreaseSnapParams& params) {
    check_indices(mesh, "snapped mesh");
    check_indices(input, "input mesh");
    auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!positive(params.radius) || !positive(params.tolerance) || !(params.corner_radius >= 0.0) ||
        !(std::isnan(params.min_depth) || params.min_depth >= 0.0) ||
        !(params.min_turn_deg >= 0.0) || !(params.min_turn_deg <= 180.0) || !(params.kappa_floor >= 0.0) ||
        !(params.knife_kappa_floor >= 0.0) || !(params.knife_turn_deg >= 0.0) || !(params.knife_turn_deg <= 180.0) ||
        !(params.min_length >= 0.0) || !bend_params_valid(params))
        throw InvalidInput("snap_to_acute_creases: the radius and tolerance must be positive and finite, the corner "
                           "radius, depth, length and bend distance not negative (the last finite), the turns between 0 "
                           "and 180 degrees, the kappa floors not negative");
}

} // namespace

CreaseSnapStats snap_to_acute_creases(Mesh& mesh, const Reference& reference, const CreaseSnapParams& params) {
    check_snap(mesh, reference.mesh, params);
    return snap_to_acute_creases(
        mesh, reference, AcuteCreases(reference.mesh, params.min_turn_deg, 0.5 * params.radius, params.min_length), params);
}

CreaseSnapStats snap_to_acute_creases(Mesh& mesh, const Reference& reference, const AcuteCreases& creases,
                                      const CreaseSnapParams& params) {
    check_snap(mesh, reference.mesh, params);
    const AabbTree& input_tree = reference.tree;
    CreaseSnapStats stats;
    stats.creases = creases.size();
    if (creases.size() == 0 || mesh.triangles.rows() == 0) return stats;
    Snapper snapper(mesh, input_tree, params);
    // A vertex moves once: a second entry (near two corners, or a corner and a crease) holds a
    // target found from where it was.
    std::vector<char> moved(static_cast<size_t>(mesh.points.rows()), 0);
    // A crease vertex moves where the crease is cut deeper than min_depth; a corner's, with
    // min_depth given (the feature angle's creases), wherever it is not on the corner.
    const double depth = std::isnan(params.min_depth) ? params.tolerance : params.min_depth;
    const double corner_depth = std::isnan(params.min_depth) ? params.tolerance : 0.0;
    // Each corner of the creases first: the nearest vertex within corner_radius that can move
    // onto it, the next nearest where the nearest's move would spoil its triangles (a corner
    // whose nearest vertex belongs to another corner, or sits in a fan too poor to move).
    constexpr int kCornerCandidates = 4;
    for (const Eigen::Vector3d& c : creases.corners()) {
        const Eigen::VectorXd d2 = (mesh.points.rowwise() - c.transpose()).rowwise().squaredNorm();
        std::vector<std::pair<double, int32_t>> candidates;
        for (Eigen::Index v = 0; v < d2.size(); ++v)
            if (d2(v) <= params.corner_radius * params.corner_radius) candidates.emplace_back(d2(v), static_cast<int32_t>(v));
        std::sort(candidates.begin(), candidates.end());
        if (!candidates.empty() && candidates.front().first == 0.0) {
            moved[candidates.front().second] = 1; // a vertex on the corner already
            continue;
        }
        for (size_t k = 0; k < candidates.size() && k < kCornerCandidates; ++k) {
            const int32_t v = candidates[k].second;
            if (!moved[v] && snapper.snap(v, c, corner_depth, stats.flipped, params.kappa_floor)) {
                moved[v] = 1;
                ++stats.moved;
                break;
            }
        }
    }
    // Then the vertices near a crease, nearest first (then by index: deterministic).
    std::vector<std::tuple<double, int32_t, Eigen::Vector3d, long>> near; // distance, vertex, target, crease edge
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v) {
        const Eigen::Vector3d p = mesh.points.row(v).transpose();
        if (const auto x = creases.nearest(p, params.radius); x && (x->point - p).squaredNorm() > 0.0)
            near.emplace_back((x->point - p).norm(), static_cast<int32_t>(v), x->point, x->segment);
    }
    std::sort(near.begin(), near.end(),
              [](const auto& l, const auto& r) { return std::tie(std::get<0>(l), std::get<1>(l)) < std::tie(std::get<0>(r), std::get<1>(r)); });
    for (const auto& [distance, v, x, segment] : near) {
        if (!moved[v] && snapper.snap(v, x, depth, stats.flipped, params.kappa_floor_beside(creases.turn(segment)))) {
            moved[v] = 1;
            ++stats.moved;
        }
    }
    if (stats.moved > 0) snapper.mesh().write_to(mesh);
    return stats;
}

std::vector<AcuteCreases::Bend> bends_off_mesh_creases(const Mesh& mesh, const AcuteCreases& creases,
                                                       const CreaseSnapParams& params) {
    check_indices(mesh, "mesh");
    if (!bend_params_valid(params))
        throw InvalidInput("bends_off_mesh_creases: the bend's turn must be between 0 and 180 degrees, its distance "
                           "not negative and finite");
    std::vector<AcuteCreases::Bend> out;
    if (!(params.bend_distance > 0.0)) return out;
    const std::vector<AcuteCreases::Bend> bends = creases.bends(params.bend_turn_deg);
    if (bends.empty()) return out;
    const MeshCreases passing(mesh, params);
    for (const AcuteCreases::Bend& b : bends)
        if (passing.distance(b.point, params.bend_distance) > params.bend_distance) out.push_back(b);
    return out;
}

std::vector<Eigen::Vector3d> crease_gaps(const Mesh& mesh, const AcuteCreases& creases, const CreaseSnapParams& params) {
    check_indices(mesh, "mesh");
    if (!(params.bend_distance >= 0.0) || !std::isfinite(params.bend_distance) || !(params.gap_separation >= 0.0) ||
        !std::isfinite(params.gap_separation))
        throw InvalidInput("crease_gaps: the distance and the separation must be finite and not negative");
    std::vector<Eigen::Vector3d> out;
    if (!(params.bend_distance > 0.0) || !(params.gap_separation > 0.0) || creases.size() == 0) return out;
    const MeshCreases passing(mesh, params);
    // Distances past the separation all rank alike: farther than that, a point is listed first
    // whatever its distance.
    const double reach = std::max(params.bend_distance, params.gap_separation);
    // Only where another crease runs across from the point within twice that: a strip between
    // two creases, one of which the output's row stands for. Elsewhere the output's crease is a
    // chord across its own chain's bend (bends_off_mesh_creases).
    const double strip = 2.0 * reach;
    std::vector<std::pair<double, Eigen::Vector3d>> missed;
    for (long s = 0; s < creases.size(); ++s) {
        const auto& [a, b] = creases.segment(s);
        constexpr long kMostPieces = 100000; // as SegmentIndex's
        const long pieces = std::clamp(static_cast<long>(std::ceil((b - a).norm() / params.bend_distance)), 1L, kMostPieces);
        for (long i = 0; i <= pieces; ++i) {
            const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / static_cast<double>(pieces));
            if (const double d = passing.distance(p, reach);
                d > params.bend_distance && creases.distance_across(p, s, strip) <= strip)
                missed.emplace_back(std::min(d, reach), p);
        }
    }
    std::stable_sort(missed.begin(), missed.end(), [](const auto& l, const auto& r) { return l.first > r.first; });
    // The points listed, by cells of the separation's size: a point's neighbours within the
    // separation lie in the 27 cells round its own.
    const double cell = params.gap_separation;
    auto key = [&](const Eigen::Vector3d& p, int dx, int dy, int dz) {
        const auto c = [&](double x, int d) { return static_cast<uint64_t>(static_cast<int64_t>(std::floor(x / cell)) + d) & 0x1fffffu; };
        return (c(p.x(), dx) << 42) | (c(p.y(), dy) << 21) | c(p.z(), dz);
    };
    std::unordered_map<uint64_t, std::vector<int32_t>> cells;
    for (const auto& [distance, p] : missed) {
        bool crowded = false;
        for (int dx = -1; dx <= 1 && !crowded; ++dx)
            for (int dy = -1; dy <= 1 && !crowded; ++dy)
                for (int dz = -1; dz <= 1 && !crowded; ++dz)
                    if (const auto found = cells.find(key(p, dx, dy, dz)); found != cells.end())
                        crowded = std::any_of(found->second.begin(), found->second.end(),
                                              [&](int32_t k) { return (out[k] - p).norm() < params.gap_separation; });
        if (crowded) continue;
        cells[key(p, 0, 0, 0)].push_back(static_cast<int32_t>(out.size()));
        out.push_back(p);
    }
    return out;
}

} // namespace liftremesh
