#include "liftremesh/spatial/aabb_tree.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {

constexpr int kLeafSize = 4;  // triangles per leaf at most
constexpr int kMaxDepth = 64; // median splits halve the count: depth <= log2(#F) + 1 <= 33

//! An axis-aligned box, its corners of type T. A point added is rounded outwards to T (exact
//! for double), so the box holds it.
template <typename T>
struct AxisBox {
    std::array<T, 3> lo, hi;
    void add(const Eigen::Vector3d& p) {
        for (int k = 0; k < 3; ++k) {
            T below = static_cast<T>(p[k]), above = below;
            if (below > p[k]) below = std::nextafter(below, -std::numeric_limits<T>::infinity());
            if (above < p[k]) above = std::nextafter(above, std::numeric_limits<T>::infinity());
            lo[k] = std::min(lo[k], below);
            hi[k] = std::max(hi[k], above);
        }
    }
    void add(const AxisBox& b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
        }
    }
    static AxisBox empty() {
        AxisBox b;
        b.lo.fill(std::numeric_limits<T>::infinity());
        b.hi.fill(-std::numeric_limits<T>::infinity());
        return b;
    }
};

using Box = AxisBox<double>;
//! A box of unit normals, in floats: half the memory, the bound still safe.
using NormalBox = AxisBox<float>;

//! A node of the tree. Inner nodes have two children stored next to each other.
struct Node {
    Box box;       //!< bounding box of the node's triangles
    int32_t first; //!< leaf: first triangle (tree order); inner: index of the left child
    int32_t count; //!< leaf: number of triangles (>= 1); inner: 0
};

//! The triangles under a node: a range of the tree order, from its leftmost leaf's first to its
//! rightmost leaf's last (Builder splits each node's range in two).
std::pair<int32_t, int32_t> triangle_range(const std::vector<Node>& nodes, const Node& node) {
    const Node* left = &node;
    while (left->count == 0) left = &nodes[left->first];
    const Node* right = &node;
    while (right->count == 0) right = &nodes[right->first + 1];
    return {left->first, right->first + right->count};
}

//! Squared distance from q to the box's farthest corner.
double box_farthest_squared_distance(const Box& box, const Eigen::Vector3d& q) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = std::max(q[k] - box.lo[k], box.hi[k] - q[k]);
        d2 += d * d;
    }
    return d2;
}

//! Squared distance from q to the box (0 inside).
double box_squared_distance(const Box& box, const Eigen::Vector3d& q) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double below = box.lo[k] - q[k], above = q[k] - box.hi[k];
        const double d = std::max({below, above, 0.0});
        d2 += d * d;
    }
    return d2;
}

// Sort key that keeps a strict weak order when a coordinate is NaN.
double sort_key(double x) { return std::isnan(x) ? std::numeric_limits<double>::infinity() : x; }

// Subtrees over at least this many triangles are built as OpenMP tasks, and the constructor's
// loops run in parallel from this many triangles on.
constexpr int32_t kParallelSize = 4096;

//! Nodes below the root of a subtree over n triangles: none under a leaf, else its two children
//! and theirs. Median splits give at most two sizes a level, which `known` keeps.
int32_t nodes_below(int32_t n, std::map<int32_t, int32_t>& known) {
    if (n <= kLeafSize) return 0;
    if (const auto it = known.find(n); it != known.end()) return it->second;
    const int32_t count = 2 + nodes_below(n / 2, known) + nodes_below(n - n / 2, known);
    known.emplace(n, count);
    return count;
}

//! Builds a tree into nodes sized for it beforehand, so that the two halves of a node can be
//! built at once: each subtree's nodes are a range of its own, in depth-first order. The nodes'
//! boxes are left to bound_boxes, once the triangles are in tree order.
struct Builder {
    //! A triangle's centroid beside its index: the median searches read them in sequence.
    struct Item {
        Eigen::Vector3d centroid;
        int32_t triangle;
    };
    std::vector<Node>& nodes;
    std::vector<Item>& order; //!< triangles in tree order once built
    const std::map<int32_t, int32_t>& below; //!< nodes_below, for every subtree size of the tree

    //! Builds the subtree of nodes[index] over order[begin, end), its nodes below it taken from
    //! `next` on, splitting at the median centroid along the longest axis of the centroids' box.
    void build(int32_t index, int32_t next, int32_t begin, int32_t end) {
        Node& node = nodes[index];
        if (end - begin <= kLeafSize) {
            node.first = begin;
            node.count = end - begin;
            return;
        }
        Eigen::Vector3d clo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
        Eigen::Vector3d chi = -clo;
        for (int32_t i = begin; i < end; ++i) {
            clo = clo.cwiseMin(order[i].centroid);
            chi = chi.cwiseMax(order[i].centroid);
        }
        int axis = 0;
        (chi - clo).maxCoeff(&axis);
        const int32_t mid = begin + (end - begin) / 2;
        std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](const Item& s, const Item& t) {
            return sort_key(s.centroid[axis]) < sort_key(t.centroid[axis]);
        });
        node.first = next;
        node.count = 0;
        const int32_t right_next = next + 2 + (mid - begin <= kLeafSize ? 0 : below.at(mid - begin));
        // Shared: the halves write apart (order, nodes), and this call waits for them.
#pragma omp task default(shared) if (mid - begin >= kParallelSize)
        build(next, next + 2, begin, mid);
#pragma omp task default(shared) if (end - mid >= kParallelSize)
        build(next + 1, right_next, mid, end);
#pragma omp taskwait
    }
};

//! Sets every node's box from the triangles' (`boxes`, in tree order): a leaf's holds its
//! triangles', an inner node's its children's. Children come after their parent (Builder), so
//! one backward pass bounds every node; min and max are exact, so an inner node's box is that
//! of its triangles.
void bound_boxes(std::vector<Node>& nodes, const std::vector<Box>& boxes) {
    for (size_t i = nodes.size(); i-- > 0;) {
        Node& node = nodes[i];
        if (node.count > 0) {
            node.box = Box::empty();
            for (int32_t t = node.first; t < node.first + node.count; ++t) node.box.add(boxes[t]);
        } else {
            node.box = nodes[node.first].box;
            node.box.add(nodes[node.first + 1].box);
        }
    }
}

} // namespace

struct AabbTree::Impl {
    std::vector<Node> nodes;              //!< nodes[0] is the root (empty tree: no node)
    std::vector<Eigen::Vector3d> corners; //!< 3 corners per triangle, in tree order
    std::vector<Box> boxes;               //!< bounding box of each triangle, in tree order
    std::vector<int32_t> ids;             //!< input triangle index, in tree order
    std::vector<Eigen::Vector3d> normals; //!< unit normal per input triangle, in input order
    //! Per node, a box holding its triangles' normals, in floats rounded outwards (half the
    //! memory of doubles; the bound stays safe): made by the first query that needs them, the
    //! ball sums or the thin-wall search (bound_normals), and kept as long as the tree.
    std::vector<NormalBox> normal_boxes;
    std::once_flag normals_bounded;
    const std::vector<NormalBox>& bound_normals();
};

const std::vector<NormalBox>& AabbTree::Impl::bound_normals() {
    std::call_once(normals_bounded, [this] {
        normal_boxes.assign(nodes.size(), NormalBox::empty());
        // Children come after their parent (Builder), so one backward pass bounds every node.
        for (size_t i = nodes.size(); i-- > 0;) {
            const Node& node = nodes[i];
            NormalBox& box = normal_boxes[i];
            if (node.count > 0) {
                for (int32_t t = node.first; t < node.first + node.count; ++t) box.add(normals[ids[t]]);
            } else {
                box = normal_boxes[node.first];
                box.add(normal_boxes[node.first + 1]);
            }
        }
    });
    return normal_boxes;
}

AabbTree::AabbTree(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
    check_indices(mesh, "AABB tree");
    const auto nf = static_cast<int32_t>(mesh.triangles.rows());
    if (nf == 0) return;
    // Read from the mesh twice (centroids to order the triangles, then corners in that order)
    // rather than copied: on a million triangles a copy is 70 MB of fresh pages, which the
    // kernel zeroes one by one.
    auto corner = [&mesh](int32_t f, int j) -> Eigen::Vector3d { return mesh.points.row(mesh.triangles(f, j)).transpose(); };
    std::vector<Builder::Item> order(static_cast<size_t>(nf));
    impl_->normals.resize(static_cast<size_t>(nf));
#pragma omp parallel for schedule(static) if (nf >= kParallelSize)
    for (int32_t f = 0; f < nf; ++f) {
        const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
        order[f] = {(a + b + c) / 3.0, f};
        impl_->normals[f] = liftremesh::triangle_normal(a, b, c);
    }

    std::map<int32_t, int32_t> below;
    impl_->nodes.resize(1 + static_cast<size_t>(nodes_below(nf, below)));
    Builder builder{impl_->nodes, order, below};
#pragma omp parallel if (nf >= kParallelSize)
#pragma omp single
    builder.build(0, 1, 0, nf);

    impl_->corners.resize(3 * static_cast<size_t>(nf));
    impl_->boxes.resize(static_cast<size_t>(nf));
#pragma omp parallel for schedule(static) if (nf >= kParallelSize)
    for (int32_t t = 0; t < nf; ++t) {
        Box& box = impl_->boxes[t];
        box = Box::empty();
        for (int j = 0; j < 3; ++j) {
            impl_->corners[3 * static_cast<size_t>(t) + j] = corner(order[t].triangle, j);
            box.add(impl_->corners[3 * static_cast<size_t>(t) + j]);
        }
    }
    bound_boxes(impl_->nodes, impl_->boxes);
    impl_->ids.resize(static_cast<size_t>(nf));
    for (int32_t t = 0; t < nf; ++t) impl_->ids[t] = order[t].triangle;
}

AabbTree::~AabbTree() = default;
AabbTree::AabbTree(AabbTree&&) noexcept = default;
AabbTree& AabbTree::operator=(AabbTree&&) noexcept = default;

ClosestPoint AabbTree::closest(const Eigen::Vector3d& q) const {
    return search(q, {Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()),
                      std::numeric_limits<double>::infinity(), -1});
}

ClosestPoint AabbTree::closest(const Eigen::Vector3d& q, const Eigen::Vector3d& on_mesh) const {
    return search(q, {on_mesh, (on_mesh - q).squaredNorm(), -1});
}

int32_t AabbTree::any_within(const Eigen::Vector3d& q, double r) const {
    return search(q, {Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()), r * r, -1}, true).triangle;
}

ClosestPoint AabbTree::closest_where(const Eigen::Vector3d& q, double r, const FacingAgainst& facing,
                                     const std::function<bool(int32_t, const Eigen::Vector3d&)>& accept) const {
    return search(q, {Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()), r * r, -1}, false, &facing,
                  &accept);
}

Eigen::Vector3d AabbTree::triangle_normal(int32_t triangle) const {
    if (triangle < 0 || static_cast<size_t>(triangle) >= impl_->normals.size())
        throw InvalidInput("AABB tree: no triangle " + std::to_string(triangle));
    return impl_->normals[static_cast<size_t>(triangle)];
}

namespace {

//! Whether two closed boxes meet.
bool boxes_meet(const Box& a, const Box& b) {
    for (int k = 0; k < 3; ++k)
        if (!(a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k])) return false;
    return true;
}

//! Sum of a box's sides.
double extent(const Box& b) { return (b.hi[0] - b.lo[0]) + (b.hi[1] - b.lo[1]) + (b.hi[2] - b.lo[2]); }

//! Whether the unit normal n faces as `facing` asks: the test the triangles are held to.
bool faces(const Eigen::Vector3d& n, const AabbTree::FacingAgainst& facing) {
    return std::any_of(facing.directions.begin(), facing.directions.end(),
                       [&](const Eigen::Vector3d& m) { return n.dot(m) < facing.max_dot; });
}

//! Whether some normal in the box may face as `facing` asks: the least n.m over the box is the
//! sum, axis by axis, of the lesser end's product. A margin far above the rounding of that sum
//! keeps the bound on the safe side, so no triangle that faces() accepts is ever skipped.
bool may_face(const NormalBox& normals, const AabbTree::FacingAgainst& facing) {
    return std::any_of(facing.directions.begin(), facing.directions.end(), [&](const Eigen::Vector3d& m) {
        double least = 0.0;
        for (int k = 0; k < 3; ++k) least += std::min(double{normals.lo[k]} * m[k], double{normals.hi[k]} * m[k]);
        return least < facing.max_dot + 1e-9;
    });
}

} // namespace

void AabbTree::overlapping_pairs(const std::function<bool(int32_t, int32_t)>& visit) const {
    const auto& nodes = impl_->nodes;
    const auto& boxes = impl_->boxes;
    if (nodes.empty()) return;
    // Pending node pairs: (i, i) the pairs within node i, (i, j) those between two disjoint nodes.
    std::vector<std::pair<int32_t, int32_t>> pending = {{0, 0}};
    while (!pending.empty()) {
        const auto [i, j] = pending.back();
        pending.pop_back();
        const Node &a = nodes[i], &b = nodes[j];
        if (i == j) {
            if (a.count > 0) {
                for (int32_t s = a.first; s < a.first + a.count; ++s)
                    for (int32_t t = s + 1; t < a.first + a.count; ++t)
                        if (boxes_meet(boxes[s], boxes[t]) && !visit(impl_->ids[s], impl_->ids[t])) return;
            } else {
                pending.emplace_back(a.first, a.first);
                pending.emplace_back(a.first + 1, a.first + 1);
                pending.emplace_back(a.first, a.first + 1);
            }
            continue;
        }
        if (!boxes_meet(a.box, b.box)) continue;
        if (a.count > 0 && b.count > 0) {
            for (int32_t s = a.first; s < a.first + a.count; ++s)
                for (int32_t t = b.first; t < b.first + b.count; ++t)
                    if (boxes_meet(boxes[s], boxes[t]) && !visit(impl_->ids[s], impl_->ids[t])) return;
        } else if (a.count == 0 && (b.count > 0 || extent(a.box) >= extent(b.box))) { // split the larger inner node
            pending.emplace_back(a.first, j);
            pending.emplace_back(a.first + 1, j);
        } else {
            pending.emplace_back(i, b.first);
            pending.emplace_back(i, b.first + 1);
        }
    }
}

void AabbTree::triangles_within(const Eigen::Vector3d& q, double r, std::vector<int32_t>& out) const {
    const auto& nodes = impl_->nodes;
    if (nodes.empty() || !(r > 0.0)) return;
    const double r2 = r * r;
    // A box whose farthest corner is nearer than r holds only triangles nearer than r: they are
    // taken without a test. The margin keeps this clear of the rounding of the per-triangle test.
    const double inside_d2 = r2 * (1.0 - 1e-9);
    int32_t stack[2 * kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes[stack[--top]];
        if (!(box_squared_distance(node.box, q) < r2)) continue;
        if (box_farthest_squared_distance(node.box, q) < inside_d2) { // all of it in the ball
            const auto [begin, end] = triangle_range(nodes, node);
            out.insert(out.end(), impl_->ids.begin() + begin, impl_->ids.begin() + end);
            continue;
        }
        if (node.count > 0) {
            for (int32_t t = node.first; t < node.first + node.count; ++t) {
                if (!(box_squared_distance(impl_->boxes[t], q) < r2)) continue;
                const Eigen::Vector3d* c = &impl_->corners[3 * static_cast<size_t>(t)];
                if ((closest_point_on_triangle(q, c[0], c[1], c[2]) - q).squaredNorm() < r2) out.push_back(impl_->ids[t]);
            }
            continue;
        }
        assert(top + 2 <= 2 * kMaxDepth);
        stack[top++] = node.first + 1;
        stack[top++] = node.first;
    }
}

AabbTree::NormalSums AabbTree::normal_sums() const {
    NormalSums out;
    const auto& ids = impl_->ids;
    const auto& nodes = impl_->nodes;
    const auto nt = static_cast<int32_t>(ids.size());
    out.normals.resize(ids.size());
    out.weighted.resize(ids.size());
#pragma omp parallel for schedule(static) if (nt >= kParallelSize)
    for (int32_t t = 0; t < nt; ++t) {
        const Eigen::Vector3d* c = &impl_->corners[3 * static_cast<size_t>(t)];
        out.normals[t] = impl_->normals[ids[t]];
        out.weighted[t] = triangle_area(c[0], c[1], c[2]) * impl_->normals[ids[t]];
    }
    out.nodes.assign(nodes.size(), Eigen::Vector3d::Zero());
    // Children come after their parent (Builder), so one backward pass sums every node.
    for (size_t i = nodes.size(); i-- > 0;) {
        const Node& node = nodes[i];
        Eigen::Vector3d& sum = out.nodes[i];
        if (node.count > 0) {
            for (int32_t t = node.first; t < node.first + node.count; ++t) sum += out.weighted[t];
        } else {
            sum = out.nodes[node.first] + out.nodes[node.first + 1];
        }
    }
    return out;
}

AabbTree::BallNormalSums AabbTree::area_weighted_normals_in_ball(const NormalSums& normal_sums, const Eigen::Vector3d& q,
                                                                double r, const FacingWith& facing) const {
    BallNormalSums sums{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    const auto& nodes = impl_->nodes;
    if (nodes.empty() || !(r > 0.0)) return sums;
    if (normal_sums.nodes.size() != nodes.size())
        throw InvalidInput("AABB tree: normal sums made for another tree");
    const NormalBox* normal_boxes = impl_->bound_normals().data();
    const double r2 = r * r;
    const double inside_d2 = r2 * (1.0 - 1e-9); // as in triangles_within
    // The range of n.dot(direction) over a node's box of normals: the lesser and the greater end's
    // products axis by axis. The margin keeps a node's verdict clear of that sum's rounding, so
    // a node is settled whole only when every triangle's own test would agree.
    auto facing_range = [&](const NormalBox& box) {
        double least = 0.0, most = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double lo = double{box.lo[k]} * facing.direction[k], hi = double{box.hi[k]} * facing.direction[k];
            least += std::min(lo, hi);
            most += std::max(lo, hi);
        }
        return std::pair{least - 1e-9, most + 1e-9};
    };
    int32_t stack[2 * kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const int32_t index = stack[--top];
        const Node& node = nodes[index];
        if (!(box_squared_distance(node.box, q) < r2)) continue;
        if (box_farthest_squared_distance(node.box, q) < inside_d2) {
            // All of it in the ball: its sum goes whole to one side if all its normals do.
            const auto [least, most] = facing_range(normal_boxes[index]);
            if (least >= facing.min_dot || most < facing.min_dot) {
                (least >= facing.min_dot ? sums.facing : sums.against) += normal_sums.nodes[index];
                continue;
            }
        }
        if (node.count > 0) {
            for (int32_t t = node.first; t < node.first + node.count; ++t) {
                if (!(box_squared_distance(impl_->boxes[t], q) < r2)) continue;
                const Eigen::Vector3d& n = normal_sums.normals[t];
                Eigen::Vector3d& sum = n.dot(facing.direction) >= facing.min_dot ? sums.facing : sums.against;
                // The ball is convex: a triangle whose corners are inside is wholly inside.
                const Eigen::Vector3d* c = &impl_->corners[3 * static_cast<size_t>(t)];
                if ((c[0] - q).squaredNorm() < inside_d2 && (c[1] - q).squaredNorm() < inside_d2 &&
                    (c[2] - q).squaredNorm() < inside_d2) {
                    sum += normal_sums.weighted[t];
                    continue;
                }
                // Zero for a triangle the ball misses.
                sum += triangle_ball_intersection_area(q, r, c[0], c[1], c[2], n) * n;
            }
            continue;
        }
        assert(top + 2 <= 2 * kMaxDepth);
        stack[top++] = node.first + 1;
        stack[top++] = node.first;
    }
    return sums;
}

void AabbTree::triangles_meeting_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                     std::vector<int32_t>& out) const {
    const auto& nodes = impl_->nodes;
    if (nodes.empty()) return;
    Box query = Box::empty();
    query.add(lo);
    query.add(hi);
    int32_t stack[2 * kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes[stack[--top]];
        if (!boxes_meet(node.box, query)) continue;
        if (node.count > 0) {
            for (int32_t t = node.first; t < node.first + node.count; ++t)
                if (boxes_meet(impl_->boxes[t], query)) out.push_back(impl_->ids[t]);
            continue;
        }
        assert(top + 2 <= 2 * kMaxDepth);
        stack[top++] = node.first + 1;
        stack[top++] = node.first;
    }
}

ClosestPoint AabbTree::search(const Eigen::Vector3d& q, ClosestPoint best, bool first_hit, const FacingAgainst* facing,
                              const std::function<bool(int32_t, const Eigen::Vector3d&)>* accept) const {
    const auto& nodes = impl_->nodes;
    if (nodes.empty()) return best;
    const NormalBox* normal_boxes = facing ? impl_->bound_normals().data() : nullptr;

    // Depth-first, nearer child first; a node is skipped once its box is no nearer than the best,
    // and so is a leaf's triangle (its exact distance costs six times its box's).
    struct Pending {
        int32_t index;
        double box_d2;
    };
    Pending stack[2 * kMaxDepth]; // not a std::array of pairs, which every query would zero
    int top = 0;
    stack[top++] = {0, box_squared_distance(nodes[0].box, q)};
    while (top > 0) {
        const auto [index, box_d2] = stack[--top];
        if (box_d2 >= best.squared_distance) continue;
        if (facing && !may_face(normal_boxes[index], *facing)) continue;
        const Node& node = nodes[index];
        if (node.count > 0) {
            for (int32_t t = node.first; t < node.first + node.count; ++t) {
                if (box_squared_distance(impl_->boxes[t], q) >= best.squared_distance) continue;
                if (facing && !faces(impl_->normals[impl_->ids[t]], *facing)) continue;
                const Eigen::Vector3d* c = &impl_->corners[3 * static_cast<size_t>(t)];
                const Eigen::Vector3d p = closest_point_on_triangle(q, c[0], c[1], c[2]);
                const double d2 = (p - q).squaredNorm();
                if (d2 < best.squared_distance && (!accept || (*accept)(impl_->ids[t], p))) {
                    best = {p, d2, impl_->ids[t]};
                    if (first_hit) return best;
                }
            }
            continue;
        }
        const double dl = box_squared_distance(nodes[node.first].box, q);
        const double dr = box_squared_distance(nodes[node.first + 1].box, q);
        assert(top + 2 <= 2 * kMaxDepth);
        if (dl <= dr) {
            stack[top++] = {node.first + 1, dr};
            stack[top++] = {node.first, dl};
        } else {
            stack[top++] = {node.first, dl};
            stack[top++] = {node.first + 1, dr};
        }
    }
    return best;
}

} // namespace liftremesh
