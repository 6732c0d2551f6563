#include "liftremesh/cvt_energy.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/geometry.h"

#include <cmath>
#include <vector>

namespace liftremesh {

namespace {

template <int D>
struct ObjectiveAccumulator {
    using Vec = Eigen::Matrix<double, D, 1>;
    using Map = Eigen::Map<const Vec>;
    const LiftedSurface& surface;
    const LiftedPoints& sites;
    double sigma;
    std::vector<double> value;        // per thread
    std::vector<LiftedPoints> grad;   // per thread, #S by D

    ObjectiveAccumulator(const LiftedSurface& s, const LiftedPoints& v, double sig, int threads)
        : surface(s), sites(v), sigma(sig), value(threads, 0.0), grad(threads, LiftedPoints::Zero(v.rows(), D)) {}

    // Pi_p y: the component of y normal to triangle p (Eq. 13, 14).
    Vec normal_part(long p, const Vec& y) const {
        const Map u1(surface.u1.row(p).data()), u2(surface.u2.row(p).data());
        return y - u1 * u1.dot(y) - u2 * u2.dot(y);
    }
    Vec tangent_part(long p, const Vec& y) const {
        const Map u1(surface.u1.row(p).data()), u2(surface.u2.row(p).data());
        return u1 * u1.dot(y) + u2 * u2.dot(y);
    }

    void operator()(int thread, const RvdPolygon& poly) {
        const long k = poly.site, p = poly.triangle;
        const double w = surface.weights[p]; // rho_p^delta, Eq. 25
        const Vec vk = Map(sites.row(k).data());
        auto vertex = [&](int i) { return Map(poly.vertices + static_cast<long>(i) * D); };

        // Inner part, as if no feature sensitivity (Algorithm 2, lines 3-7).
        double area = 0.0, f = 0.0;
        Vec moment = Vec::Zero();
        const Vec w1 = vertex(0) - vk;
        for (int i = 1; i + 1 < poly.size; ++i) {
            const Vec w2 = vertex(i) - vk, w3 = vertex(i + 1) - vk;
            const double a = triangle_area(w1, w2, w3);
            // Eq. 6: int_T |x - v|^2 = |T|/6 (sum over the 6 unordered pairs (i <= j) of w_i . w_j)
            f += a / 6.0 * (w1.squaredNorm() + w2.squaredNorm() + w3.squaredNorm() + w1.dot(w2) + w2.dot(w3) + w1.dot(w3));
            area += a;
            moment += a * (vertex(0) + vertex(i) + vertex(i + 1)) / 3.0;
        }
        Vec g = 2.0 * (area * vk - moment); // Eq. 7

        if (sigma > 1.0) { // feature sensitivity (lines 8-18)
            const double s2 = sigma * sigma - 1.0;
            const Vec wk = normal_part(p, vertex(0) - vk); // constant over the triangle
            const double wk2 = wk.squaredNorm();
            f += s2 * area * wk2;  // Eq. 11: the normal component, weighted by sigma^2 - 1
            g -= 2.0 * s2 * area * wk; // Eq. 17
            for (int i = 0; i < poly.size; ++i) {
                const int32_t l = poly.edges[i];
                if (l < 0) continue; // a piece of the triangle's edge: no boundary term
                const Vec vl = Map(sites.row(l).data());
                const Vec c1 = vertex(i), c2 = vertex((i + 1) % poly.size);
                // n_{k,l,p} . (v_l - v_k) = |tangential part of v_l - v_k|: the bisector's in-plane normal.
                const double denom = tangent_part(p, vl - vk).norm();
                if (!(denom > 0.0)) continue;
                const double wl2 = normal_part(p, c1 - vl).squaredNorm();
                const double len = (c2 - c1).norm();
                g += (s2 * len * (wk2 - wl2) / denom) * (0.5 * (c1 + c2) - vk); // Eq. 20
            }
        }
        value[thread] += w * f;
        grad[thread].row(k) += w * g.transpose();
    }
};

template <int D>
double objective_fixed(const LiftedSurface& surface, const LiftedPoints& sites, double sigma, int threads,
                       LiftedPoints& gradient, RvdCache* cache) {
    ObjectiveAccumulator<D> acc(surface, sites, sigma, threads);
    compute_rvd(surface, sites, threads, [&acc](int thread, const RvdPolygon& poly) { acc(thread, poly); }, cache);
    double total = 0.0;
    gradient = LiftedPoints::Zero(sites.rows(), D);
    for (int t = 0; t < threads; ++t) {
        total += acc.value[t];
        gradient += acc.grad[t];
    }
    return total;
}

} // namespace

double cvt_objective(const LiftedSurface& surface, const LiftedPoints& sites, double sigma, int threads,
                     LiftedPoints& gradient, RvdCache* cache) {
    const int n = resolve_threads(threads);
    const double f = surface.dimension() == 3 ? objective_fixed<3>(surface, sites, sigma, n, gradient, cache)
                                              : objective_fixed<6>(surface, sites, sigma, n, gradient, cache);
    if (!std::isfinite(f) || !gradient.allFinite())
        throw NumericalFailure("the objective or its gradient is not finite (degenerate sites or surface)");
    return f;
}

} // namespace liftremesh
