#include "liftremesh/cvt/sampling.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace liftremesh {

namespace {
// Triangle f's share of the sites: |T_p| sqrt(w_p), 0 for an invalid triangle.
double sampling_weight(const LiftedSurface& surface, Eigen::Index f) {
    if (!surface.valid[f]) return 0.0;
    return triangle_area(surface.points.row(surface.triangles(f, 0)), surface.points.row(surface.triangles(f, 1)),
                         surface.points.row(surface.triangles(f, 2))) *
           std::sqrt(surface.weights[f]);
}

// The running sums of the triangles' shares, taken as they were given (LiftedSurface::row_of),
// so that a seed draws the same sites whatever order the surface stores them in. The shares
// are worked out row after row, each row's data read after the last one's.
std::vector<double> cumulative_weights(const LiftedSurface& surface) {
    const Eigen::Index nf = surface.triangles.rows();
    std::vector<double> share(static_cast<size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f) share[f] = sampling_weight(surface, f);
    std::vector<double> cumulative(static_cast<size_t>(nf));
    double total = 0.0;
    for (Eigen::Index g = 0; g < nf; ++g) cumulative[g] = total += share[surface.row_of[g]];
    return cumulative;
}

} // namespace

double sampling_mass(const LiftedSurface& surface) {
    const std::vector<double> cumulative = cumulative_weights(surface);
    return cumulative.empty() ? 0.0 : cumulative.back();
}

LiftedPoints random_sites(const LiftedSurface& surface, long count, std::uint64_t seed) {
    const Eigen::Index nf = surface.triangles.rows();
    const std::vector<double> cumulative = cumulative_weights(surface);
    const double total = cumulative.empty() ? 0.0 : cumulative.back();
    if (!(total > 0.0)) throw InvalidInput("the surface has no triangle of positive area to place sites on");
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    LiftedPoints sites(count, surface.dimension());
    for (long k = 0; k < count; ++k) {
        const double r = u01(rng) * total;
        const Eigen::Index f = surface.row_of[std::min<Eigen::Index>(
            nf - 1, std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin())];
        double a = u01(rng), b = u01(rng);
        if (a + b > 1.0) {
            a = 1.0 - a;
            b = 1.0 - b;
        }
        sites.row(k) = (1.0 - a - b) * surface.points.row(surface.triangles(f, 0)) +
                       a * surface.points.row(surface.triangles(f, 1)) + b * surface.points.row(surface.triangles(f, 2));
    }
    // Near in space, near in memory: the diagram's kd-tree queries and clipping then mostly hit
    // the cache (sites move little during the optimisation).
    const std::vector<long> order = morton_order(sites.data(), count, static_cast<int>(sites.cols()));
    LiftedPoints sorted(count, sites.cols());
    for (long i = 0; i < count; ++i) sorted.row(i) = sites.row(order[i]);
    return sorted;
}

} // namespace liftremesh
