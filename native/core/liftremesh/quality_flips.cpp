#include "liftremesh/quality_flips.h"

#include "liftremesh/exceptions.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace liftremesh {

bool quality_flip_keeps_surface(const EditableMesh& mesh, const EditableMesh::Quad& quad, const AabbTree& input,
                                double tolerance) {
    if (!mesh.flip_improves_quality(quad)) return false;
    const std::vector<Eigen::Vector3d>& x = mesh.points;
    auto distance = [&](const Eigen::Vector3d& p) { return std::sqrt(input.closest(p).squared_distance); };
    const double before = distance(0.5 * (x[quad.a] + x[quad.b]));
    const double after = distance(0.5 * (x[quad.c] + x[quad.d]));
    return after <= std::max(0.5 * tolerance, before);
}

long flip_for_quality(Mesh& mesh, const AabbTree& input, double tolerance, int passes) {
    check_indices(mesh, "flipped mesh");
    if (!(tolerance > 0.0) || !std::isfinite(tolerance) || passes < 0)
        throw InvalidInput("flip_for_quality: the tolerance must be positive and finite, the passes not negative");
    EditableMesh editable(mesh);
    long total = 0;
    // The first pass looks at every edge, each next one at the edges of the triangles the last
    // one changed: only their quads can have become worth a flip.
    std::vector<char> around(editable.tris.size(), 1), changed;
    for (int pass = 0; pass < passes; ++pass) {
        const long flips = editable.flip_pass_around(
            around, [&](const EditableMesh::Quad& q) { return quality_flip_keeps_surface(editable, q, input, tolerance); },
            changed);
        total += flips;
        if (flips == 0) break;
        around.swap(changed);
    }
    if (total > 0) editable.write_to(mesh);
    return total;
}

} // namespace liftremesh
