#include "liftremesh/polish/quality_polish.h"

#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace liftremesh {

namespace {

// A quad whose two triangles turn by less than this (cosine of 5 degrees) is not weighed for a
// chord flip, which measures two distances. A chord lying s below a surface its other two
// vertices are on, each within t of it, turns its triangles by about 2 atan(s / t): over 10
// degrees for s of half the tolerance (0.075 h) and t up to 0.8 h.
constexpr double kChordMinTurnCos = 0.99619469809174553;

// Passes of fold, chord and quality flips (the fold rule asks for turns over 90 degrees, the
// quality rule under 30: never both), the first over the edges of the triangles flagged in
// `around`, each next one over those of the triangles the last one changed. Returns the flips;
// counts the folds undone.
long flip_passes(EditableMesh& mesh, const AabbTree& input, double tolerance, int passes, std::vector<char> around,
                 long& unfolded) {
    long total = 0;
    std::vector<char> changed;
    auto accept = [&](const EditableMesh::Quad& q) {
        if (fold_flip_fits_input(mesh, q, input, tolerance)) {
            ++unfolded;
            return true;
        }
        // A chord across a curved surface (the wall of a hole, a fillet) whose midpoint lies over
        // half the tolerance off it, where the other diagonal runs along the surface and lies at
        // most half as far (chord_flip_fits_input). The quality flips never take it back: they
        // may not give a diagonal more than half the tolerance off the input, nor farther than
        // the old one.
        const Eigen::Vector3d n1 = mesh.normal(mesh.tris[q.t1]), n2 = mesh.normal(mesh.tris[q.t2]);
        if (n1.dot(n2) < kChordMinTurnCos * n1.norm() * n2.norm()) {
            const auto [before, after] = diagonal_distances(mesh, q, input);
            if (chord_flip_fits_input(mesh, q, before, after, input, tolerance)) return true;
            return quality_flip_keeps_surface(mesh, q, before, after, tolerance);
        }
        return quality_flip_keeps_surface(mesh, q, input, tolerance);
    };
    for (int pass = 0; pass < passes; ++pass) {
        const long flips = mesh.flip_pass_around(around, accept, changed);
        total += flips;
        if (flips == 0) break;
        around.swap(changed);
    }
    return total;
}

// The caps' pass (see the header), over the edges opposite an angle of 150 degrees or more:
// one is flipped when cap_flip_fits_input allows it and neither new triangle turns by more than
// 120 degrees from the cap's neighbour it now borders (else the cap stood for a face narrower
// than the edge length, the rim of a thin plate). Returns the flips.
long flip_caps(EditableMesh& mesh, const AabbTree& input, double tolerance) {
    std::vector<uint64_t> keys;
    for (const EditableMesh::Tri& t : mesh.tris)
        for (int j = 0; j < 3; ++j) {
            const Eigen::Vector3d u = mesh.points[t[(j + 1) % 3]] - mesh.points[t[j]];
            const Eigen::Vector3d v = mesh.points[t[(j + 2) % 3]] - mesh.points[t[j]];
            if (u.dot(v) <= kCosCap * u.norm() * v.norm()) keys.push_back(edge_key(t[(j + 1) % 3], t[(j + 2) % 3]));
        }
    if (keys.empty()) return 0; // the edges' uses are made only where there is a cap
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    const auto uses = mesh.edge_uses();
    keys.erase(std::remove_if(keys.begin(), keys.end(), [&](uint64_t k) { return uses.at(k).size() != 2; }), keys.end());
    std::vector<char> flipped;
    const double cos_fold = -0.5; // 120 degrees
    auto accept = [&](const EditableMesh::Quad& q) {
        if (!cap_flip_fits_input(mesh, q, input, tolerance)) return false;
        const auto [n1, n2] = EditableMesh::flipped(q);
        // The cap's other two edges: each now borders n1 or n2, across from the cap's neighbour.
        for (const EditableMesh::Tri* n : {&n1, &n2})
            for (int j = 0; j < 3; ++j) {
                const int32_t u = (*n)[j], w = (*n)[(j + 1) % 3];
                if (edge_key(u, w) == edge_key(q.c, q.d)) continue;
                const auto found = uses.find(edge_key(u, w));
                if (found == uses.end()) continue;
                for (int k = 0; k < static_cast<int>(found->second.size()) && k < 2; ++k) {
                    const int other = found->second[k].tri;
                    if (other == q.t1 || other == q.t2) continue;
                    if (flipped[static_cast<size_t>(other)]) return false; // changed in this pass: weighed in the next
                    const Eigen::Vector3d a = mesh.normal(*n), b = mesh.normal(mesh.tris[static_cast<size_t>(other)]);
                    if (!(a.dot(b) > cos_fold * a.norm() * b.norm())) return false;
                }
            }
        return true;
    };
    return mesh.flip_pass(uses, keys, {}, accept, flipped);
}

class Relaxation {
public:
    // The fans and the border, made once: moving vertices does not change the triangles.
    Relaxation(EditableMesh& mesh, const AabbTree& input, const QualityPolishParams& params)
        : mesh_(mesh), input_(input), params_(params), cos_flat_(std::cos(params.flat_angle_deg * M_PI / 180.0)),
          on_border_(mesh.border_points()), fans_(mesh.fans()) {}

    // One pass over the vertices of the bad triangles, in index order; flags the moved ones.
    long pass(std::vector<char>& moved) {
        const size_t nv = mesh_.points.size();
        std::vector<char> candidate(nv, 0);
        for (const EditableMesh::Tri& t : mesh_.tris)
            if (mesh_.kappa(t) < params_.relax_below)
                for (int32_t v : t) candidate[v] = !on_border_[v];
        for (size_t v = 0; v < nv; ++v)
            if (!candidate[v] && !on_border_[v] && fan_has_turned(static_cast<int32_t>(v))) candidate[v] = 1;
        long count = 0;
        for (size_t v = 0; v < nv; ++v)
            if (candidate[v] && relax(static_cast<int32_t>(v))) {
                moved[v] = 1;
                ++count;
            }
        return count;
    }

private:
    // The worst kappa of v's fan, or -1 if a triangle turned by more than 30 degrees from `was`.
    double fan_worst(int32_t v, const std::vector<Eigen::Vector3d>& was) const {
        double worst = 2.0;
        size_t i = 0;
        for (const int32_t* t = fans_.begin(v); t != fans_.end(v); ++t, ++i) {
            const EditableMesh::Tri& tri = mesh_.tris[*t];
            if (!EditableMesh::turns_little(mesh_.normal(tri), was[i])) return -1.0;
            worst = std::min(worst, mesh_.kappa(tri));
        }
        return worst;
    }

    // Whether a triangle of v's fan faces against the others, lying in their plane (turned over
    // on it: the triangles overlap).
    bool fan_has_turned(int32_t v) const {
        Eigen::Vector3d plane = Eigen::Vector3d::Zero();
        for (const int32_t* t = fans_.begin(v); t != fans_.end(v); ++t) plane += mesh_.normal(mesh_.tris[*t]).normalized();
        if (!(plane.norm() > 0.0)) return false;
        plane.normalize();
        for (const int32_t* t = fans_.begin(v); t != fans_.end(v); ++t)
            if (turned(mesh_.normal(mesh_.tris[*t]).normalized().dot(plane))) return true;
        return false;
    }

    // A normal at this cosine to the fan's plane is turned over onto it (not within the flat
    // angle of it, but of its opposite).
    bool turned(double along) const { return !(along >= cos_flat_) && along <= -cos_flat_; }

    bool relax(int32_t v) {
        const Eigen::Vector3d p = mesh_.points[v];
        std::vector<Eigen::Vector3d> was;
        Eigen::Vector3d plane = Eigen::Vector3d::Zero(); // the fan's mean normal
        for (const int32_t* t = fans_.begin(v); t != fans_.end(v); ++t) {
            was.push_back(mesh_.normal(mesh_.tris[*t]));
            plane += was.back().normalized();
        }
        if (was.size() < 3 || !(plane.norm() > 0.0)) return false;
        plane.normalize();
        // A triangle turned over in the fan's plane (fan_has_turned) must come out facing as the
        // others do: its normal is expected along the plane's, and until it does, the fan's worst
        // is below every kappa (fan_worst).
        std::vector<char> is_turned(was.size(), 0); // in the fan's order, as `was`
        bool any_turned = false;
        for (size_t i = 0; i < was.size(); ++i) {
            Eigen::Vector3d& n = was[i];
            const double along = n.normalized().dot(plane);
            if (turned(along)) {
                n = plane * n.norm();
                is_turned[i] = 1;
                any_turned = true;
            } else if (!(along >= cos_flat_)) {
                return false; // a crease or a strong bend (or NaN)
            }
        }
        // The triangles turned over are those facing against the input, not the others: the
        // input faces the plane's way at most of the others' centroids (at a vertex itself, on a
        // crease, the nearest input triangle may lie on the other face).
        if (any_turned) {
            int agree = 0, others = 0;
            size_t i = 0;
            for (const int32_t* t = fans_.begin(v); t != fans_.end(v); ++t, ++i) {
                if (is_turned[i]) continue;
                const EditableMesh::Tri& tri = mesh_.tris[*t];
                ++others;
                const Eigen::Vector3d centroid =
                    (mesh_.points[tri[0]] + mesh_.points[tri[1]] + mesh_.points[tri[2]]) / 3.0;
                const int32_t under = input_.closest(centroid).triangle;
                agree += under >= 0 && input_.triangle_normal(under).dot(plane) > 0.0;
            }
            if (!(2 * agree > others)) return false;
        }
        auto in_plane = [&](const Eigen::Vector3d& d) -> Eigen::Vector3d { return d - plane * d.dot(plane); };

        std::vector<Eigen::Vector3d> targets;
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (const int32_t* t = fans_.begin(v); t != fans_.end(v); ++t) {
            const EditableMesh::Tri& tri = mesh_.tris[*t];
            const int j = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
            const Eigen::Vector3d a = mesh_.points[tri[(j + 1) % 3]], b = mesh_.points[tri[(j + 2) % 3]];
            centroid += a + b; // each neighbour of an inner vertex is in two triangles of its fan
            if (!(mesh_.kappa(tri) < params_.relax_below)) continue;
            // The apex of the equilateral triangle on a-b, on v's side, in the fan's plane.
            const Eigen::Vector3d mid = 0.5 * (a + b), along = (b - a).normalized();
            const Eigen::Vector3d up = in_plane((p - mid) - along * (p - mid).dot(along));
            if (!(up.norm() > 0.0)) continue;
            const Eigen::Vector3d apex = mid + up.normalized() * (b - a).norm() * std::sqrt(3.0) / 2.0;
            for (double s : {0.25, 0.5, 0.75}) targets.push_back(p + s * (apex - p));
        }
        centroid /= static_cast<double>(2 * was.size());
        targets.insert(targets.begin(), p + in_plane(centroid - p));

        double best = fan_worst(v, was);
        Eigen::Vector3d chosen = p;
        for (const Eigen::Vector3d& target : targets) {
            mesh_.points[v] = input_.closest(target).point;
            if (const double worst = fan_worst(v, was); worst > best + 1e-9) {
                best = worst;
                chosen = mesh_.points[v];
            }
        }
        mesh_.points[v] = chosen;
        return chosen != p;
    }

    EditableMesh& mesh_;
    const AabbTree& input_;
    const QualityPolishParams& params_;
    const double cos_flat_;
    std::vector<char> on_border_; // an end of an edge without exactly two triangles
    CompressedRows fans_;         // vertex -> its triangles
};

void check_polish(const Mesh& mesh, const QualityPolishParams& params) {
    check_indices(mesh, "polished mesh");
    if (!(params.tolerance > 0.0) || !std::isfinite(params.tolerance) || params.flip_passes < 0 ||
        params.relax_passes < 0)
        throw InvalidInput("polish_quality: the tolerance must be positive and finite, the passes not negative");
}

// Per triangle of `mesh`, whether one of its corners is flagged in `at` (#V flags).
std::vector<char> triangles_at(const EditableMesh& mesh, const std::vector<char>& at) {
    std::vector<char> around(mesh.tris.size(), 0);
    for (size_t t = 0; t < mesh.tris.size(); ++t)
        for (int32_t v : mesh.tris[t]) around[t] = around[t] || at[v];
    return around;
}

} // namespace

QualityPolishStats polish_quality(Mesh& mesh, const Reference& reference, const QualityPolishParams& params) {
    const AabbTree& input = reference.tree;
    check_polish(mesh, params);
    EditableMesh editable(mesh);
    QualityPolishStats stats;
    stats.flipped = flip_caps(editable, input, params.tolerance);
    stats.flipped += flip_passes(editable, input, params.tolerance, params.flip_passes,
                                std::vector<char>(editable.tris.size(), 1), stats.unfolded);
    std::vector<char> moved(editable.points.size(), 0);
    Relaxation relaxation(editable, input, params);
    for (int pass = 0; pass < params.relax_passes; ++pass) {
        const long count = relaxation.pass(moved);
        stats.moved += count;
        if (count == 0) break;
    }
    if (stats.moved > 0)
        stats.flipped += flip_passes(editable, input, params.tolerance, params.flip_passes,
                                     triangles_at(editable, moved), stats.unfolded);
    if (stats.flipped > 0 || stats.moved > 0) editable.write_to(mesh);
    return stats;
}

long flip_around(Mesh& mesh, const Reference& reference, const QualityPolishParams& params,
                 const std::vector<int32_t>& vertices) {
    check_polish(mesh, params);
    if (vertices.empty()) return 0;
    std::vector<char> at(static_cast<size_t>(mesh.points.rows()), 0);
    for (const int32_t v : vertices) {
        if (v < 0 || v >= mesh.points.rows()) throw InvalidInput("flip_around: a vertex index is out of range");
        at[static_cast<size_t>(v)] = 1;
    }
    EditableMesh editable(mesh);
    long unfolded = 0;
    const long flipped =
        flip_passes(editable, reference.tree, params.tolerance, params.flip_passes, triangles_at(editable, at), unfolded);
    if (flipped > 0) editable.write_to(mesh);
    return flipped;
}

} // namespace liftremesh
