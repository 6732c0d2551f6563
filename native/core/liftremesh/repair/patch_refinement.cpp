#include "liftremesh/repair/patch_refinement.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/editable_mesh.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <vector>

namespace liftremesh {

namespace {

using Tri = EditableMesh::Tri;

// The patch triangles (from `first` on) under edit; the triangles before stay as they are.
class Patch {
public:
    Patch(const Mesh& mesh, Eigen::Index first) : mesh_(mesh, first), first_added_(static_cast<int32_t>(mesh.points.rows())) {
        for (Eigen::Index f = 0; f < first; ++f)
            for (int j = 0; j < 3; ++j) outside_.insert(edge_key(mesh.triangles(f, j), mesh.triangles(f, (j + 1) % 3)));
    }

    // Splits the edges two patch triangles share that are longer than 4/3 h where no edge
    // from the midpoint to an opposite vertex would be shorter than 4/5 h, or longer than h / 2
    // and opposite an angle above 120 degrees (a sliver's long side), longest first; a triangle
    // is split once a round. Returns whether any edge was split. The 4/5 h is isotropic
    // remeshing's collapse bound (Botsch and Kobbelt): a hole of the mesh's own size, such as a
    // quad whose diagonal is a little over 4/3 h, keeps its two triangles rather than gaining a
    // vertex a remesher would collapse again. Nor is an edge split whose two triangles turn by
    // more than 30 degrees: a patch folded there (a hole across a knife edge, whose loop runs
    // down both faces) has its midpoint off both, inside the wedge, where no later step puts it
    // back on the input.
    bool split_long_edges(double h, long max_added) {
        std::vector<std::pair<double, uint64_t>> candidates;
        const auto uses = mesh_.edge_uses();
        for (const auto& [key, use] : uses) {
            if (use.size() != 2) continue;
            if (!EditableMesh::turns_little(mesh_.normal(mesh_.tris[use[0].tri]), mesh_.normal(mesh_.tris[use[1].tri])))
                continue;
            const Tri& t = mesh_.tris[use[0].tri];
            const int32_t a = t[use[0].j], b = t[(use[0].j + 1) % 3];
            const double length = (mesh_.points[b] - mesh_.points[a]).norm();
            const bool obtuse = opposite_cos(use[0]) < -0.5 || opposite_cos(use[1]) < -0.5;
            const Eigen::Vector3d mid = 0.5 * (mesh_.points[a] + mesh_.points[b]);
            const bool apart = (opposite(use[0]) - mid).norm() >= 0.8 * h && (opposite(use[1]) - mid).norm() >= 0.8 * h;
            if ((length > 4.0 / 3.0 * h && apart) || (obtuse && length > 0.5 * h)) candidates.emplace_back(-length, key);
        }
        std::sort(candidates.begin(), candidates.end()); // longest first, then by key: deterministic
        std::vector<char> touched(mesh_.tris.size(), 0);
        bool any = false;
        for (const auto& [negative_length, key] : candidates) {
            const auto& use = uses.at(key);
            if (touched[use[0].tri] || touched[use[1].tri]) continue;
            if (added() >= max_added) break;
            const auto quad = mesh_.quad_of(use);
            if (!quad) continue;
            mesh_.split_edge(*quad, 0.5 * (mesh_.points[quad->a] + mesh_.points[quad->b]));
            touched[quad->t1] = touched[quad->t2] = 1;
            touched.resize(mesh_.tris.size(), 1);
            any = true;
        }
        return any;
    }

    // Flips shared patch edges while a flip raises the smaller kappa of its two triangles.
    void flip_edges() {
        std::vector<char> flipped;
        for (int pass = 0; pass < 20; ++pass) {
            const auto uses = mesh_.edge_uses();
            std::vector<uint64_t> keys;
            for (const auto& [key, use] : uses)
                if (use.size() == 2) keys.push_back(key);
            std::sort(keys.begin(), keys.end());
            auto better = [&](const EditableMesh::Quad& q) { return mesh_.flip_improves_quality(q); };
            if (mesh_.flip_pass(uses, keys, outside_, better, flipped) == 0) break;
        }
    }

    // Moves each added vertex to the average of its neighbours, unless that turns one of its
    // triangles by more than 30 degrees or makes one degenerate.
    void smooth(int sweeps) {
        std::vector<Eigen::Vector3d>& points = mesh_.points;
        const std::vector<Tri>& tris = mesh_.tris;
        const auto added = static_cast<size_t>(static_cast<int32_t>(points.size()) - first_added_);
        if (added == 0) return;
        std::vector<std::vector<int>> incident(added);
        std::vector<std::unordered_set<int32_t>> ring(added);
        for (size_t f = 0; f < tris.size(); ++f)
            for (int j = 0; j < 3; ++j) {
                const int32_t v = tris[f][j];
                if (v < first_added_) continue;
                incident[v - first_added_].push_back(static_cast<int>(f));
                ring[v - first_added_].insert(tris[f][(j + 1) % 3]);
                ring[v - first_added_].insert(tris[f][(j + 2) % 3]);
            }
        for (int sweep = 0; sweep < sweeps; ++sweep)
            for (size_t i = 0; i < added; ++i) {
                if (ring[i].empty()) continue;
                std::vector<int32_t> around(ring[i].begin(), ring[i].end());
                std::sort(around.begin(), around.end()); // a fixed summation order
                Eigen::Vector3d target = Eigen::Vector3d::Zero();
                for (int32_t w : around) target += points[w];
                target /= static_cast<double>(around.size());
                const int32_t v = first_added_ + static_cast<int32_t>(i);
                std::vector<Eigen::Vector3d> before;
                for (int f : incident[i]) before.push_back(mesh_.normal(tris[f]));
                const Eigen::Vector3d old = points[v];
                points[v] = target;
                bool ok = true;
                for (size_t k = 0; k < before.size() && ok; ++k)
                    ok = EditableMesh::turns_little(before[k], mesh_.normal(tris[incident[i][k]])) &&
                         mesh_.kappa(tris[incident[i][k]]) > 0.0;
                if (!ok) points[v] = old;
            }
    }

    long added() const { return static_cast<long>(mesh_.points.size()) - first_added_; }

    void write_to(Mesh& mesh, Eigen::Index first) const { mesh_.write_to(mesh, first); }

private:
    // The vertex of the use's triangle opposite its edge.
    Eigen::Vector3d opposite(const EditableMesh::Use& u) const { return mesh_.points[mesh_.tris[u.tri][(u.j + 2) % 3]]; }

    // Cosine of the angle of the use's triangle opposite its edge.
    double opposite_cos(const EditableMesh::Use& u) const {
        const Tri& t = mesh_.tris[u.tri];
        const Eigen::Vector3d c = opposite(u);
        const Eigen::Vector3d e1 = mesh_.points[t[u.j]] - c, e2 = mesh_.points[t[(u.j + 1) % 3]] - c;
        const double n = e1.norm() * e2.norm();
        return n > 0.0 ? e1.dot(e2) / n : 1.0;
    }

    EditableMesh mesh_;
    int32_t first_added_;
    std::unordered_set<uint64_t> outside_; // edges of the triangles before `first`
};

} // namespace

PatchRefinementStats refine_patches(Mesh& mesh, const PatchRefinementParams& params) {
    const Eigen::Index first = params.first;
    const double h = params.spacing;
    check_indices(mesh, "refine_patches");
    if (first < 0 || first > mesh.triangles.rows())
        throw InvalidInput("refine_patches: first patch triangle " + std::to_string(first) + " is out of range");
    if (!(h > 0.0) || !std::isfinite(h)) throw InvalidInput("refine_patches: edge length must be positive and finite");
    if (first == mesh.triangles.rows()) return {};
    Patch patch(mesh, first);
    for (int round = 0; round < params.rounds; ++round) {
        const bool split = patch.split_long_edges(h, params.max_added);
        patch.flip_edges();
        patch.smooth(3);
        if (!split) break;
    }
    patch.write_to(mesh, first);
    return {patch.added()};
}

} // namespace liftremesh
