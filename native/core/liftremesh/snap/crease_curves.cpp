#include "liftremesh/snap/crease_curves.h"

#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/edit/flip_rules.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {

// The creases of the input as chains: each vertex's crease neighbours, and the curve through
// them (see the header).
class CreaseCurves {
public:
    CreaseCurves(const Mesh& input, const AcuteCreases& creases, const CreaseCurveParams& params)
        : input_(input), cos_smooth_(std::cos(params.smooth_turn_deg * M_PI / 180.0)),
          max_ratio_(params.max_chord_ratio) {
        std::vector<std::pair<int32_t, int32_t>> pairs;
        for (long s = 0; s < creases.size(); ++s) {
            const auto& [a, b] = creases.ends(s);
            pairs.emplace_back(a, b);
            pairs.emplace_back(b, a);
        }
        next_ = compress_rows(input.points.rows(), pairs);
    }

    // The curve's point at t in [0, 1] along the chord (p, q): the cubic Hermite curve with the
    // unit tangents at its ends times the length that makes it a circle's arc where the two
    // tangents and the chord are a circle's (4 r tan(alpha / 4), alpha the angle between the
    // tangents, r the radius: L = 2 r sin(alpha / 2) for the chord); the chord's length where
    // they are parallel.
    Eigen::Vector3d at(int32_t p, int32_t q, double t) const {
        const Eigen::Vector3d x0 = point(p), x1 = point(q);
        const Eigen::Vector3d u0 = tangent(p, q), u1 = -tangent(q, p);
        const double alpha = std::acos(std::clamp(u0.dot(u1), -1.0, 1.0));
        const double length = (x1 - x0).norm() * (alpha > 1e-6 ? 2.0 * std::tan(0.25 * alpha) / std::sin(0.5 * alpha) : 1.0);
        const Eigen::Vector3d m0 = length * u0, m1 = length * u1;
        const double t2 = t * t, t3 = t2 * t;
        return (2.0 * t3 - 3.0 * t2 + 1.0) * x0 + (t3 - 2.0 * t2 + t) * m0 + (3.0 * t2 - 2.0 * t3) * x1 + (t3 - t2) * m1;
    }

private:
    Eigen::Vector3d point(int32_t v) const { return input_.points.row(v).transpose(); }

    // The other neighbour a of p on its chain beyond the chord (p, q), if p lies inside a smooth
    // curve there: p has two crease neighbours, the chain turns at p by less than the smooth
    // turn, and the chords (a, p) and (p, q) are about as long as each other. Else -1.
    int32_t smooth_beyond(int32_t p, int32_t q) const {
        if (next_.end(p) - next_.begin(p) != 2) return -1;
        const int32_t a = next_.begin(p)[0] == q ? next_.begin(p)[1] : next_.begin(p)[0];
        if (a == q) return -1;
        const Eigen::Vector3d in = point(p) - point(a), out = point(q) - point(p);
        const double d0 = in.norm(), d1 = out.norm();
        if (!(d0 > 0.0 && d1 > 0.0) || std::max(d0, d1) > max_ratio_ * std::min(d0, d1)) return -1;
        return in.dot(out) > cos_smooth_ * d0 * d1 ? a : -1;
    }

    // The curve's unit tangent at p on the chord (p, q), towards q: the parabola's through
    // (a, p, q) at p if p lies inside a smooth curve (Bessel's), else the parabola's through
    // (p, q, r) at p if q does, else the chord's direction (a straight chord between corners).
    Eigen::Vector3d tangent(int32_t p, int32_t q) const {
        const Eigen::Vector3d x = point(p), y = point(q);
        const double d1 = (y - x).norm();
        Eigen::Vector3d m = y - x;
        if (const int32_t a = smooth_beyond(p, q); a >= 0) {
            const double d0 = (x - point(a)).norm();
            m = d1 / (d0 + d1) * (x - point(a)) / d0 + d0 / (d0 + d1) * (y - x) / d1;
        } else if (const int32_t r = smooth_beyond(q, p); r >= 0) {
            const double d2 = (point(r) - y).norm();
            const Eigen::Vector3d first = (y - x) / d1, second = ((point(r) - y) / d2 - first) / (d1 + d2);
            m = first - d1 * second;
        }
        return m.normalized();
    }

    const Mesh& input_;
    double cos_smooth_ = 1.0, max_ratio_ = 1.0;
    CompressedRows next_;
};

void check_params(const CreaseCurveParams& params) {
    if (!(params.near >= 0.0) || !(params.max_move >= 0.0) || !(params.min_length >= 0.0) ||
        !(params.smooth_turn_deg > 0.0 && params.smooth_turn_deg < 90.0) || !(params.max_chord_ratio >= 1.0) ||
        !std::isfinite(params.near) || !std::isfinite(params.max_move))
        throw InvalidInput("move_onto_crease_curves: a parameter is out of range");
}

} // namespace

CreaseCurveStats move_onto_crease_curves(Mesh& mesh, const Mesh& input, const CreaseCurveParams& params) {
    check_params(params);
    if (params.near == 0.0 || params.max_move == 0.0 || mesh.triangles.rows() == 0) return {};
    // Sampled every ten reaches: a few samples a chord.
    return move_onto_crease_curves(mesh, input, AcuteCreases(input, params.min_turn_deg, 10.0 * params.near, params.min_length),
                                   params);
}

CreaseCurveStats move_onto_crease_curves(Mesh& mesh, const Mesh& input, const AcuteCreases& creases,
                                         const CreaseCurveParams& params) {
    check_params(params);
    CreaseCurveStats stats;
    if (params.near == 0.0 || params.max_move == 0.0 || mesh.triangles.rows() == 0) return stats;
    stats.creases = creases.size();
    if (creases.size() == 0) return stats;
    const CreaseCurves curves(input, creases, params);

    const CompressedRows fans = vertex_triangles(mesh);
    auto vertices = [&mesh](long f) { return triangle_vertices(mesh, f); };
    auto unit_normal = [&](long f) { return triangle_normal(corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2)); };
    auto kappa = [&](long f) { return triangle_kappa(corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2)); };
    // The triangles a fan's may cross, from a tree of the mesh as it was: no vertex moves
    // farther than max_move, so a box grown by that finds every one.
    const AabbTree tree(mesh);
    std::vector<int32_t> near_triangles;
    auto crossings = [&](Eigen::Index v) {
        long count = 0;
        for (const int32_t* f = fans.begin(v); f != fans.end(v); ++f) {
            const std::array<int32_t, 3> fi = vertices(*f);
            const std::array<Eigen::Vector3d, 3> fc = {corner(mesh, *f, 0), corner(mesh, *f, 1), corner(mesh, *f, 2)};
            const Eigen::Vector3d grow = Eigen::Vector3d::Constant(params.max_move);
            near_triangles.clear();
            tree.triangles_meeting_box(fc[0].cwiseMin(fc[1]).cwiseMin(fc[2]) - grow, fc[0].cwiseMax(fc[1]).cwiseMax(fc[2]) + grow,
                                       near_triangles);
            for (int32_t g : near_triangles) {
                if (g == *f) continue;
                const std::array<int32_t, 3> gi = vertices(g);
                count += triangles_cross(fi, fc, gi, {corner(mesh, g, 0), corner(mesh, g, 1), corner(mesh, g, 2)});
            }
        }
        return count;
    };
    // The edges of v's fan folded shut: a triangle of the fan turned by less than 30 degrees
    // still folds onto the one across a knife edge (a 151-degree edge turned by 20 more).
    auto folded_round = [&](Eigen::Index v) {
        return count_folded_edges(
            fans.row(v), vertices, unit_normal, [&fans](int32_t w) { return fans.row(w); });
    };
    const double cos_turn = std::cos(30.0 * M_PI / 180.0);
    std::vector<Eigen::Vector3d> normals_before;
    for (Eigen::Index v = 0; v < mesh.points.rows(); ++v) {
        if (fans.begin(v) == fans.end(v)) continue;
        const Eigen::Vector3d x = mesh.points.row(v).transpose();
        // The nearest crease chord within reach, and the curve's point at the vertex's place along it.
        const std::optional<AcuteCreases::Nearest> chord = creases.nearest(x, params.near);
        if (!chord) continue;
        const auto& [a, b] = creases.ends(chord->segment);
        Eigen::Vector3d y = curves.at(a, b, chord->t);
        const double move = (y - x).norm();
        if (!(move > 0.0)) continue;
        if (move > params.max_move) y = x + (params.max_move / move) * (y - x);
        // The fan as it was: its normals, its worst kappa, the triangles it crosses.
        normals_before.clear();
        double worst_before = std::numeric_limits<double>::infinity();
        for (const int32_t* f = fans.begin(v); f != fans.end(v); ++f) {
            normals_before.push_back(unit_normal(*f));
            worst_before = std::min(worst_before, kappa(*f));
        }
        const long crossed_before = crossings(v);
        const int folded_before = folded_round(v);
        mesh.points.row(v) = y.transpose();
        bool keep = true;
        double worst_after = std::numeric_limits<double>::infinity();
        for (const int32_t* f = fans.begin(v); f != fans.end(v) && keep; ++f) {
            keep = unit_normal(*f).dot(normals_before[f - fans.begin(v)]) >= cos_turn;
            worst_after = std::min(worst_after, kappa(*f));
        }
        // Off the input's chords, a vertex can meet another part of the surface that touches
        // this one along the crease (two housings of a connector).
        keep = keep && worst_after >= std::min(params.kappa_floor, worst_before) && folded_round(v) <= folded_before &&
               crossings(v) <= crossed_before;
        if (keep)
            ++stats.moved;
        else
            mesh.points.row(v) = x.transpose();
    }
    return stats;
}

} // namespace liftremesh
