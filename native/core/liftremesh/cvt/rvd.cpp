#include "liftremesh/cvt/rvd.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/spatial/neighbor_search.h"
#include "liftremesh/system/threads.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace liftremesh {

namespace {
// Each triangle's tangent basis (Eq. 15), one triangle at a time: in parallel, each thread with
// its own vectors, allocated once.
void tangent_bases(LiftedSurface& s) {
    const Eigen::Index nf = s.triangles.rows(), d = s.points.cols();
#pragma omp parallel
    {
        Eigen::VectorXd x1(d), x2(d), x3(d), u1(d), u2(d);
#pragma omp for schedule(static, 4096)
        for (Eigen::Index f = 0; f < nf; ++f) {
            x1 = s.points.row(s.triangles(f, 0)).transpose();
            x2 = s.points.row(s.triangles(f, 1)).transpose();
            x3 = s.points.row(s.triangles(f, 2)).transpose();
            if (tangent_basis<Eigen::Dynamic>(x1, x2, x3, u1, u2)) {
                s.u1.row(f) = u1.transpose();
                s.u2.row(f) = u2.transpose();
                s.valid[f] = 1;
            }
        }
    }
}
} // namespace

LiftedSurface make_lifted_surface(LiftedPoints points, Triangles triangles, Eigen::VectorXd weights) {
    LiftedSurface s;
    const int d = static_cast<int>(points.cols());
    if (d != 3 && d != 6) throw InvalidInput("lifted points have " + std::to_string(d) + " columns, expected 3 or 6");
    const Eigen::Index nf = triangles.rows();
    s.points = std::move(points);
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> centroids(nf, 3);
    for (Eigen::Index f = 0; f < nf; ++f)
        centroids.row(f) = (s.points.row(triangles(f, 0)).leftCols<3>() + s.points.row(triangles(f, 1)).leftCols<3>() +
                            s.points.row(triangles(f, 2)).leftCols<3>()) / 3.0;
    // The diagram walks the triangles in this order, reading each one's rows: stored in it,
    // they are read one after the other, wherever the input lists them.
    const std::vector<long> order = morton_order(centroids.data(), nf, 3);
    s.triangles.resize(nf, 3);
    s.weights.resize(nf);
    s.row_of.resize(static_cast<size_t>(nf));
    for (Eigen::Index i = 0; i < nf; ++i) {
        s.triangles.row(i) = triangles.row(order[i]);
        s.weights[i] = weights.size() == nf ? weights[order[i]] : 1.0;
        s.row_of[order[i]] = static_cast<int32_t>(i);
    }
    s.u1 = LiftedPoints::Zero(nf, d);
    s.u2 = LiftedPoints::Zero(nf, d);
    s.valid.assign(nf, 0);
    tangent_bases(s);
    return s;
}

double lifted_area(const LiftedSurface& s) {
    double total = 0.0;
    for (const int32_t f : s.row_of)
        if (s.valid[f])
            total += triangle_area(s.points.row(s.triangles(f, 0)), s.points.row(s.triangles(f, 1)),
                                   s.points.row(s.triangles(f, 2)));
    return total;
}

double polygon_area(const RvdPolygon& poly) {
    const double* c = poly.planar;
    double twice = 0.0; // shoelace; the polygon runs in the triangle's (counter-clockwise) order
    for (int i = 0; i < poly.size; ++i) {
        const int j = i + 1 == poly.size ? 0 : i + 1;
        twice += c[2 * i] * c[2 * j + 1] - c[2 * j] * c[2 * i + 1];
    }
    return 0.5 * std::abs(twice);
}

int rvd_chunks(const LiftedSurface& surface) {
    // About 32 triangles a chunk: small enough to even out the threads' ends, large enough to
    // keep each chunk's sites in its thread's cache.
    return static_cast<int>(std::clamp<long>(static_cast<long>(surface.triangles.rows()) / 32, 1, 256));
}

namespace {

// A convex polygon in the plane of one triangle, in the triangle's 2D orthonormal coordinates
// (origin at its first vertex, axes u1, u2 of Eq. 15), with the line id of each edge (see
// RvdPolygon::edges). Fixed storage: clipping a triangle by n half-planes gives at most 3 + n
// vertices, and a cell is clipped by a few tens of bisectors at most.
struct Polygon2 {
    static constexpr int kCapacity = 96;
    Eigen::Vector2d v[kCapacity];
    int32_t e[kCapacity];
    int n = 0;
    void push(const Eigen::Vector2d& x, int32_t id) {
        v[n] = x;
        e[n++] = id;
    }
    bool full() const { return n + 1 >= kCapacity; }
};

// Clips `in` to the points of the plane nearer to site k than to site l. With w = v - x0 and
// x = x0 + a u1 + b u2, |x - v_k|^2 <= |x - v_l|^2 reads (a, b).(ab_l - ab_k) <= (|w_l|^2 - |w_k|^2) / 2.
// Sutherland-Hodgman; the new edge carries the id l. Returns false, leaving `out` untouched,
// when the bisector misses the polygon (nothing cut).
[[gnu::always_inline]] inline bool clip_by_bisector(const Polygon2& in, const PlanarSite& k, const PlanarSite& l,
                                                    int32_t id, Polygon2& out) {
    const Eigen::Vector2d dir = l.ab - k.ab;
    const double offset = 0.5 * (l.norm2 - k.norm2);
    const int n = in.n; // local counts: `in` and `out` are never the same polygon, but the
                        // compiler cannot know it and would reload them at every vertex
    double side[Polygon2::kCapacity];
    bool any_out = false;
    for (int i = 0; i < n; ++i) {
        side[i] = in.v[i].dot(dir) - offset;
        any_out |= side[i] > 0.0;
    }
    if (!any_out) return false;
    int m = 0;
    for (int i = 0; i < n; ++i) {
        const int j = i + 1 == n ? 0 : i + 1;
        const bool in_i = side[i] <= 0.0, in_j = side[j] <= 0.0;
        if (in_i) {
            out.v[m] = in.v[i];
            out.e[m++] = in.e[i];
        }
        if (in_i != in_j) {
            const double t = side[i] / (side[i] - side[j]);
            out.v[m] = in.v[i] + t * (in.v[j] - in.v[i]);
            out.e[m++] = in_i ? id : in.e[i]; // leaving: the bisector follows
        }
    }
    out.n = m;
    return true;
}

// Largest squared distance from a site to the polygon's vertices, in R^d: in-plane part plus
// the site's squared distance to the plane.
double max_squared_distance(const Polygon2& p, const Eigen::Vector2d& ab, double off_plane2) {
    double r2 = 0.0;
    for (int i = 0; i < p.n; ++i) r2 = std::max(r2, (p.v[i] - ab).squaredNorm());
    return r2 + off_plane2;
}

// How far the sites are from the anchor of the cache's tree and lists.
struct Staleness {
    Eigen::VectorXd displacement;  // #S distance of each site from its anchor position
    std::vector<int32_t> movers;   // the sites farther than the rebuild distance from it
    std::vector<char> is_mover;    // #S
    double rest = 0.0;             // largest displacement of the other sites
    // Per site k, the movers m now within `reach` of k's anchor: all those that can cut a
    // polygon of k of radius R with 2 R + displacement[k] < reach (nanoflann finds distances < reach).
    double reach = 0.0;
    CompressedRows near_movers;
};

// Makes the cache's tree and neighbour lists current for `positions` if too many sites moved
// too far since they were made (or there are none), and says how stale they are.
Staleness refresh_neighbours(const LiftedPoints& positions, int threads, RvdCache& cache) {
    const long ns = positions.rows();
    Staleness st;
    st.is_mover.assign(ns, 0);
    // Movers are few when the sites settle; a rebuild once they are too many for this.
    const size_t max_movers = static_cast<size_t>(std::max(32L, ns / 128));
    if (cache.tree && cache.anchor.rows() == ns && cache.k > 0) {
        st.displacement = (positions - cache.anchor).rowwise().norm();
        for (long s = 0; s < ns && st.movers.size() <= max_movers; ++s)
            if (st.displacement[s] > cache.rebuild_distance) st.movers.push_back(static_cast<int32_t>(s));
        if (st.movers.size() <= max_movers) {
            for (int32_t m : st.movers) st.is_mover[m] = 1;
            for (long s = 0; s < ns; ++s)
                if (!st.is_mover[s]) st.rest = std::max(st.rest, st.displacement[s]);
            st.reach = 3.0 * cache.spacing;
            std::vector<std::pair<int32_t, int32_t>> pairs; // (site, mover)
            std::vector<int32_t> found;
            for (int32_t m : st.movers) {
                found.clear();
                cache.tree->within(positions.row(m).data(), st.reach, found);
                for (int32_t k : found)
                    if (k != m && !st.is_mover[k]) pairs.emplace_back(k, m);
            }
            st.near_movers = compress_rows(ns, pairs);
            return st;
        }
        st.movers.clear(); // is_mover is still all zero
    }
    st.displacement = Eigen::VectorXd::Zero(ns);
    // The lists made at the previous anchor hint the new ones: most neighbours stay neighbours.
    std::vector<int32_t> previous;
    const int previous_k = cache.tree && cache.anchor.rows() == ns ? cache.k : 0;
    if (previous_k > 0) previous.swap(cache.neighbours);
    cache.anchor = positions;
    cache.tree = std::make_shared<const KdTree>(positions);
    const KdTree& tree = *cache.tree;
    cache.k = static_cast<int>(std::min<long>(ns, 24));
    cache.neighbours.resize(static_cast<size_t>(ns) * cache.k);
    cache.distances2.resize(cache.neighbours.size());
    const int k = cache.k;
#pragma omp parallel for num_threads(threads) schedule(static, 256)
    for (long s = 0; s < ns; ++s)
        tree.knn(positions.row(s).data(), k, &cache.neighbours[s * k], &cache.distances2[s * k],
                 previous_k > 0 ? &previous[s * previous_k] : nullptr, previous_k);
    // Typical spacing: the median distance to the nearest other site.
    std::vector<double> nearest;
    for (long s = 0; s < ns; ++s)
        if (k > 1) nearest.push_back(std::sqrt(cache.distances2[s * k + 1]));
    if (!nearest.empty()) {
        std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
        cache.spacing = nearest[nearest.size() / 2];
        cache.rebuild_distance = 0.35 * cache.spacing;
    }
    ++cache.rebuilds;
    return st;
}

} // namespace

// Per-site scratch valid while a stamp equals the current triangle: its planar coordinates,
// computed once per triangle, and whether the site was queued already.
struct SiteScratch {
    int32_t planar_stamp = -1, visited_stamp = -1;
    PlanarSite planar;
}; // one cache line holds two

struct RvdScratch {
    struct OfThread {
        std::vector<SiteScratch> site;
        //! Per site, the chunk that last visited it and its rank there (RvdPolygon::chunk_rank).
        std::vector<std::pair<int32_t, int32_t>> rank;
    };
    std::vector<std::unique_ptr<OfThread>> threads; // apart, so that threads do not share lines
};

namespace {

template <int D>
void compute_rvd_fixed(const LiftedSurface& surface, const LiftedPoints& sites, int threads,
                       const PolygonVisitor& visit, RvdCache& cache) {
    using Vec = Eigen::Matrix<double, D, 1>;
    using Map = Eigen::Map<const Vec>;
    const long ns = static_cast<long>(sites.rows());
    const long nf = static_cast<long>(surface.triangles.rows());
    if (ns == 0) return;
    // Neighbours are searched in R^3 (the first three coordinates) even on the lifted surface:
    // 3D queries are far cheaper, and since the 3D distance never exceeds the lifted one,
    // walking the candidates in 3D order and stopping once d_3(k, l) > 2R (R measured in R^d)
    // still proves that no site left out can cut the polygon.
    const LiftedPoints positions = sites.leftCols(3);
    auto lifted_d2 = [&](long a, const double* b) { return (Map(sites.row(a).data()) - Map(b)).squaredNorm(); };

    // Tree and nearest-neighbour lists, possibly from an earlier diagram: made at the anchor
    // positions, from which all sites but a few movers are at most st.rest away (see RvdCache).
    const Staleness st = refresh_neighbours(positions, threads, cache);
    const char* const is_mover = st.is_mover.data(); // read for every listed neighbour: a local
                                                      // pointer, not reloaded through `st`
    const KdTree& tree = *cache.tree;
    const int k_cached = cache.k;
    const int32_t* nn = cache.neighbours.data();
    const double* nn_d2 = cache.distances2.data();
    if (static_cast<long>(cache.seeds.size()) != nf) cache.seeds.assign(nf, -1);
    // Chunks: contiguous runs of the Morton order (their own part of the surface, so their own
    // sites in a thread's cache) with as much work as the others had last time, taken by the
    // threads as they come. One fixed run per thread leaves threads idle at the end of the
    // diagram wherever the host slows them down unevenly; many smaller chunks even that out.
    if (static_cast<long>(cache.work.size()) != nf) cache.work.assign(nf, 1);
    const int chunks = rvd_chunks(surface);
    cache.chunk_sites.assign(chunks, 0);
    std::vector<long> bounds(static_cast<size_t>(chunks) + 1, nf);
    bounds[0] = 0;
    {
        double total = 0.0;
        for (int32_t w : cache.work) total += w;
        double done = 0.0;
        int c = 1;
        for (long i = 0; i < nf && c < chunks; ++i) {
            done += cache.work[i];
            while (c < chunks && done >= total * c / chunks) bounds[c++] = i + 1;
        }
    }

    if (!cache.scratch) cache.scratch = std::make_shared<RvdScratch>();
    while (static_cast<int>(cache.scratch->threads.size()) < threads)
        cache.scratch->threads.push_back(std::make_unique<RvdScratch::OfThread>());

#pragma omp parallel num_threads(threads)
    {
        auto buffers = std::make_unique<Polygon2[]>(2); // swapped by pointer after each clip
        Polygon2* poly = &buffers[0];
        Polygon2* scratch = &buffers[1];
        std::vector<PlanarSite> edge_sites(Polygon2::kCapacity);
        std::vector<int32_t> queue, more;
        std::vector<double> more_d2;
        std::vector<int32_t> candidates;
        RvdScratch::OfThread& mine = *cache.scratch->threads[thread_index()];
        std::vector<SiteScratch>& scratch_of = mine.site;
        std::vector<std::pair<int32_t, int32_t>>& rank_of = mine.rank;
        scratch_of.assign(ns, SiteScratch{});
        rank_of.assign(ns, {-1, -1});
#pragma omp for schedule(dynamic, 1)
        for (int chunk = 0; chunk < chunks; ++chunk) {
            int32_t ranks = 0; // sites of this chunk so far
            for (long p = bounds[chunk]; p < bounds[chunk + 1]; ++p) {
                if (!surface.valid[p]) continue;
                int32_t work = 1; // polygons and bisector tests on this triangle
                const Vec x0 = Map(surface.points.row(surface.triangles(p, 0)).data());
                const Vec x1 = Map(surface.points.row(surface.triangles(p, 1)).data());
                const Vec x2 = Map(surface.points.row(surface.triangles(p, 2)).data());
                const Vec u1 = Map(surface.u1.row(p).data()), u2 = Map(surface.u2.row(p).data());
                const Eigen::Vector2d c0(0.0, 0.0), c1((x1 - x0).dot(u1), 0.0), c2((x2 - x0).dot(u1), (x2 - x0).dot(u2));
                auto planar = [&](long s) -> const PlanarSite& {
                    SiteScratch& sc = scratch_of[s];
                    if (sc.planar_stamp != p) {
                        const Vec w = Map(sites.row(s).data()) - x0;
                        sc.planar = PlanarSite{Eigen::Vector2d(w.dot(u1), w.dot(u2)), w.squaredNorm()};
                        sc.planar_stamp = static_cast<int32_t>(p);
                    }
                    return sc.planar;
                };
                auto enqueue = [&](int32_t s) {
                    if (scratch_of[s].visited_stamp == p) return false;
                    scratch_of[s].visited_stamp = static_cast<int32_t>(p);
                    // Its neighbour list is read when its turn in the queue comes: asked for
                    // now, its loads overlap the work done until then.
                    __builtin_prefetch(&nn[s * k_cached]);
                    __builtin_prefetch(&nn_d2[s * k_cached]);
                    if (k_cached > 8) __builtin_prefetch(&nn_d2[s * k_cached + 8]); // its second line
                    queue.push_back(s);
                    return true;
                };
                // Seed: any site whose cell meets the triangle; propagation finds the others. The
                // one that met it last time usually still does; otherwise the site nearest to the
                // centroid in R^d, which owns it: it lies within the lifted distance rho of any
                // site, so within the 3D distance rho now, and rho + st.rest at the anchor unless
                // it is a mover.
                const Vec centroid = (x0 + x1 + x2) / 3.0;
                auto exact_seed = [&]() {
                    int32_t first = tree.nearest(centroid.data());
                    double best = lifted_d2(first, centroid.data());
                    candidates.assign(st.movers.begin(), st.movers.end());
                    tree.within(centroid.data(), std::sqrt(best) + st.rest, candidates);
                    for (int32_t c : candidates)
                        if (const double d2 = lifted_d2(c, centroid.data()); d2 < best || (d2 == best && c < first)) {
                            best = d2;
                            first = c;
                        }
                    return first;
                };
                const int32_t remembered = cache.seeds[p];
                bool seed_is_exact = remembered < 0 || remembered >= ns;
                const int32_t first = seed_is_exact ? exact_seed() : remembered;
                bool any_polygon = false;
                queue.clear();
                enqueue(first);
                while (!queue.empty() || (!any_polygon && !seed_is_exact)) {
                    if (queue.empty()) { // the remembered seed no longer meets the triangle
                        seed_is_exact = true;
                        if (!enqueue(exact_seed())) break;
                    }
                    const int32_t k = queue.back();
                    queue.pop_back();
                    // The nearest neighbours' rows, which the first cuts read one after the
                    // other, asked for at once: their loads overlap instead of waiting in turn.
                    for (int j = 0; j < std::min(k_cached, 8); ++j) {
                        const int32_t l = nn[k * k_cached + j];
                        __builtin_prefetch(sites.row(l).data());
                        __builtin_prefetch(&scratch_of[l]);
                    }
                    const PlanarSite vk = planar(k);
                    const double off_plane2 = vk.off_plane2();
                    poly->n = 0;
                    poly->push(c0, -1);
                    poly->push(c1, -2);
                    poly->push(c2, -3);
                    // Candidates in order of distance from a query point q: the anchor of k, or k
                    // itself if it is a mover (its list is made now). A site l other than a mover
                    // is at most st.rest from its anchor, so |v_k - v_l| >= |q - anchor_l| - slack,
                    // and no site at more than 2 sqrt(r2) from k can cut the polygon: none at
                    // |q - anchor_l|^2 > stop_d2 can.
                    const bool k_moves = is_mover[k];
                    const double* query = k_moves ? positions.row(k).data() : cache.anchor.row(k).data();
                    const double slack = (k_moves ? 0.0 : st.displacement[k]) + st.rest;
                    double r2 = max_squared_distance(*poly, vk.ab, off_plane2);
                    // (2 sqrt(r2) + slack)^2, made when needed: it is at least 4 r2, so a listed
                    // distance below that goes on without the square root, which clipping a
                    // polygon would otherwise pay at every cut.
                    double stop_d2 = -1.0;
                    auto security_d2 = [&]() {
                        if (stop_d2 < 0.0) {
                            const double reach = 2.0 * std::sqrt(r2) + slack;
                            stop_d2 = reach * reach;
                        }
                        return stop_d2;
                    };
                    auto beyond_security = [&](double d2) { return d2 > 4.0 * r2 && d2 > security_d2(); };
                    // From the sites' rows, which planar() reads next, not from `positions`:
                    // one row in the cache for each neighbour instead of two.
                    const Eigen::Vector3d pk = sites.row(k).template head<3>().transpose();
                    // Applies the bisector of k and l if l is near enough to cut the polygon.
                    enum Outcome { kGoOn, kEmpty, kFull };
                    auto cut_by = [&](int32_t l) {
                        ++work;
                        const double d2 = (sites.row(l).template head<3>().transpose() - pk).squaredNorm();
                        if (d2 > 4.0 * r2) return kGoOn; // too far to cut this polygon
                        // Coincident sites: the lower index owns the cell.
                        if (d2 == 0.0 && lifted_d2(l, sites.row(k).data()) == 0.0) {
                            if (l > k) return kGoOn;
                            enqueue(l); // l owns this cell: propagate through it instead
                            return kEmpty;
                        }
                        if (poly->full()) return kFull; // cannot happen for a Voronoi cell of a sane sampling
                        if (!clip_by_bisector(*poly, vk, planar(l), l, *scratch)) return kGoOn;
                        std::swap(poly, scratch);
                        if (poly->n < 3) return kEmpty;
                        r2 = max_squared_distance(*poly, vk.ab, off_plane2);
                        stop_d2 = -1.0;
                        return kGoOn;
                    };
                    const int32_t* list = &nn[k * k_cached];
                    const double* list_d2 = &nn_d2[k * k_cached];
                    int count = k_cached;
                    if (k_moves) {
                        more.resize(k_cached);
                        more_d2.resize(k_cached);
                        count = tree.knn(query, k_cached, more.data(), more_d2.data());
                        list = more.data();
                        list_d2 = more_d2.data();
                    }
                    Outcome outcome = kGoOn;
                    bool complete = false; // the list holds every site within the security radius
                    for (int j = 0;; ++j) {
                        if (j == count) { // ran out of listed neighbours
                            if (complete || count >= ns) break;
                            // Before the security radius: every site within it, from the tree, in
                            // the same order as a longer list would give (ties aside). It only
                            // shrinks from here. Bisectors already applied cut nothing the
                            // second time.
                            count = tree.within_sorted(query, security_d2(), more, more_d2);
                            list = more.data();
                            list_d2 = more_d2.data();
                            complete = true;
                            j = 0;
                            if (count == 0) break;
                        }
                        const int32_t l = list[j];
                        if (l == k || is_mover[l]) continue; // movers come below
                        if (beyond_security(list_d2[j])) break; // security radius reached: so are all later and unlisted sites
                        if ((outcome = cut_by(l)) != kGoOn) break;
                    }
                    // The movers, wherever they are: those near k's anchor if that is far enough,
                    // else all. The polygon only shrinks, so those left out by the radius at this
                    // point could cut nothing either.
                    if (!st.movers.empty() && outcome == kGoOn) {
                        // The search is strict.
                        const bool near_enough = !k_moves && 2.0 * std::sqrt(r2) + st.displacement[k] < st.reach;
                        const int32_t* m = near_enough ? st.near_movers.begin(k) : st.movers.data();
                        const int32_t* end = near_enough ? st.near_movers.end(k) : st.movers.data() + st.movers.size();
                        for (; outcome == kGoOn && m != end; ++m)
                            if (*m != k) outcome = cut_by(*m);
                    }
                    const bool empty = outcome == kEmpty;
                    if (empty) continue;
                    if (!any_polygon && cache.seeds[p] != k) cache.seeds[p] = k; // no write (cache line) if unchanged
                    any_polygon = true;
                    RvdPolygon out;
                    out.site = k;
                    out.triangle = static_cast<int32_t>(p);
                    out.size = poly->n;
                    out.planar = poly->v[0].data(); // Vector2d has no padding: size x 2 doubles
                    out.edges = poly->e;
                    out.site_planar = vk;
                    for (int i = 0; i < poly->n; ++i)
                        if (poly->e[i] >= 0) edge_sites[i] = planar(poly->e[i]);
                    out.edge_sites = edge_sites.data();
                    if (rank_of[k].first != chunk) rank_of[k] = {chunk, ranks++};
                    out.chunk_rank = rank_of[k].second;
                    visit(chunk, out);
                    work += poly->n;
                    for (int i = 0; i < poly->n; ++i)
                        if (poly->e[i] >= 0) enqueue(poly->e[i]);
                }
                cache.work[p] = work;
            }
            cache.chunk_sites[chunk] = ranks;
        }
    }
}

} // namespace

void compute_rvd(const LiftedSurface& surface, const LiftedPoints& sites, int threads, const PolygonVisitor& visit,
                 RvdCache* cache) {
    if (sites.cols() != surface.dimension())
        throw InvalidInput("sites have " + std::to_string(sites.cols()) + " coordinates, the surface " +
                           std::to_string(surface.dimension()));
    if (!sites.allFinite()) throw NumericalFailure("a site has a non-finite coordinate");
    const int n = resolve_threads(threads);
    RvdCache local;
    RvdCache& c = cache ? *cache : local;
    if (surface.dimension() == 3)
        compute_rvd_fixed<3>(surface, sites, n, visit, c);
    else
        compute_rvd_fixed<6>(surface, sites, n, visit, c);
}

namespace {

// Per site, the areas of its cell's polygons, each times weight(triangle).
template <class Weight>
Eigen::VectorXd cell_sums(const LiftedSurface& surface, const LiftedPoints& sites, int threads, RvdCache* cache,
                          Weight weight) {
    ChunkSiteSums<double> areas(surface, 0.0, cache);
    compute_rvd(
        surface, sites, threads,
        [&](int chunk, const RvdPolygon& poly) { areas.of(chunk, poly) += weight(poly.triangle) * polygon_area(poly); },
        cache);
    Eigen::VectorXd total = Eigen::VectorXd::Zero(sites.rows());
    areas.for_each([&](int32_t site, double area) { total[site] += area; });
    return total;
}

} // namespace

Eigen::VectorXd restricted_cell_areas(const LiftedSurface& surface, const LiftedPoints& sites, int threads,
                                      RvdCache* cache) {
    return cell_sums(surface, sites, threads, cache, [](long) { return 1.0; });
}

Eigen::VectorXd restricted_cell_masses(const LiftedSurface& surface, const LiftedPoints& sites, int threads,
                                       RvdCache* cache) {
    return cell_sums(surface, sites, threads, cache, [&](long p) { return surface.weights[p]; });
}

} // namespace liftremesh
