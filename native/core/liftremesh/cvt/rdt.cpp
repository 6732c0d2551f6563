#include "liftremesh/cvt/rdt.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>

namespace liftremesh {

namespace {

// A piece of a cell lies across a knife edge from the rest when their normals turn by more than
// 90 degrees (a wedge sharper than a right angle), and less than 160: nearly antiparallel, the
// two sides of a thin wall or slot, which the lifting keeps apart (lift/thin_walls.h).
constexpr double kAcrossEdgeCos = 0.0, kAcrossWallCos = -0.94;

// The polygon Omega_{k|T_p} of the diagram, as the triangulation needs it.
struct Piece {
    int32_t site = -1, triangle = -1;
    double area = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // in R^3 (on the input triangle)
    std::uint8_t edges = 0;                             // bit j: the polygon reaches edge j of its triangle
};

// A point where three cells meet: a vertex of piece `piece` (of site k) between the bisectors
// of k and l and of k and m.
struct Corner {
    int32_t piece = -1; // index in its chunk's pieces until merged, then in all pieces
    int32_t l = -1, m = -1;
};

struct ChunkFound {
    std::vector<Piece> pieces;
    std::vector<Corner> corners;
};

// Area and centroid of a polygon of the diagram, the centroid mapped to R^3: the first three
// coordinates of x0 + a u1 + b u2 lie on the input triangle itself (the lifting adds the rest).
Piece measure_piece(const LiftedSurface& surface, const RvdPolygon& poly) {
    Piece piece;
    piece.site = poly.site;
    piece.triangle = poly.triangle;
    const double* c = poly.planar;
    double twice = 0.0;
    Eigen::Vector2d moment = Eigen::Vector2d::Zero();
    for (int i = 0; i < poly.size; ++i) {
        const int j = i + 1 == poly.size ? 0 : i + 1;
        const double cross = c[2 * i] * c[2 * j + 1] - c[2 * j] * c[2 * i + 1];
        twice += cross;
        moment += cross * Eigen::Vector2d(c[2 * i] + c[2 * j], c[2 * i + 1] + c[2 * j + 1]);
        if (poly.edges[i] < 0) piece.edges |= static_cast<std::uint8_t>(1u << (-1 - poly.edges[i]));
    }
    piece.area = 0.5 * std::abs(twice);
    // A piece of zero area has no centroid; its first vertex stands in (finite, and weighted by
    // the zero area wherever pieces are summed).
    const Eigen::Vector2d ab = twice != 0.0 ? Eigen::Vector2d(moment / (3.0 * twice)) : Eigen::Vector2d(c[0], c[1]);
    const long p = poly.triangle;
    piece.centroid = surface.points.row(surface.triangles(p, 0)).head<3>().transpose() +
                     ab[0] * surface.u1.row(p).head<3>().transpose() + ab[1] * surface.u2.row(p).head<3>().transpose();
    return piece;
}

} // namespace

RestrictedDelaunay restricted_delaunay(const LiftedSurface& surface, const LiftedPoints& sites, int threads,
                                       const RestrictedDelaunayParams& params, RvdCache* cache) {
    const long ns = static_cast<long>(sites.rows());
    if (params.held < 0 || params.held > ns)
        throw InvalidInput("restricted_delaunay: the held sites must be between none and all of them");
    std::vector<ChunkSlot<ChunkFound>> found(rvd_chunks(surface));
    compute_rvd(surface, sites, threads, [&](int chunk, const RvdPolygon& poly) {
        ChunkFound& f = found[chunk].value;
        const auto piece = static_cast<int32_t>(f.pieces.size());
        f.pieces.push_back(measure_piece(surface, poly));
        for (int i = 0; i < poly.size; ++i) {
            // Vertex i joins the edge before it (from i-1) and the edge after it (from i).
            const int32_t l = poly.edges[(i + poly.size - 1) % poly.size], m = poly.edges[i];
            if (l < 0 || m < 0 || l == m) continue;
            f.corners.push_back({piece, l, m});
        }
    }, cache);
    // The chunks' pieces and corners in chunk order, each chunk's freed as it is copied: the
    // run's peak memory is here on a large run.
    size_t piece_count = 0, corner_count = 0;
    for (const auto& f : found) {
        piece_count += f.value.pieces.size();
        corner_count += f.value.corners.size();
    }
    std::vector<Piece> pieces;
    std::vector<Corner> corners;
    pieces.reserve(piece_count);
    corners.reserve(corner_count);
    for (auto& f : found) {
        const auto offset = static_cast<int32_t>(pieces.size());
        pieces.insert(pieces.end(), f.value.pieces.begin(), f.value.pieces.end());
        for (Corner c : f.value.corners) {
            c.piece += offset;
            corners.push_back(c);
        }
        f.value = ChunkFound{};
    }
    const auto np = static_cast<int>(pieces.size());

    // Pieces of one cell joined across an input edge they both reach, or along the input's
    // boundary (key kBoundary): (edge key, site, piece), sorted, then runs linked.
    const Triangles& tri = surface.triangles;
    std::vector<std::uint64_t> boundary; // keys of the edges with one use, sorted as edge_counts() is
    for (const EdgeCount& e : edge_counts(tri))
        if (e.count == 1) boundary.push_back(edge_key(e.a, e.b));
    auto is_boundary = [&](std::uint64_t key) { return std::binary_search(boundary.begin(), boundary.end(), key); };
    constexpr std::uint64_t kBoundary = std::numeric_limits<std::uint64_t>::max();
    std::vector<std::tuple<std::uint64_t, int32_t, int>> reach;
    for (int i = 0; i < np; ++i)
        for (int j = 0; j < 3; ++j)
            if (pieces[i].edges & (1u << j)) {
                const long p = pieces[i].triangle;
                const std::uint64_t key = edge_key(tri(p, j), tri(p, (j + 1) % 3));
                reach.emplace_back(is_boundary(key) ? kBoundary : key, pieces[i].site, i);
            }
    std::sort(reach.begin(), reach.end());
    std::vector<std::pair<int, int>> links;
    for (size_t i = 1; i < reach.size(); ++i)
        if (std::get<0>(reach[i]) == std::get<0>(reach[i - 1]) && std::get<1>(reach[i]) == std::get<1>(reach[i - 1]))
            links.emplace_back(std::get<2>(reach[i - 1]), std::get<2>(reach[i]));
    std::vector<int> label;
    const int count = connected_components(np, links, label);

    // The connected parts of each cell, their areas and centroids.
    std::vector<double> part_area(static_cast<size_t>(count), 0.0), cell_area(static_cast<size_t>(ns), 0.0);
    std::vector<Eigen::Vector3d> part_moment(static_cast<size_t>(count), Eigen::Vector3d::Zero());
    std::vector<int32_t> part_site(static_cast<size_t>(count), -1);
    // Area-weighted, for the parts across a knife edge (below): only where rows of sites are held.
    std::vector<Eigen::Vector3d> part_normal(params.held > 0 ? static_cast<size_t>(count) : 0, Eigen::Vector3d::Zero());
    auto corner3 = [&](long f, int j) -> Eigen::Vector3d { return surface.points.row(tri(f, j)).head<3>().transpose(); };
    for (int i = 0; i < np; ++i) {
        const int part = label[i];
        if (params.held > 0) {
            const long f = pieces[i].triangle;
            part_normal[part] += pieces[i].area * triangle_normal(corner3(f, 0), corner3(f, 1), corner3(f, 2));
        }
        part_area[part] += pieces[i].area;
        part_moment[part] += pieces[i].area * pieces[i].centroid;
        part_site[part] = pieces[i].site;
        cell_area[pieces[i].site] += pieces[i].area;
    }
    // Per site, its largest part (kept at row k) and how many parts are large enough to count.
    std::vector<int> largest(static_cast<size_t>(ns), -1), counted(static_cast<size_t>(ns), 0);
    // (Of positive area: a cell of degenerate polygons only is never split, and a split piece's
    // centroid is always defined.)
    auto large = [&](int part) {
        return part_area[part] > 0.0 && part_area[part] >= params.min_piece * cell_area[part_site[part]];
    };
    for (int part = 0; part < count; ++part) {
        const int32_t k = part_site[part];
        if (largest[k] < 0 || part_area[part] > part_area[largest[k]]) largest[k] = part;
        counted[k] += large(part) ? 1 : 0;
    }

    RestrictedDelaunay result;
    std::vector<Eigen::Vector3d> points(static_cast<size_t>(ns));
    for (long k = 0; k < ns; ++k) points[k] = sites.row(k).head<3>().transpose();
    std::vector<int32_t> vertex_of_part(static_cast<size_t>(count));
    for (int part = 0; part < count; ++part) {
        const int32_t k = part_site[part];
        if (counted[k] <= 1 || part == largest[k] || !large(part)) {
            vertex_of_part[part] = k;
        } else {
            vertex_of_part[part] = static_cast<int32_t>(points.size());
            points.push_back(part_moment[part] / part_area[part]);
        }
    }
    for (long k = 0; k < ns; ++k)
        if (counted[k] > 1) {
            ++result.split_sites;
            points[k] = part_moment[largest[k]] / part_area[largest[k]];
        }

    // Triangles: the parts of k, l and m at the corner's input triangle (none for l or m if its
    // cell has no piece there, the corner lying on that triangle's edge: then its largest).
    std::vector<std::pair<std::int64_t, int>> piece_at; // (site * #F + triangle, piece), sorted
    piece_at.reserve(static_cast<size_t>(np));
    const std::int64_t nf = tri.rows();
    for (int i = 0; i < np; ++i) piece_at.emplace_back(pieces[i].site * nf + pieces[i].triangle, i);
    std::sort(piece_at.begin(), piece_at.end());
    auto part_at = [&](int32_t site, int32_t triangle) {
        const auto it = std::lower_bound(piece_at.begin(), piece_at.end(), std::make_pair(site * nf + triangle, -1));
        return it != piece_at.end() && it->first == site * nf + triangle ? label[it->second] : -1;
    };
    auto corner_parts = [&](const Corner& c) {
        const int32_t triangle = pieces[c.piece].triangle;
        return std::array<std::pair<int32_t, int>, 3>{
            {{pieces[c.piece].site, label[c.piece]}, {c.l, part_at(c.l, triangle)}, {c.m, part_at(c.m, triangle)}}};
    };
    // Rotated so the smallest index comes first (the three cells report the same triangle); none
    // if a part is taken as one of the triangle's other cells (below).
    auto triangle_of = [&](const Corner& c) -> std::optional<std::array<int32_t, 3>> {
        std::array<int32_t, 3> t;
        const auto parts = corner_parts(c);
        for (int j = 0; j < 3; ++j) t[j] = parts[j].second < 0 ? parts[j].first : vertex_of_part[parts[j].second];
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return std::nullopt;
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        return t;
    };
    std::vector<std::array<int32_t, 3>> all;
    auto triangulate = [&] {
        all.clear();
        for (const Corner& c : corners)
            if (const auto t = triangle_of(c)) all.push_back(*t);
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
    };
    triangulate();

    // A small part taken as its cell's largest may lie across a knife edge from it (their
    // normals 90 to 160 degrees apart): where the edge's sites are held (params.held), a cell
    // near it on one face reaches round onto the other between two of them. Its triangles then
    // join the faces through the wedge: the held pair's triangle on the other face turned over
    // (a pair folded shut, which the manifold repair removes with the crease edge), or triangles
    // across it, three on an edge. There the part is taken as the nearest of its neighbours on
    // its own side (their largest parts facing as it does), as if that cell covered it: the
    // triangles it made with that neighbour vanish, the others are that neighbour's; kept so
    // where they come out whole (and, without such a neighbour, left as it was). With a vertex
    // of its own, a sliver's width from the edge, it would fold its few triangles.
    if (params.held > 0 && !all.empty()) {
        auto across_edge = [&](int part) {
            const int32_t k = part_site[part];
            const Eigen::Vector3d &n = part_normal[part], &m = part_normal[largest[k]];
            const double cos_turn = n.dot(m) / (n.norm() * m.norm());
            return part != largest[k] && !large(part) && part_area[part] > 0.0 && cos_turn < kAcrossEdgeCos &&
                   cos_turn > kAcrossWallCos;
        };
        // The edges of `all` (a triangle a row of three corners, as edge_uses reads them).
        static_assert(sizeof(std::array<int32_t, 3>) == 3 * sizeof(int32_t));
        EdgeUses edges;
        auto list_edges = [&] { edges = edge_uses(all.front().data(), static_cast<long>(all.size())); };
        auto uses = [&](int32_t p, int32_t q) -> long { // triangles on edge {p, q}
            const int32_t lo = std::min(p, q), hi = std::max(p, q);
            const auto from = std::lower_bound(edges.a.begin(), edges.a.end(), lo) - edges.a.begin();
            const auto to = std::upper_bound(edges.a.begin() + from, edges.a.end(), lo) - edges.a.begin();
            const auto e = std::lower_bound(edges.b.begin() + from, edges.b.begin() + to, hi) - edges.b.begin();
            return e < to && edges.b[e] == hi ? edges.count(e) : 0;
        };
        auto broken = [&](const std::array<int32_t, 3>& t) { // folded onto another, or an edge in three
            if (std::binary_search(all.begin(), all.end(), std::array<int32_t, 3>{t[0], t[2], t[1]})) return true;
            for (int j = 0; j < 3; ++j)
                if (uses(t[j], t[j == 2 ? 0 : j + 1]) > 2) return true;
            return false;
        };
        list_edges();
        std::vector<char> marked(static_cast<size_t>(count), 0);
        for (const Corner& c : corners)
            if (const auto t = triangle_of(c); t && broken(*t))
                for (const auto& [site, part] : corner_parts(c))
                    if (part >= 0 && across_edge(part)) marked[part] = 1;
        // Each marked part's nearest neighbour on its side: (squared distance, site), -1 if none.
        std::vector<std::pair<double, int32_t>> stand_in(static_cast<size_t>(count), {std::numeric_limits<double>::infinity(), -1});
        for (const Corner& c : corners) {
            const int part = label[c.piece];
            if (!marked[part]) continue;
            const Eigen::Vector3d centroid = part_moment[part] / part_area[part];
            for (const int32_t other : {c.l, c.m}) {
                if (largest[other] < 0 || !(part_normal[largest[other]].dot(part_normal[part]) > 0.0)) continue;
                const double d = (sites.row(other).head<3>().transpose() - centroid).squaredNorm();
                if (d < stand_in[part].first) stand_in[part] = {d, other};
            }
        }
        bool taken = false;
        for (int part = 0; part < count; ++part)
            if (stand_in[part].second >= 0) {
                vertex_of_part[part] = stand_in[part].second;
                taken = true;
            }
        if (taken) {
            triangulate();
            list_edges();
            bool undone = false;
            for (const Corner& c : corners) {
                const int part = label[c.piece];
                if (stand_in[part].second < 0 || vertex_of_part[part] == part_site[part]) continue;
                if (const auto t = triangle_of(c); t && broken(*t)) {
                    vertex_of_part[part] = part_site[part];
                    undone = true;
                }
            }
            if (undone) triangulate();
        }
    }

    result.mesh = make_mesh(points, all);
    return result;
}

} // namespace liftremesh
