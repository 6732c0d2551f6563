#include "liftremesh/mesh/editable_mesh.h"

#include "liftremesh/mesh/geometry.h"

#include <algorithm>

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
    set_tri(q.t1, n1);
    set_tri(q.t2, n2);
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
    set_tri(q.t1, {q.a, m, q.c});
    set_tri(q.t2, {q.b, m, q.d});
    add_tri({m, q.b, q.c});
    add_tri({m, q.a, q.d});
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

void EditableMesh::keep_fans() {
    keep_ = true;
    fans_.assign(points.size(), {});
    for (size_t t = 0; t < tris.size(); ++t)
        for (int32_t v : tris[t]) fans_[v].push_back(static_cast<int32_t>(t));
}

const std::vector<int32_t>& EditableMesh::fan(int32_t v) const {
    static const std::vector<int32_t> none;
    return static_cast<size_t>(v) < fans_.size() ? fans_[v] : none;
}

void EditableMesh::set_tri(int t, const Tri& tri) {
    if (journal_ && static_cast<size_t>(t) < journal_->tris) journal_->changed.emplace_back(t, tris[t]);
    if (keep_)
        for (int32_t v : tris[t]) {
            std::vector<int32_t>& f = fans_[v];
            f.erase(std::find(f.begin(), f.end(), t));
        }
    tris[t] = tri;
    if (keep_)
        for (int32_t v : tri) {
            if (static_cast<size_t>(v) >= fans_.size()) fans_.resize(v + 1);
            fans_[v].push_back(t);
        }
}

int EditableMesh::add_tri(const Tri& tri) {
    const int t = static_cast<int>(tris.size());
    tris.push_back(tri);
    if (keep_)
        for (int32_t v : tri) {
            if (static_cast<size_t>(v) >= fans_.size()) fans_.resize(v + 1);
            fans_[v].push_back(t);
        }
    return t;
}

void EditableMesh::begin_edits() { journal_ = Journal{points.size(), tris.size(), {}}; }

void EditableMesh::roll_back() {
    const Journal j = std::move(*journal_);
    journal_.reset();
    while (tris.size() > j.tris) {
        if (keep_)
            for (int32_t v : tris.back()) {
                std::vector<int32_t>& f = fans_[v];
                f.erase(std::find(f.begin(), f.end(), static_cast<int32_t>(tris.size() - 1)));
            }
        tris.pop_back();
    }
    for (auto it = j.changed.rbegin(); it != j.changed.rend(); ++it) set_tri(it->first, it->second);
    points.resize(j.points);
    if (keep_ && fans_.size() > points.size()) fans_.resize(points.size());
}

void EditableMesh::keep_edits() { journal_.reset(); }

std::vector<int> EditableMesh::tris_near(const std::vector<int32_t>& near) const {
    std::vector<int> out;
    for (int32_t v : near) out.insert(out.end(), fan(v).begin(), fan(v).end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::unordered_map<uint64_t, EditableMesh::Uses> EditableMesh::edge_uses_near(std::vector<int32_t> near) const {
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    auto listed = [&](int32_t v) { return std::binary_search(near.begin(), near.end(), v); };
    std::unordered_map<uint64_t, Uses> uses;
    for (const int f : tris_near(near)) // in triangle order, as edge_uses_around adds them
        for (int j = 0; j < 3; ++j) {
            const int32_t a = tris[f][j], b = tris[f][(j + 1) % 3];
            if (listed(a) || listed(b)) add_use(uses, edge_key(a, b), f, j);
        }
    return uses;
}

std::optional<EditableMesh::Quad> EditableMesh::quad_at(int t, int j) const {
    const int32_t a = tris[t][j], b = tris[t][(j + 1) % 3];
    Uses uses;
    auto add = [&](int s, int i) {
        if (uses.count < 2) uses.first[uses.count] = {s, i};
        ++uses.count;
    };
    add(t, j);
    for (const int s : fan(a))
        for (int i = 0; i < 3; ++i) {
            const int32_t p = tris[s][i], q = tris[s][(i + 1) % 3];
            if (s != t && ((p == a && q == b) || (p == b && q == a))) add(s, i);
        }
    return quad_of(uses);
}

bool EditableMesh::joined(int32_t u, int32_t v) const {
    for (const int s : fan(u))
        for (int32_t w : tris[s])
            if (w == v) return true;
    return false;
}

std::pair<const int32_t*, const int32_t*> EditableMesh::FanSnapshot::operator()(int32_t v) const {
    const auto it = std::lower_bound(points_.begin(), points_.end(), v);
    if (it == points_.end() || *it != v) return {nullptr, nullptr};
    const long row = it - points_.begin();
    return {rows_.begin(row), rows_.end(row)};
}

EditableMesh::FanSnapshot EditableMesh::fans_near(const std::vector<int>& near) const {
    std::vector<int32_t> corners;
    for (const int t : near) corners.insert(corners.end(), tris[t].begin(), tris[t].end());
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    FanSnapshot snapshot;
    for (const int t : tris_near(corners)) snapshot.points_.insert(snapshot.points_.end(), tris[t].begin(), tris[t].end());
    std::vector<int32_t>& listed = snapshot.points_;
    std::sort(listed.begin(), listed.end());
    listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
    std::vector<std::pair<int32_t, int32_t>> pairs;
    for (size_t row = 0; row < listed.size(); ++row) {
        std::vector<int32_t> fan_now = fan(listed[row]);
        std::sort(fan_now.begin(), fan_now.end()); // triangle order, as fans() gives them
        for (const int32_t t : fan_now) pairs.emplace_back(static_cast<int32_t>(row), t);
    }
    snapshot.rows_ = compress_rows(static_cast<long>(listed.size()), pairs);
    return snapshot;
}

long EditableMesh::flip_pass_near(std::vector<int> near, const std::function<bool(const Quad&)>& accept,
                                  std::vector<int>& flipped) {
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    auto listed = [&](int t) { return std::binary_search(near.begin(), near.end(), t); };
    std::vector<int32_t> corners;
    for (const int t : near) corners.insert(corners.end(), tris[t].begin(), tris[t].end());
    // Every edge with an end among the corners is in `uses`, so an edge c-d of a quad here is too.
    const auto uses = edge_uses_near(corners);
    std::vector<uint64_t> keys;
    for (const auto& [key, use] : uses)
        if (use.size() == 2 && (listed(use[0].tri) || listed(use[1].tri))) keys.push_back(key);
    std::sort(keys.begin(), keys.end());
    std::vector<char> flags;
    const long flips = flip_pass(uses, keys, {}, accept, flags);
    flipped.clear();
    for (const uint64_t key : keys)
        for (int i = 0; i < 2; ++i)
            if (const int t = uses.at(key)[i].tri; flags[t] && std::find(flipped.begin(), flipped.end(), t) == flipped.end())
                flipped.push_back(t);
    return flips;
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
