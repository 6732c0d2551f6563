#include "liftremesh/cvt/cvt_energy.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"

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
    // Per chunk of the diagram, its part of the objective and of each site's gradient, added up
    // chunk after chunk: the same sums, to the bit, whatever the thread count.
    std::vector<ChunkSlot<double>> values;
    ChunkSiteSums<Vec> gradients;

    ObjectiveAccumulator(const LiftedSurface& s, const LiftedPoints& v, double sig, const RvdCache* cache)
        : surface(s), sites(v), sigma(sig), values(rvd_chunks(s)), gradients(s, Vec::Zero(), cache) {}

    double total(LiftedPoints& gradient) const {
        double value = 0.0;
        for (const auto& chunk : values) value += chunk.value;
        gradient = LiftedPoints::Zero(sites.rows(), D);
        gradients.for_each([&](int32_t site, const Vec& g) { gradient.row(site) += g.transpose(); });
        return value;
    }

    // Every polygon lies in the plane of its triangle p and arrives in p's orthonormal frame
    // (x = x0 + a u1 + b u2), so the integrals are 2D ones: with w_k = v_k - x0 split into its
    // in-plane part s_k and its part normal to the plane (length^2 o_k), |x - v_k|^2 =
    // |(a, b) - s_k|^2 + o_k, and Pi_p (x - v_k) = -(normal part of w_k) for every x (Eq. 13).
    void operator()(int chunk, const RvdPolygon& poly) {
        const long k = poly.site, p = poly.triangle;
        const double w = surface.weights[p]; // rho_p^delta, Eq. 25
        const Map x0(surface.points.row(surface.triangles(p, 0)).data());
        const Map u1(surface.u1.row(p).data()), u2(surface.u2.row(p).data());
        const Vec wk = Map(sites.row(k).data()) - x0;
        const Eigen::Vector2d sk = poly.site_planar.ab;
        const double ok = poly.site_planar.off_plane2();
        auto vertex = [&](int i) { return Eigen::Map<const Eigen::Vector2d>(poly.planar + 2 * i); };

        // Inner part, as if no feature sensitivity (Algorithm 2, lines 3-7), on a fan of the polygon.
        double area = 0.0, f = 0.0;
        Eigen::Vector2d moment = Eigen::Vector2d::Zero();
        const Eigen::Vector2d w1 = vertex(0) - sk;
        for (int i = 1; i + 1 < poly.size; ++i) {
            const Eigen::Vector2d w2 = vertex(i) - sk, w3 = vertex(i + 1) - sk;
            const Eigen::Vector2d e2 = w2 - w1, e3 = w3 - w1;
            const double a = 0.5 * std::abs(e2.x() * e3.y() - e2.y() * e3.x());
            // Eq. 6: int_T |x - v|^2 = |T|/6 (sum over the 6 unordered pairs (i <= j) of w_i . w_j)
            f += a / 6.0 * (w1.squaredNorm() + w2.squaredNorm() + w3.squaredNorm() + w1.dot(w2) + w2.dot(w3) + w1.dot(w3));
            area += a;
            moment += a * (vertex(0) + vertex(i) + vertex(i + 1)) / 3.0;
        }
        f += area * ok; // the part of |x - v_k|^2 normal to the plane, constant over it
        // Eq. 7: 2 (|Omega| v_k - int x) = 2 (|Omega| w_k - (moment.x u1 + moment.y u2)).
        Vec g = 2.0 * (area * wk - moment.x() * u1 - moment.y() * u2);

        if (sigma > 1.0) { // feature sensitivity (lines 8-18)
            const double s2 = sigma * sigma - 1.0;
            const Vec normal_k = wk - sk.x() * u1 - sk.y() * u2; // Pi_p w_k = -Pi_p (x - v_k)
            f += s2 * area * ok;              // Eq. 11: the normal component, weighted by sigma^2 - 1
            g += 2.0 * s2 * area * normal_k;  // Eq. 17: d/dv of s2 |Omega| |Pi (x - v)|^2
            // Eq. 20 on each bisector edge e = (c1, c2) with site l:
            //   (sigma^2 - 1) |e| (|Pi(c - v_k)|^2 - |Pi(c - v_l)|^2) / (n . (v_l - v_k)) (mid(e) - v_k),
            // where n . (v_l - v_k) = |s_l - s_k| (the bisector's in-plane normal is along s_l - s_k).
            // Summed as (sum coef mid) - (sum coef) w_k in the frame.
            double coef_sum = 0.0;
            Eigen::Vector2d coef_mid = Eigen::Vector2d::Zero();
            for (int i = 0; i < poly.size; ++i) {
                if (poly.edges[i] < 0) continue; // a piece of the triangle's edge: no boundary term
                const PlanarSite& sl = poly.edge_sites[i];
                const double denom = (sl.ab - sk).norm();
                if (!(denom > 0.0)) continue;
                const Eigen::Vector2d c1 = vertex(i), c2 = vertex(i + 1 == poly.size ? 0 : i + 1);
                const double coef = s2 * (c2 - c1).norm() * (ok - sl.off_plane2()) / denom;
                coef_sum += coef;
                coef_mid += coef * 0.5 * (c1 + c2);
            }
            g += coef_mid.x() * u1 + coef_mid.y() * u2 - coef_sum * wk;
        }
        values[chunk].value += w * f;
        gradients.of(chunk, poly) += w * g;
    }
};

template <int D>
double objective_fixed(const LiftedSurface& surface, const LiftedPoints& sites, double sigma, int threads,
                       LiftedPoints& gradient, RvdCache* cache) {
    ObjectiveAccumulator<D> acc(surface, sites, sigma, cache);
    compute_rvd(surface, sites, threads, [&acc](int chunk, const RvdPolygon& poly) { acc(chunk, poly); }, cache);
    return acc.total(gradient);
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
