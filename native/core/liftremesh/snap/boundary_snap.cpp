#include "liftremesh/snap/boundary_snap.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/neighbor_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <unordered_set>
#include <utility>

namespace liftremesh {

namespace {

using Edge = std::pair<int32_t, int32_t>;

Eigen::Vector3d position(const Mesh& m, int32_t v) { return m.points.row(v).transpose(); }

std::vector<Edge> boundary_edges(const Triangles& triangles) {
    std::vector<Edge> out;
    for (const EdgeCount& e : edge_counts(triangles))
        if (e.count == 1) out.emplace_back(e.a, e.b);
    return out;
}

struct Corner {
    int32_t vertex;
    double turn_deg; // 180 where the boundary does not simply pass through (not two edges)
};

// Corners of the boundary made of `edges` (see boundary_corners()), by increasing vertex index.
std::vector<Corner> find_corners(const Mesh& mesh, const std::vector<Edge>& edges, double angle_deg) {
    std::vector<std::vector<int32_t>> next(static_cast<size_t>(mesh.points.rows()));
    for (const auto& [a, b] : edges) {
        next[a].push_back(b);
        next[b].push_back(a);
    }
    std::vector<Corner> out;
    for (size_t v = 0; v < next.size(); ++v) {
        if (next[v].empty()) continue;
        if (next[v].size() != 2) {
            out.push_back({static_cast<int32_t>(v), 180.0});
            continue;
        }
        const Eigen::Vector3d p = position(mesh, static_cast<int32_t>(v));
        const Eigen::Vector3d in = p - position(mesh, next[v][0]), out_dir = position(mesh, next[v][1]) - p;
        if (!(in.norm() > 0.0 && out_dir.norm() > 0.0)) continue; // a zero-length edge has no direction
        const double turn = std::atan2(in.cross(out_dir).norm(), in.dot(out_dir)) * 180.0 / M_PI;
        if (turn > angle_deg) out.push_back({static_cast<int32_t>(v), turn});
    }
    return out;
}

void check_options(const BoundarySnapParams& o) {
    auto fail = [](const char* field, double value, const char* expected) {
        std::ostringstream message;
        message << "BoundarySnapParams." << field << " = " << value << ": expected " << expected;
        throw InvalidInput(message.str());
    };
    if (!(o.corner_angle_deg > 0.0 && o.corner_angle_deg < 180.0))
        fail("corner_angle_deg", o.corner_angle_deg, "an angle in (0, 180) degrees");
    if (!(o.reach > 0.0 && std::isfinite(o.reach))) fail("reach", o.reach, "a finite number > 0");
    if (!(o.min_area_ratio >= 0.0 && o.min_area_ratio < 1.0))
        fail("min_area_ratio", o.min_area_ratio, "a number in [0, 1)");
    if (!(o.min_kappa >= 0.0 && o.min_kappa < 1.0)) fail("min_kappa", o.min_kappa, "a number in [0, 1)");
}

// Moves of single output vertices, each kept only if no triangle around the vertex flips, loses
// more than the allowed share of its area or falls below the kappa floor, measured against the
// triangles as they were when the mover was made (the accepted moves of neighbours count).
class VertexMover {
public:
    VertexMover(Mesh& mesh, const std::vector<int32_t>& movable, const BoundarySnapParams& options)
        : mesh_(mesh), min_area_ratio_(options.min_area_ratio), min_kappa_(options.min_kappa),
          slot_(static_cast<size_t>(mesh.points.rows()), -1) {
        for (size_t i = 0; i < movable.size(); ++i) slot_[movable[i]] = static_cast<int32_t>(i);
        // Triangles around each movable vertex, and how each was at construction.
        std::vector<std::pair<int32_t, int32_t>> pairs; // (slot, triangle)
        const Triangles& t = mesh.triangles;
        for (Eigen::Index f = 0; f < t.rows(); ++f)
            for (int j = 0; j < 3; ++j)
                if (slot_[t(f, j)] >= 0) pairs.emplace_back(slot_[t(f, j)], static_cast<int32_t>(f));
        around_ = compress_rows(static_cast<long>(movable.size()), pairs);
        for (int32_t f : around_.values) {
            before_.push_back(doubled_normal(f));
            kappa_before_.push_back(kappa(f));
        }
    }

    //! Puts vertex v at `target` unless a triangle around it would flip, collapse or fall below
    //! the quality floor.
    bool try_move(int32_t v, const Eigen::Vector3d& target) {
        const int32_t s = slot_[v];
        const Eigen::Vector3d old = position(mesh_, v);
        mesh_.points.row(v) = target.transpose();
        for (int32_t k = around_.offsets[s]; k < around_.offsets[s + 1]; ++k) {
            const int32_t f = around_.values[k];
            const Eigen::Vector3d after = doubled_normal(f), &before = before_[k];
            const bool collapses = after.norm() < min_area_ratio_ * before.norm();
            const bool flips = before.squaredNorm() > 0.0 && after.dot(before) <= 0.0;
            const bool sliver = kappa(f) < std::min(min_kappa_, kappa_before_[k]);
            if (collapses || flips || sliver) {
                mesh_.points.row(v) = old.transpose();
                return false;
            }
        }
        return true;
    }

    //! The triangles around the movable vertex of slot s.
    const int32_t* begin(size_t s) const { return around_.begin(static_cast<long>(s)); }
    const int32_t* end(size_t s) const { return around_.end(static_cast<long>(s)); }

private:
    Eigen::Vector3d doubled_normal(int32_t f) const { // (b - a) x (c - a): twice the area, along the normal
        const Eigen::Vector3d a = position(mesh_, mesh_.triangles(f, 0));
        return (position(mesh_, mesh_.triangles(f, 1)) - a).cross(position(mesh_, mesh_.triangles(f, 2)) - a);
    }

    double kappa(int32_t f) const { // Eq. 26
        return triangle_kappa(position(mesh_, mesh_.triangles(f, 0)), position(mesh_, mesh_.triangles(f, 1)),
                              position(mesh_, mesh_.triangles(f, 2)));
    }

    Mesh& mesh_;
    double min_area_ratio_, min_kappa_;
    std::vector<int32_t> slot_;           // per vertex of the mesh: index in `movable`, or -1
    CompressedRows around_;               // per movable vertex (its slot): its triangles
    std::vector<Eigen::Vector3d> before_; // doubled normal of each listed triangle at construction
    std::vector<double> kappa_before_;    // and its kappa
};

// Nearest points on a set of segments. The segments are sampled at most `spacing` apart (the
// midpoints of equal pieces): the nearest sample, at distance m, bounds the distance d to the
// nearest segment by d <= m, and every segment at distance <= m has a sample within
// m + spacing / 2; the segments of the samples within that radius are tested exactly.
class SegmentSearch {
public:
    SegmentSearch(const Mesh& mesh, const std::vector<Edge>& segments, double spacing)
        : mesh_(mesh), segments_(segments) {
        double length = 0.0;
        for (const Edge& s : segments) length += (position(mesh, s.first) - position(mesh, s.second)).norm();
        spacing = segment_sample_spacing(length, spacing);
        half_spacing_ = 0.5 * spacing;
        std::vector<Eigen::Vector3d> samples;
        for (size_t i = 0; i < segments.size(); ++i) {
            const Eigen::Vector3d a = position(mesh, segments[i].first), b = position(mesh, segments[i].second);
            const long pieces = std::max(1L, static_cast<long>(std::ceil((b - a).norm() / spacing)));
            for (long k = 0; k < pieces; ++k) {
                samples.push_back(a + (b - a) * ((static_cast<double>(k) + 0.5) / static_cast<double>(pieces)));
                segment_of_.push_back(static_cast<int32_t>(i));
            }
        }
        LiftedPoints pts(static_cast<Eigen::Index>(samples.size()), 3);
        for (size_t i = 0; i < samples.size(); ++i) pts.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
        tree_ = std::make_unique<KdTree>(pts);
    }

    //! The nearest point on the segments to q if it lies within `radius`.
    bool nearest_within(const Eigen::Vector3d& q, double radius, Eigen::Vector3d& point) const {
        int32_t i;
        double m2;
        if (tree_->knn(q.data(), 1, &i, &m2) < 1) return false;
        const double m = std::sqrt(m2);
        if (m > radius + half_spacing_) return false; // every segment is farther than radius
        found_.clear();
        tree_->within(q.data(), m + half_spacing_, found_);
        candidates_.clear();
        for (int32_t sample : found_) candidates_.push_back(segment_of_[sample]);
        candidates_.push_back(segment_of_[i]); // found_ may miss it by rounding at the radius
        std::sort(candidates_.begin(), candidates_.end());
        candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
        double best = std::numeric_limits<double>::infinity();
        for (int32_t s : candidates_) { // increasing segment index: ties go to the first
            const Eigen::Vector3d p = closest_point_on_segment(q, position(mesh_, segments_[s].first),
                                                               position(mesh_, segments_[s].second));
            const double d2 = (p - q).squaredNorm();
            if (d2 < best) {
                best = d2;
                point = p;
            }
        }
        return best <= radius * radius;
    }

private:
    const Mesh& mesh_;
    const std::vector<Edge>& segments_;
    double half_spacing_;
    std::vector<int32_t> segment_of_; // per sample
    std::unique_ptr<KdTree> tree_;
    mutable std::vector<int32_t> found_, candidates_;
};

// The boundary vertices of the output with what the moves need to know about them.
struct OutputBoundary {
    struct DirectedEdge {
        int32_t a, b, triangle; // the boundary edge a -> b, as its triangle runs it
    };
    std::vector<int32_t> vertices;         // increasing index
    std::vector<double> reach;             // per vertex: options.reach x mean length of its boundary edges
    std::vector<Eigen::Vector3d> outward;  // per vertex: see below
    std::vector<DirectedEdge> directed;    // the boundary edges with their triangles
    std::unordered_set<std::uint64_t> is_boundary; // edge_key() of each boundary edge
    double max_reach = 0.0, mean_edge = 0.0;

    OutputBoundary(const Mesh& output, double reach_factor) {
        const std::vector<Edge> edges = boundary_edges(output.triangles);
        if (edges.empty()) return;
        std::vector<int32_t> slot(static_cast<size_t>(output.points.rows()), -1);
        for (const auto& [a, b] : edges)
            for (int32_t v : {a, b})
                if (slot[v] < 0) {
                    slot[v] = 0;
                    vertices.push_back(v);
                }
        std::sort(vertices.begin(), vertices.end());
        for (size_t i = 0; i < vertices.size(); ++i) slot[vertices[i]] = static_cast<int32_t>(i);
        reach.assign(vertices.size(), 0.0);
        std::vector<int> degree(vertices.size(), 0);
        for (const auto& [a, b] : edges) {
            const double length = (position(output, a) - position(output, b)).norm();
            mean_edge += length / static_cast<double>(edges.size());
            for (int32_t v : {a, b}) {
                reach[slot[v]] += length;
                ++degree[slot[v]];
            }
        }
        for (size_t i = 0; i < vertices.size(); ++i) {
            reach[i] *= reach_factor / degree[i];
            max_reach = std::max(max_reach, reach[i]);
        }
        // Outward: the sum of the unit normals of the vertex's boundary edges in the planes of
        // their triangles, pointing away from them. A triangle, counter-clockwise about its
        // normal n, lies left of its edge a -> b: outward is (b - a) x n.
        outward.assign(vertices.size(), Eigen::Vector3d::Zero());
        is_boundary.reserve(2 * edges.size());
        for (const auto& [a, b] : edges) is_boundary.insert(edge_key(a, b));
        for (Eigen::Index f = 0; f < output.triangles.rows(); ++f)
            for (int j = 0; j < 3; ++j) {
                const int32_t a = output.triangles(f, j), b = output.triangles(f, (j + 1) % 3);
                if (slot[a] < 0 || slot[b] < 0 || !is_boundary.count(edge_key(a, b))) continue;
                const Eigen::Vector3d n =
                    triangle_normal(corner(output, f, 0), corner(output, f, 1), corner(output, f, 2));
                directed.push_back({a, b, static_cast<int32_t>(f)});
                const Eigen::Vector3d out = (position(output, b) - position(output, a)).cross(n);
                const double length = out.norm();
                if (!(length > 0.0)) continue;
                outward[slot[a]] += out / length;
                outward[slot[b]] += out / length;
            }
    }

    //! #vertices by 3: where the boundary vertices are in `output` now, row i for vertices[i].
    LiftedPoints positions(const Mesh& output) const {
        LiftedPoints at(static_cast<Eigen::Index>(vertices.size()), 3);
        for (size_t i = 0; i < vertices.size(); ++i)
            at.row(static_cast<Eigen::Index>(i)) = output.points.row(vertices[i]);
        return at;
    }

    //! Whether a -> b or b -> a is a boundary edge.
    bool has_edge(int32_t a, int32_t b) const { return is_boundary.count(edge_key(a, b)) > 0; }

    //! The index of output vertex v in `vertices` (v must be a boundary vertex).
    size_t slot(int32_t v) const {
        return static_cast<size_t>(std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin());
    }

    //! Whether moving vertex i from `from` to `to` goes out of the output, towards input it does
    //! not cover yet. A move back into the output would uncover input its triangles cover now.
    bool goes_out(size_t i, const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
        return (to - from).dot(outward[i]) > 0.0;
    }
};

// Step 2b of snap_boundary(): removes the flaps among the vertices `beyond` (slots of those whose
// nearest point on the input's boundary lies back inside the output): a vertex in a single
// triangle whose other two vertices now lie on the input's boundary (within `on_boundary`) and
// whose edge between them has a triangle on its other side. Its site sat outside the surface,
// with a cell too small to pull it in; the triangle covers no input. Returns how many.
long remove_flaps(Mesh& output, const OutputBoundary& boundary, const VertexMover& mover, const SegmentSearch& search,
                  const std::vector<size_t>& beyond, double on_boundary) {
    std::vector<char> drop(static_cast<size_t>(output.triangles.rows()), 0);
    long removed = 0;
    Eigen::Vector3d unused;
    for (size_t i : beyond) {
        if (mover.end(i) - mover.begin(i) != 1) continue;
        const int32_t f = *mover.begin(i), v = boundary.vertices[i];
        int j = 0;
        while (output.triangles(f, j) != v) ++j;
        const int32_t x = output.triangles(f, (j + 1) % 3), y = output.triangles(f, (j + 2) % 3);
        if (boundary.has_edge(x, y)) continue; // held by its corners only: removing it would cut the surface
        if (search.nearest_within(position(output, x), on_boundary, unused) &&
            search.nearest_within(position(output, y), on_boundary, unused)) {
            drop[f] = 1;
            ++removed;
        }
    }
    if (removed == 0) return 0;
    drop_triangles(output, drop);
    remove_unreferenced_vertices(output);
    return removed;
}

// Step 3 of snap_boundary(): the corners step 1 could not match, with no output boundary vertex
// within reach, get a vertex of their own (see snap_boundary()). Returns how many.
long insert_corners(Mesh& output, const Mesh& input, const std::vector<Corner>& corners,
                    const OutputBoundary& boundary, double min_kappa, const AabbTree& input_tree) {
    long made = 0;
    if (corners.empty()) return made;
    // The new triangle on the input, within `tolerance`, at the points of a barycentric grid
    // of step 1/4 (its corners aside, which are the output's and the input's).
    auto on_input = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                        double tolerance) {
        for (int i = 0; i <= 4; ++i)
            for (int j = 0; i + j <= 4; ++j) {
                if (i == 4 || j == 4 || i + j == 0) continue;
                const Eigen::Vector3d q = (i * a + j * b + (4 - i - j) * c) / 4.0;
                if (input_tree.any_within(q, tolerance) < 0) return false;
            }
        return true;
    };
    // A corner farther than this many reaches from the edge is not one the output cut off
    // but one it does not have (a part lost at a coarse size): left alone, as in step 2.
    constexpr double kEarReach = 6.0;
    // The new triangle must lie this close to the input, in reaches (about edge lengths): the
    // tolerance of the crease-point insertion (hausdorff_refinement.h), as for a chord of a
    // curved border. Farther, it would bridge a gap to another part or a fold.
    constexpr double kOnInput = 0.15;
    // The new triangle's angle at the corner is about the corner's: with 20 degrees its kappa
    // is 0.57 at best (isosceles), with 10 degrees 0.32. Accepted down to half the quality
    // floor (0.15 by default: the isosceles triangle of 4.5 degrees), below which the corner
    // stays cut.
    const double min_ear_kappa = 0.5 * min_kappa;
    const LiftedPoints at = boundary.positions(output);
    const KdTree tree(at);
    std::vector<std::pair<int32_t, int32_t>> pairs; // (slot of an end, directed edge)
    for (size_t e = 0; e < boundary.directed.size(); ++e)
        for (int32_t v : {boundary.directed[e].a, boundary.directed[e].b})
            pairs.emplace_back(static_cast<int32_t>(boundary.slot(v)), static_cast<int32_t>(e));
    const CompressedRows edges_at = compress_rows(static_cast<long>(boundary.vertices.size()), pairs);
    std::vector<char> used(boundary.directed.size(), 0); // one new triangle per edge
    std::vector<int32_t> found;
    for (const Corner& c : corners) {
        const Eigen::Vector3d p = position(input, c.vertex);
        found.clear();
        tree.within(p.data(), kEarReach * boundary.max_reach, found);
        // A vertex within reach (one step 1 could not move, or one step 2 moved near the
        // corner): the corner is cut by less than an edge length, and stays so.
        if (std::any_of(found.begin(), found.end(),
                        [&](int32_t i) { return (at.row(i).transpose() - p).norm() <= boundary.reach[i]; }))
            continue;
        int32_t best_edge = -1;
        double best_kappa = min_ear_kappa;
        for (int32_t i : found)
            for (const int32_t* e = edges_at.begin(i); e != edges_at.end(i); ++e) {
                const auto& [a, b, f] = boundary.directed[*e];
                const Eigen::Vector3d pa = position(output, a), pb = position(output, b);
                const Eigen::Vector3d n =
                    triangle_normal(corner(output, f, 0), corner(output, f, 1), corner(output, f, 2));
                const double edge_reach = 0.5 * (boundary.reach[boundary.slot(a)] + boundary.reach[boundary.slot(b)]);
                if (used[*e] || (pb - pa).cross(n).dot(p - pa) <= 0.0 || // the corner beyond the edge
                    (closest_point_on_segment(p, pa, pb) - p).norm() > kEarReach * edge_reach ||
                    triangle_normal(pb, pa, p).dot(n) <= 0.0) // the new triangle not turned over
                    continue;
                const double kappa = triangle_kappa(pb, pa, p); // Eq. 26
                if (kappa > best_kappa && on_input(pb, pa, p, kOnInput * edge_reach)) {
                    best_kappa = kappa;
                    best_edge = *e;
                }
            }
        if (best_edge < 0) continue;
        const OutputBoundary::DirectedEdge& edge = boundary.directed[best_edge];
        const auto v = static_cast<int32_t>(output.points.rows());
        output.points.conservativeResize(v + 1, Eigen::NoChange);
        output.points.row(v) = p.transpose();
        output.triangles.conservativeResize(output.triangles.rows() + 1, Eigen::NoChange);
        // b -> a: the other way round to its neighbour.
        output.triangles.row(output.triangles.rows() - 1) << edge.b, edge.a, v;
        used[best_edge] = 1;
        ++made;
    }
    return made;
}

// Step 1 of snap_boundary(): each corner, sharpest first, onto the nearest free output boundary
// vertex within reach that can go there. Marks the vertices used in `placed`, leaves in `corners`
// those not matched (sharpest first); returns how many were.
long match_corners(const Mesh& output, const Mesh& input, std::vector<Corner>& corners, const OutputBoundary& boundary,
                   VertexMover& mover, std::vector<char>& placed) {
    std::stable_sort(corners.begin(), corners.end(),
                     [](const Corner& x, const Corner& y) { return x.turn_deg > y.turn_deg; });
    // Positions before any move, so that every candidate is measured from where it was.
    const LiftedPoints before = boundary.positions(output);
    const KdTree tree(before);
    long matched = 0;
    std::vector<int32_t> found;
    std::vector<std::pair<double, int32_t>> candidates;
    std::vector<Corner> unmatched;
    for (const Corner& c : corners) {
        const Eigen::Vector3d p = position(input, c.vertex);
        found.clear();
        tree.within(p.data(), boundary.max_reach, found);
        candidates.clear();
        for (int32_t i : found) {
            const Eigen::Vector3d from = before.row(i).transpose();
            const double d = (from - p).norm();
            if (!placed[i] && d <= boundary.reach[i] && boundary.goes_out(static_cast<size_t>(i), from, p))
                candidates.emplace_back(d, i);
        }
        std::sort(candidates.begin(), candidates.end());
        const auto taken = std::find_if(candidates.begin(), candidates.end(), [&](const auto& d_i) {
            return mover.try_move(boundary.vertices[d_i.second], p);
        });
        if (taken == candidates.end()) {
            unmatched.push_back(c);
            continue;
        }
        placed[taken->second] = 1;
        ++matched;
    }
    corners = std::move(unmatched);
    return matched;
}

} // namespace

std::vector<int32_t> boundary_corners(const Mesh& mesh, double angle_deg) {
    check_indices(mesh, "boundary_corners");
    if (!(angle_deg >= 0.0 && angle_deg < 180.0))
        throw InvalidInput("boundary_corners: angle_deg = " + std::to_string(angle_deg) +
                           ": expected an angle in [0, 180) degrees");
    std::vector<int32_t> out;
    for (const Corner& c : find_corners(mesh, boundary_edges(mesh.triangles), angle_deg)) out.push_back(c.vertex);
    return out;
}

BoundarySnapStats snap_boundary(Mesh& output, const Reference& reference, const BoundarySnapParams& options) {
    const Mesh& input = reference.mesh;
    check_options(options);
    check_indices(input, "snap_boundary input");
    check_indices(output, "snap_boundary output");
    BoundarySnapStats stats;
    const std::vector<Edge> input_edges = boundary_edges(input.triangles);
    if (input_edges.empty()) return stats; // closed input: nothing to snap to
    std::vector<Corner> corners = find_corners(input, input_edges, options.corner_angle_deg);
    stats.input_corners = static_cast<long>(corners.size());
    const OutputBoundary boundary(output, options.reach);
    if (boundary.vertices.empty()) return stats;
    VertexMover mover(output, boundary.vertices, options);
    std::vector<char> placed(boundary.vertices.size(), 0);
    stats.corners_matched = match_corners(output, input, corners, boundary, mover, placed);

    // Step 2: every other boundary vertex onto its nearest point of the input's boundary. The
    // sample spacing only trades tree size against candidates per query (the answer is exact):
    // half the mean output boundary edge, and at most ~8 samples per boundary edge or vertex.
    double input_length = 0.0;
    for (const auto& [a, b] : input_edges) input_length += (position(input, a) - position(input, b)).norm();
    const double spacing = std::max(
        0.5 * boundary.mean_edge,
        input_length / (8.0 * static_cast<double>(input_edges.size() + boundary.vertices.size())));
    if (!(spacing > 0.0)) return stats; // all boundary edges have zero length: no direction to go
    const SegmentSearch search(input, input_edges, spacing);
    std::vector<size_t> beyond; // slots of the vertices whose nearest boundary point lies inward
    const double on_boundary = 1e-9 * boundary.mean_edge; // distances below this are rounding
    for (size_t i = 0; i < boundary.vertices.size(); ++i) {
        if (placed[i]) continue;
        const Eigen::Vector3d q = position(output, boundary.vertices[i]);
        Eigen::Vector3d target = q;
        if (!search.nearest_within(q, boundary.reach[i], target) || target == q) continue;
        if (!boundary.goes_out(i, q, target)) {
            if ((target - q).norm() > on_boundary) beyond.push_back(i); // not a rounding error
            continue;
        }
        if (mover.try_move(boundary.vertices[i], target))
            ++stats.vertices_snapped;
        else
            ++stats.moves_refused;
    }

    stats.flaps_removed = remove_flaps(output, boundary, mover, search, beyond, on_boundary);

    // Step 3: the corners step 1 left, each given a vertex of its own where the boundary, as the
    // moves left it, passes it by.
    if (!corners.empty())
        stats.corners_inserted = insert_corners(output, input, corners, OutputBoundary(output, options.reach),
                                                options.min_kappa, reference.tree);
    return stats;
}

} // namespace liftremesh
