#include "liftremesh/mesh/editable_mesh.h"

#include "liftremesh/mesh/geometry.h"

namespace liftremesh {

namespace {
constexpr double kCos30 = 0.86602540378443865; // largest turn of a triangle's normal in a flip
} // namespace

EditableMesh::EditableMesh(const Mesh& mesh, Eigen::Index first) {
    points.reserve(static_cast<size_t>(mesh.points.rows()));
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) points.push_back(mesh.points.row(i).transpose());
    for (Eigen::Index f = first; f < mesh.triangles.rows(); ++f)
        tris.push_back({mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)});
}

namespace {
void add_use(std::unordered_map<uint64_t, EditableMesh::Uses>& uses, uint64_t key, int tri, int j) {
    EditableMesh::Uses& u = uses[key];
    if (u.count < 2) u.first[u.count] = {tri, j};
    ++u.count;
}
} // namespace

std::unordered_map<uint64_t, EditableMesh::Uses> EditableMesh::edge_uses() const {
    std::unordered_map<uint64_t, Uses> uses;
    uses.reserve(2 * tris.size());
    for (size_t f = 0; f < tris.size(); ++f)
        for (int j = 0; j < 3; ++j) add_use(uses, edge_key(tris[f][j], tris[f][(j + 1) % 3]), static_cast<int>(f), j);
    return uses;
}

std::unordered_map<uint64_t, EditableMesh::Uses> EditableMesh::edge_uses_around(const std::vector<char>& flagged) const {
    std::unordered_map<uint64_t, Uses> uses;
    for (size_t f = 0; f < tris.size(); ++f)
        for (int j = 0; j < 3; ++j) {
            const int32_t a = tris[f][j], b = tris[f][(j + 1) % 3];
            if (flagged[a] || flagged[b]) add_use(uses, edge_key(a, b), static_cast<int>(f), j);
        }
    return uses;
}

std::optional<EditableMesh::Quad> EditableMesh::quad_of(const Uses& uses) const {
    if (uses.size() != 2) return std::nullopt;
    const Tri &first = tris[uses[0].tri], &second = tris[uses[1].tri];
    const int32_t a = first[uses[0].j], b = first[(uses[0].j + 1) % 3], c = first[(uses[0].j + 2) % 3];
    if (second[uses[1].j] != b) return std::nullopt;
    return Quad{uses[0].tri, uses[1].tri, a, b, c, second[(uses[1].j + 2) % 3]};
}

Eigen::Vector3d EditableMesh::normal(const Tri& t) const {
    return (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]);
}

double EditableMesh::kappa(const Tri& t) const { return triangle_kappa(points[t[0]], points[t[1]], points[t[2]]); }

bool EditableMesh::turns_little(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const double n = u.norm() * v.norm();
    return n > 0.0 && u.dot(v) >= kCos30 * n;
}

std::pair<EditableMesh::Tri, EditableMesh::Tri> EditableMesh::flipped(const Quad& q) {
    return {Tri{q.a, q.d, q.c}, Tri{q.d, q.b, q.c}};
}

bool EditableMesh::flip_improves_quality(const Quad& q) const {
    const auto [n1, n2] = flipped(q);
    const Eigen::Vector3d before1 = normal(tris[q.t1]), before2 = normal(tris[q.t2]);
    if (!turns_little(before1, before2)) return false; // not a near-planar quad: the flip would change the shape
    const Eigen::Vector3d mean = before1.normalized() + before2.normalized();
    if (!turns_little(mean, normal(n1)) || !turns_little(mean, normal(n2))) return false;
    return std::min(kappa(n1), kappa(n2)) > std::min(kappa(tris[q.t1]), kappa(tris[q.t2])) + 1e-9;
}

void EditableMesh::flip(const Quad& q) {
    const auto [n1, n2] = flipped(q);
    tris[q.t1] = n1;
    tris[q.t2] = n2;
}

long EditableMesh::flip_pass(const std::unordered_map<uint64_t, Uses>& uses, const std::vector<uint64_t>& keys,
                             const std::unordered_set<uint64_t>& fixed_edges,
                             const std::function<bool(const Quad&)>& accept, std::vector<char>& flipped) {
    flipped.assign(tris.size(), 0);
    std::unordered_set<uint64_t> made, gone; // edges flipped in and out in this pass
    long flips = 0;
    for (uint64_t key : keys) {
        const Uses& use = uses.at(key);
        if (flipped[use[0].tri] || flipped[use[1].tri]) continue;
        const auto quad = quad_of(use);
        if (!quad || quad->c == quad->d) continue;
        const uint64_t cd = edge_key(quad->c, quad->d);
        if (made.count(cd) || fixed_edges.count(cd) || (uses.count(cd) && !gone.count(cd))) continue;
        if (!accept(*quad)) continue;
        gone.insert(key);
        made.insert(cd);
        flip(*quad);
        flipped[quad->t1] = flipped[quad->t2] = 1;
        ++flips;
    }
    return flips;
}

long EditableMesh::flip_pass_around(const std::vector<char>& around, const std::function<bool(const Quad&)>& accept,
                                    std::vector<char>& flipped) {
    std::vector<char> flagged(points.size(), 0);
    for (size_t t = 0; t < tris.size(); ++t)
        if (around[t])
            for (int32_t v : tris[t]) flagged[v] = 1;
    // Every edge with a flagged end is in `uses`, so an edge c-d of a quad here is too.
    const auto uses = edge_uses_around(flagged);
    std::vector<uint64_t> keys;
    for (const auto& [key, use] : uses)
        if (use.size() == 2 && (around[use[0].tri] || around[use[1].tri])) keys.push_back(key);
    std::sort(keys.begin(), keys.end());
    return flip_pass(uses, keys, {}, accept, flipped);
}

int32_t EditableMesh::split_edge(const Quad& q, const Eigen::Vector3d& p) {
    const auto m = static_cast<int32_t>(points.size());
    points.push_back(p);
    tris[q.t1] = {q.a, m, q.c};
    tris[q.t2] = {q.b, m, q.d};
    tris.push_back({m, q.b, q.c});
    tris.push_back({m, q.a, q.d});
    return m;
}

// The fans of the points `listed` flags (all of them without flags), in triangle order.
CompressedRows EditableMesh::fans_of(const std::vector<char>* listed) const {
    std::vector<std::pair<int32_t, int32_t>> pairs;
    if (!listed) pairs.reserve(3 * tris.size());
    for (size_t t = 0; t < tris.size(); ++t)
        for (int32_t v : tris[t])
            if (!listed || (*listed)[v]) pairs.emplace_back(v, static_cast<int32_t>(t));
    return compress_rows(static_cast<long>(points.size()), pairs);
}

CompressedRows EditableMesh::fans() const { return fans_of(nullptr); }

CompressedRows EditableMesh::fans_around(const std::vector<char>& around) const {
    std::vector<char> corner(points.size(), 0), listed(points.size(), 0);
    for (size_t t = 0; t < tris.size() && t < around.size(); ++t)
        if (around[t])
            for (int32_t v : tris[t]) corner[v] = 1;
    for (const Tri& x : tris)
        if (corner[x[0]] || corner[x[1]] || corner[x[2]])
            for (int32_t v : x) listed[v] = 1;
    return fans_of(&listed);
}

std::vector<char> EditableMesh::border_points() const {
    std::vector<char> border(points.size(), 0);
    for (const auto& [key, use] : edge_uses())
        if (use.size() != 2) {
            const Tri& t = tris[use[0].tri];
            border[t[use[0].j]] = border[t[(use[0].j + 1) % 3]] = 1;
        }
    return border;
}

Mesh EditableMesh::to_mesh() const { return make_mesh(points, tris); }

void EditableMesh::write_to(Mesh& mesh, Eigen::Index first) const {
    mesh.points.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (size_t i = 0; i < points.size(); ++i) mesh.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
    mesh.triangles.conservativeResize(first + static_cast<Eigen::Index>(tris.size()), 3);
    for (size_t k = 0; k < tris.size(); ++k)
        for (int j = 0; j < 3; ++j) mesh.triangles(first + static_cast<Eigen::Index>(k), j) = tris[k][j];
}

} // namespace liftremesh
