#include "liftremesh/rvd.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/geometry.h"
#include "liftremesh/neighbor_search.h"

#include <omp.h>

#include <algorithm>
#include <memory>

namespace liftremesh {

LiftedSurface make_lifted_surface(LiftedPoints points, Triangles triangles, Eigen::VectorXd weights) {
    LiftedSurface s;
    const int d = static_cast<int>(points.cols());
    if (d != 3 && d != 6) throw InvalidInput("lifted points have " + std::to_string(d) + " columns, expected 3 or 6");
    const Eigen::Index nf = triangles.rows();
    s.points = std::move(points);
    s.triangles = std::move(triangles);
    s.weights = weights.size() == nf ? std::move(weights) : Eigen::VectorXd::Ones(nf);
    s.u1 = LiftedPoints::Zero(nf, d);
    s.u2 = LiftedPoints::Zero(nf, d);
    s.valid.assign(nf, 0);
    for (Eigen::Index f = 0; f < nf; ++f) {
        const Eigen::VectorXd x1 = s.points.row(s.triangles(f, 0)).transpose();
        const Eigen::VectorXd x2 = s.points.row(s.triangles(f, 1)).transpose();
        const Eigen::VectorXd x3 = s.points.row(s.triangles(f, 2)).transpose();
        Eigen::VectorXd u1, u2;
        if (tangent_basis<Eigen::Dynamic>(x1, x2, x3, u1, u2)) { // Eq. 15
            s.u1.row(f) = u1.transpose();
            s.u2.row(f) = u2.transpose();
            s.valid[f] = 1;
        }
    }
    return s;
}

double lifted_area(const LiftedSurface& s) {
    double total = 0.0;
    for (Eigen::Index f = 0; f < s.triangles.rows(); ++f)
        if (s.valid[f])
            total += triangle_area(s.points.row(s.triangles(f, 0)), s.points.row(s.triangles(f, 1)),
                                   s.points.row(s.triangles(f, 2)));
    return total;
}

int resolve_threads(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

namespace {

// A convex polygon in R^D with the line id of each edge (see RvdPolygon::edges), in fixed
// storage: clipping a triangle by n half-spaces gives at most 3 + n vertices, and a cell is
// clipped by a few tens of bisectors at most; a polygon that would grow past the capacity is
// left as it is by the clip (the caller then stops clipping it, see `full()`).
template <int D>
struct Polygon {
    using Vec = Eigen::Matrix<double, D, 1>;
    static constexpr int kCapacity = 96;
    Vec v[kCapacity];
    int32_t e[kCapacity];
    int n = 0;
    void push(const Vec& x, int32_t id) {
        v[n] = x;
        e[n++] = id;
    }
    bool full() const { return n + 1 >= kCapacity; }
};

// Clips `in` to the half-space of points nearer to vk than to vl,
// (x - (vk + vl)/2) . (vl - vk) <= 0 (Sutherland-Hodgman), the new edge carrying the id l.
// Returns false, leaving `out` untouched, when the bisector misses the polygon (nothing cut).
template <int D>
bool clip_by_bisector(const Polygon<D>& in, const typename Polygon<D>::Vec& vk, const typename Polygon<D>::Vec& vl,
                      int32_t l, Polygon<D>& out) {
    using Vec = typename Polygon<D>::Vec;
    const Vec dir = vl - vk;
    const double offset = 0.5 * (vk + vl).dot(dir);
    double side[Polygon<D>::kCapacity];
    bool any_out = false;
    for (int i = 0; i < in.n; ++i) {
        side[i] = in.v[i].dot(dir) - offset;
        any_out |= side[i] > 0.0;
    }
    if (!any_out) return false;
    out.n = 0;
    for (int i = 0; i < in.n; ++i) {
        const int j = i + 1 == in.n ? 0 : i + 1;
        const bool in_i = side[i] <= 0.0, in_j = side[j] <= 0.0;
        if (in_i) out.push(in.v[i], in.e[i]);
        if (in_i != in_j) {
            const double t = side[i] / (side[i] - side[j]);
            out.push(in.v[i] + t * (in.v[j] - in.v[i]), in_i ? l : in.e[i]); // leaving: the bisector follows
        }
    }
    return true;
}

template <int D>
double max_squared_distance(const Polygon<D>& p, const typename Polygon<D>::Vec& x) {
    double r2 = 0.0;
    for (int i = 0; i < p.n; ++i) r2 = std::max(r2, (p.v[i] - x).squaredNorm());
    return r2;
}

template <int D>
void compute_rvd_fixed(const LiftedSurface& surface, const LiftedPoints& sites, int threads,
                       const PolygonVisitor& visit) {
    using Vec = typename Polygon<D>::Vec;
    const long ns = static_cast<long>(sites.rows());
    const long nf = static_cast<long>(surface.triangles.rows());
    if (ns == 0) return;
    const KdTree tree(sites);
    auto site = [&](long k) { return Vec(Eigen::Map<const Vec>(sites.row(k).data())); };
    auto point = [&](int32_t i) { return Vec(Eigen::Map<const Vec>(surface.points.row(i).data())); };

    // Nearest neighbours of every site, computed once per diagram; rarely, a cell needs more.
    const int k_cached = static_cast<int>(std::min<long>(ns, 16));
    std::vector<int32_t> nn(static_cast<size_t>(ns) * k_cached);
    std::vector<double> nn_d2(nn.size());
#pragma omp parallel for num_threads(threads) schedule(static, 256)
    for (long k = 0; k < ns; ++k) tree.knn(sites.row(k).data(), k_cached, &nn[k * k_cached], &nn_d2[k * k_cached]);

#pragma omp parallel num_threads(threads)
    {
        const int thread = omp_get_thread_num();
        // Two polygons per thread, swapped by pointer after each clip (heap: they are large).
        auto buffers = std::make_unique<Polygon<D>[]>(2);
        Polygon<D>* poly = &buffers[0];
        Polygon<D>* scratch = &buffers[1];
        std::vector<int32_t> visited, queue, more;
        std::vector<double> more_d2;
        int32_t seeds[4];
        double seeds_d2[4];
#pragma omp for schedule(static, 16)
        for (long p = 0; p < nf; ++p) {
            if (!surface.valid[p]) continue;
            const Vec x0 = point(surface.triangles(p, 0)), x1 = point(surface.triangles(p, 1)),
                      x2 = point(surface.triangles(p, 2));
            const Vec centroid = (x0 + x1 + x2) / 3.0;
            // Seeds: the sites nearest to the centroid. The first one owns the centroid unless it
            // coincides with a lower-numbered site, in which case the next candidates are tried.
            int seeds_found = tree.knn(centroid.data(), std::min<int>(4, static_cast<int>(ns)), seeds, seeds_d2);
            int next_seed = 1;
            bool any_polygon = false;
            visited.assign(1, seeds[0]);
            queue.assign(1, seeds[0]);
            while (!queue.empty() || (!any_polygon && next_seed < seeds_found)) {
                if (queue.empty()) { // the seed's cell was empty: try the next nearest site
                    visited.push_back(seeds[next_seed]);
                    queue.push_back(seeds[next_seed++]);
                }
                const int32_t k = queue.back();
                queue.pop_back();
                const Vec vk = site(k);
                poly->n = 0;
                poly->push(x0, -1);
                poly->push(x1, -2);
                poly->push(x2, -3);
                double r2 = max_squared_distance(*poly, vk);
                const int32_t* list = &nn[k * k_cached];
                const double* list_d2 = &nn_d2[k * k_cached];
                int count = k_cached;
                bool empty = false;
                for (int j = 0;; ++j) {
                    if (j == count) { // ran out of cached neighbours before the security radius
                        if (count >= ns) break;
                        const int wanted = static_cast<int>(std::min<long>(ns, 2L * count));
                        more.resize(wanted);
                        more_d2.resize(wanted);
                        count = tree.knn(sites.row(k).data(), wanted, more.data(), more_d2.data());
                        list = more.data();
                        list_d2 = more_d2.data();
                        if (j >= count) break;
                    }
                    const int32_t l = list[j];
                    if (l == k) continue;
                    if (list_d2[j] > 4.0 * r2) break; // security radius reached
                    if (list_d2[j] == 0.0) {          // coincident sites: the lower index owns the cell
                        if (l < k) { // l owns this cell: propagate through it instead
                            empty = true;
                            if (std::find(visited.begin(), visited.end(), l) == visited.end()) {
                                visited.push_back(l);
                                queue.push_back(l);
                            }
                            break;
                        }
                        continue;
                    }
                    if (poly->full()) break; // cannot happen for a Voronoi cell of a sane sampling
                    if (!clip_by_bisector<D>(*poly, vk, Eigen::Map<const Vec>(sites.row(l).data()), l, *scratch))
                        continue;
                    std::swap(poly, scratch);
                    if (poly->n < 3) { empty = true; break; }
                    r2 = max_squared_distance(*poly, vk);
                }
                if (empty) continue;
                any_polygon = true;
                RvdPolygon out;
                out.site = k;
                out.triangle = static_cast<int32_t>(p);
                out.size = poly->n;
                out.vertices = poly->v[0].data(); // Vec has no padding: size x D doubles
                out.edges = poly->e;
                visit(thread, out);
                for (int i = 0; i < poly->n; ++i)
                    if (const int32_t id = poly->e[i]; id >= 0 && std::find(visited.begin(), visited.end(), id) == visited.end()) {
                        visited.push_back(id);
                        queue.push_back(id);
                    }
            }
        }
    }
}

} // namespace

void compute_rvd(const LiftedSurface& surface, const LiftedPoints& sites, int threads, const PolygonVisitor& visit) {
    if (sites.cols() != surface.dimension())
        throw InvalidInput("sites have " + std::to_string(sites.cols()) + " coordinates, the surface " +
                           std::to_string(surface.dimension()));
    if (!sites.allFinite()) throw NumericalFailure("a site has a non-finite coordinate");
    const int n = resolve_threads(threads);
    if (surface.dimension() == 3)
        compute_rvd_fixed<3>(surface, sites, n, visit);
    else
        compute_rvd_fixed<6>(surface, sites, n, visit);
}

Eigen::VectorXd restricted_cell_areas(const LiftedSurface& surface, const LiftedPoints& sites, int threads) {
    const int n = resolve_threads(threads);
    const int d = surface.dimension();
    std::vector<Eigen::VectorXd> per_thread(n, Eigen::VectorXd::Zero(sites.rows()));
    compute_rvd(surface, sites, n, [&](int thread, const RvdPolygon& poly) {
        using Row = Eigen::Map<const Eigen::VectorXd>;
        const Row c0(poly.vertices, d);
        for (int i = 1; i + 1 < poly.size; ++i)
            per_thread[thread][poly.site] +=
                triangle_area(c0, Row(poly.vertices + i * d, d), Row(poly.vertices + (i + 1) * d, d));
    });
    Eigen::VectorXd total = Eigen::VectorXd::Zero(sites.rows());
    for (const auto& a : per_thread) total += a;
    return total;
}

} // namespace liftremesh
