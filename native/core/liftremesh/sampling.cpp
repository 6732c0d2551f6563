#include "liftremesh/sampling.h"

#include "liftremesh/exceptions.h"
#include "liftremesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace liftremesh {

namespace {

// Interleaves the low 21 bits of x with two zero bits between each (for 3D Morton codes).
std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}

// Reorders the rows of `sites` along a Morton (Z-order) curve of their first three coordinates,
// so that sites near in space are near in memory: the kd-tree queries and clipping of the
// diagram then mostly hit the cache (sites move little during the optimisation).
void sort_spatially(LiftedPoints& sites) {
    const long n = sites.rows();
    if (n < 2) return;
    const Eigen::RowVector3d lo = sites.leftCols(3).colwise().minCoeff();
    const Eigen::RowVector3d extent = (sites.leftCols(3).colwise().maxCoeff() - lo).cwiseMax(1e-300);
    const double scale = static_cast<double>((1 << 21) - 1);
    std::vector<std::pair<std::uint64_t, long>> keys(n);
    for (long i = 0; i < n; ++i) {
        std::uint64_t code = 0;
        for (int j = 0; j < 3; ++j) {
            const auto q = static_cast<std::uint64_t>((sites(i, j) - lo[j]) / extent[j] * scale);
            code |= spread_bits(q) << j;
        }
        keys[i] = {code, i};
    }
    std::sort(keys.begin(), keys.end());
    LiftedPoints sorted(n, sites.cols());
    for (long i = 0; i < n; ++i) sorted.row(i) = sites.row(keys[i].second);
    sites = std::move(sorted);
}

} // namespace

LiftedPoints random_sites(const LiftedSurface& surface, long count, std::uint64_t seed) {
    const Eigen::Index nf = surface.triangles.rows();
    std::vector<double> cumulative(nf);
    double total = 0.0;
    for (Eigen::Index f = 0; f < nf; ++f) {
        if (surface.valid[f])
            total += triangle_area(surface.points.row(surface.triangles(f, 0)), surface.points.row(surface.triangles(f, 1)),
                                   surface.points.row(surface.triangles(f, 2))) *
                     std::sqrt(surface.weights[f]);
        cumulative[f] = total;
    }
    if (!(total > 0.0)) throw InvalidInput("the surface has no triangle of positive area to place sites on");
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    LiftedPoints sites(count, surface.dimension());
    for (long k = 0; k < count; ++k) {
        const double r = u01(rng) * total;
        const Eigen::Index f = std::min<Eigen::Index>(
            nf - 1, std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin());
        double a = u01(rng), b = u01(rng);
        if (a + b > 1.0) {
            a = 1.0 - a;
            b = 1.0 - b;
        }
        sites.row(k) = (1.0 - a - b) * surface.points.row(surface.triangles(f, 0)) +
                       a * surface.points.row(surface.triangles(f, 1)) + b * surface.points.row(surface.triangles(f, 2));
    }
    sort_spatially(sites);
    return sites;
}

} // namespace liftremesh
