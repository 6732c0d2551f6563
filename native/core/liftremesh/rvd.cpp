#include "liftremesh/rvd.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/geometry.h"
#include "liftremesh/neighbor_search.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
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

// A site seen from the plane of one triangle: its in-plane coordinates (a, b) and |v - x0|^2.
struct PlanarSite {
    Eigen::Vector2d ab;
    double norm2;
};

// Clips `in` to the points of the plane nearer to site k than to site l. With w = v - x0 and
// x = x0 + a u1 + b u2, |x - v_k|^2 <= |x - v_l|^2 reads (a, b).(ab_l - ab_k) <= (|w_l|^2 - |w_k|^2) / 2.
// Sutherland-Hodgman; the new edge carries the id l. Returns false, leaving `out` untouched,
// when the bisector misses the polygon (nothing cut).
bool clip_by_bisector(const Polygon2& in, const PlanarSite& k, const PlanarSite& l, int32_t id, Polygon2& out) {
    const Eigen::Vector2d dir = l.ab - k.ab;
    const double offset = 0.5 * (l.norm2 - k.norm2);
    double side[Polygon2::kCapacity];
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
            out.push(in.v[i] + t * (in.v[j] - in.v[i]), in_i ? id : in.e[i]); // leaving: the bisector follows
        }
    }
    return true;
}

// Largest squared distance from a site to the polygon's vertices, in R^d: in-plane part plus
// the site's squared distance to the plane.
double max_squared_distance(const Polygon2& p, const Eigen::Vector2d& ab, double off_plane2) {
    double r2 = 0.0;
    for (int i = 0; i < p.n; ++i) r2 = std::max(r2, (p.v[i] - ab).squaredNorm());
    return r2 + off_plane2;
}

template <int D>
void compute_rvd_fixed(const LiftedSurface& surface, const LiftedPoints& sites, int threads,
                       const PolygonVisitor& visit) {
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
    const KdTree tree(positions);
    auto lifted_d2 = [&](long a, const double* b) { return (Map(sites.row(a).data()) - Map(b)).squaredNorm(); };

    // Nearest neighbours of every site, computed once per diagram; rarely, a cell needs more.
    const int k_cached = static_cast<int>(std::min<long>(ns, 16));
    std::vector<int32_t> nn(static_cast<size_t>(ns) * k_cached);
    std::vector<double> nn_d2(nn.size());
#pragma omp parallel for num_threads(threads) schedule(static, 256)
    for (long k = 0; k < ns; ++k)
        tree.knn(positions.row(k).data(), k_cached, &nn[k * k_cached], &nn_d2[k * k_cached]);

#pragma omp parallel num_threads(threads)
    {
        const int thread = omp_get_thread_num();
        auto buffers = std::make_unique<Polygon2[]>(2); // swapped by pointer after each clip
        Polygon2* poly = &buffers[0];
        Polygon2* scratch = &buffers[1];
        std::vector<double> lifted; // the polygon handed to the visitor, size x D
        std::vector<int32_t> visited, queue, more;
        std::vector<double> more_d2;
        std::vector<int32_t> candidates;
#pragma omp for schedule(static, 16)
        for (long p = 0; p < nf; ++p) {
            if (!surface.valid[p]) continue;
            const Vec x0 = Map(surface.points.row(surface.triangles(p, 0)).data());
            const Vec x1 = Map(surface.points.row(surface.triangles(p, 1)).data());
            const Vec x2 = Map(surface.points.row(surface.triangles(p, 2)).data());
            const Vec u1 = Map(surface.u1.row(p).data()), u2 = Map(surface.u2.row(p).data());
            const Eigen::Vector2d c0(0.0, 0.0), c1((x1 - x0).dot(u1), 0.0), c2((x2 - x0).dot(u1), (x2 - x0).dot(u2));
            auto planar = [&](long s) {
                const Vec w = Map(sites.row(s).data()) - x0;
                return PlanarSite{Eigen::Vector2d(w.dot(u1), w.dot(u2)), w.squaredNorm()};
            };
            // Seed: the site nearest to the centroid in R^d, which owns it. It is within the
            // lifted distance rho of the 3D-nearest site, so a 3D ball of radius rho holds it.
            const Vec centroid = (x0 + x1 + x2) / 3.0;
            int32_t first = tree.nearest(centroid.data());
            double best = lifted_d2(first, centroid.data());
            candidates.clear();
            tree.within(centroid.data(), std::sqrt(best), candidates);
            for (int32_t c : candidates)
                if (const double d2 = lifted_d2(c, centroid.data()); d2 < best || (d2 == best && c < first)) {
                    best = d2;
                    first = c;
                }
            visited.assign(1, first);
            queue.assign(1, first);
            while (!queue.empty()) {
                const int32_t k = queue.back();
                queue.pop_back();
                const PlanarSite vk = planar(k);
                const double off_plane2 = std::max(0.0, vk.norm2 - vk.ab.squaredNorm());
                poly->n = 0;
                poly->push(c0, -1);
                poly->push(c1, -2);
                poly->push(c2, -3);
                double r2 = max_squared_distance(*poly, vk.ab, off_plane2);
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
                        count = tree.knn(positions.row(k).data(), wanted, more.data(), more_d2.data());
                        list = more.data();
                        list_d2 = more_d2.data();
                        if (j >= count) break;
                    }
                    const int32_t l = list[j];
                    if (l == k) continue;
                    if (list_d2[j] > 4.0 * r2) break; // security radius reached: no farther site can cut
                    if (list_d2[j] == 0.0 && lifted_d2(l, sites.row(k).data()) == 0.0) { // coincident sites: the lower index owns the cell
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
                    if (!clip_by_bisector(*poly, vk, planar(l), l, *scratch)) continue;
                    std::swap(poly, scratch);
                    if (poly->n < 3) { empty = true; break; }
                    r2 = max_squared_distance(*poly, vk.ab, off_plane2);
                }
                if (empty) continue;
                lifted.resize(static_cast<size_t>(poly->n) * D);
                for (int i = 0; i < poly->n; ++i)
                    Eigen::Map<Vec>(lifted.data() + static_cast<size_t>(i) * D) = x0 + poly->v[i].x() * u1 + poly->v[i].y() * u2;
                RvdPolygon out;
                out.site = k;
                out.triangle = static_cast<int32_t>(p);
                out.size = poly->n;
                out.vertices = lifted.data();
                out.edges = poly->e;
                visit(thread, out);
                for (int i = 0; i < poly->n; ++i)
                    if (const int32_t id = poly->e[i];
                        id >= 0 && std::find(visited.begin(), visited.end(), id) == visited.end()) {
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
