#include "liftremesh/pipeline.h"

#include "liftremesh/boundary_snap.h"
#include "liftremesh/crease_snap.h"
#include "liftremesh/density.h"
#include "liftremesh/edge_collapse.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/geometry.h"
#include "liftremesh/hausdorff_refinement.h"
#include "liftremesh/hole_filling.h"
#include "liftremesh/memory_budget.h"
#include "liftremesh/mesh_io.h"
#include "liftremesh/neighbor_search.h"
#include "liftremesh/normals.h"
#include "liftremesh/optimizer.h"
#include "liftremesh/patch_refinement.h"
#include "liftremesh/quality_polish.h"
#include "liftremesh/quality.h"
#include "liftremesh/rdt.h"
#include "liftremesh/repair.h"
#include "liftremesh/rvd.h"
#include "liftremesh/sampling.h"
#include "liftremesh/self_intersection.h"
#include "liftremesh/thin_walls.h"
#include "liftremesh/threads.h"
#include "liftremesh/untangle.h"

#include <chrono>
#include <sstream>
#include <cmath>

namespace liftremesh {

namespace {

// An equilateral mesh of edge h has about 2 triangles per vertex: area sqrt(3)/2 h^2 per vertex.
double area_per_vertex(double h) { return std::sqrt(3.0) / 2.0 * h * h; }

// Times stages into the report and gives the caller a chance to cancel between them.
class StageClock {
public:
    StageClock(RemeshReport& report, const ProgressCallback& progress) : report_(report), progress_(progress) {}
    void begin(const char* stage) {
        if (progress_ && !progress_(Progress{stage, 0, 0, 0.0, 0.0}))
            throw Cancelled(std::string("remeshing was cancelled before stage '") + stage + "'");
        stage_ = stage;
        start_ = std::chrono::steady_clock::now();
    }
    void end() {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        report_.timings.push_back({stage_, s});
    }

private:
    RemeshReport& report_;
    const ProgressCallback& progress_;
    std::string stage_;
    std::chrono::steady_clock::time_point start_;
};

// Which holes of the output to fill (Section 5.2.2): those the input does not have. A boundary
// loop of the output that mostly runs within `reach` of a boundary edge of the input is the
// input's own boundary (an open surface) and stays open; any other loop is a gap artefact.
// The boundary edges are sampled `step` apart: a point within `reach` of one is within reach +
// step / 2 of a sample.
std::function<bool(const std::vector<int32_t>&)> hole_is_artefact(const Mesh& input, const Points& output_points,
                                                                  double reach) {
    std::vector<EdgeCount> boundary;
    double length = 0.0;
    for (const EdgeCount& e : edge_counts(input.triangles))
        if (e.count == 1) {
            boundary.push_back(e);
            length += (input.points.row(e.a) - input.points.row(e.b)).norm();
        }
    if (boundary.empty()) return {}; // closed input: every hole is an artefact
    const double step = segment_sample_spacing(length, 0.25 * reach);
    std::vector<Eigen::Vector3d> samples;
    for (const EdgeCount& e : boundary) {
        const Eigen::Vector3d a = input.points.row(e.a).transpose(), b = input.points.row(e.b).transpose();
        const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
        for (int i = 0; i <= steps; ++i) samples.push_back(a + (b - a) * (static_cast<double>(i) / steps));
    }
    LiftedPoints pts(static_cast<Eigen::Index>(samples.size()), 3);
    for (size_t i = 0; i < samples.size(); ++i) pts.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
    auto tree = std::make_shared<KdTree>(pts);
    const double near_enough = step > 0.25 * reach ? reach + 0.5 * step : reach; // as before where the budget holds
    return [tree, &output_points, near_enough](const std::vector<int32_t>& loop) {
        long near = 0;
        for (int32_t v : loop) {
            int32_t i;
            double d2;
            tree->knn(output_points.row(v).data(), 1, &i, &d2);
            if (d2 <= near_enough * near_enough) ++near;
        }
        return 2 * near < static_cast<long>(loop.size());
    };
}

} // namespace

long target_site_count(const RemeshParams& params, double area) {
    if (params.target_edge_length <= 0.0) return params.target_vertices;
    const double h = params.target_edge_length;
    const double n = std::round(area / area_per_vertex(h));
    if (!(n >= 4.0) || n > static_cast<double>(kMaxVertices)) {
        std::ostringstream message;
        message << "edge_length = " << h << " gives " << n << " vertices on this surface of area " << area
                << ": expected an edge length giving 4 to " << kMaxVertices << " vertices";
        throw InvalidInput(message.str());
    }
    return static_cast<long>(n);
}

RemeshResult remesh(const Mesh& input_raw, const RemeshParams& params, const ProgressCallback& progress) {
    params.validate();
    const ThreadCountScope threads(params.threads); // every parallel loop of the run, not just the diagram's
    RemeshResult result;
    RemeshReport& report = result.report;
    StageClock clock(report, progress);

    clock.begin("prepare");
    check_mesh(input_raw, "input");
    Mesh input = input_raw;
    weld_exact(input);
    remove_unreferenced_vertices(input);
    if (input.triangles.rows() == 0) throw InvalidInput("input mesh has no non-degenerate triangle");
    check_extent(input, "input");
    const long sites_wanted = target_site_count(params, surface_area(input));
    check_memory_budget(sites_wanted, input.triangles.rows(), resolve_threads(params.threads), physical_memory_bytes());
    report.input = measure_quality(input);
    report.bbox_diagonal = bounding_box_diagonal(input.points);
    const UnitBallTransform to_unit = unit_ball_transform(input); // Section 5.1
    Mesh unit = input;
    apply_transform(to_unit, unit.points);
    clock.end();

    // The edge length of an equilateral mesh with the vertices asked for, in unit-ball units.
    const double spacing = std::sqrt(surface_area(unit) / area_per_vertex(1.0) / static_cast<double>(sites_wanted));

    clock.begin("normals");
    const Points normals = vertex_normals(unit, params.eta); // Section 5.2.1
    // Built once the normals' own tree is freed, so that the two are never held at once.
    const AabbTree input_tree(input); // thin walls here, distances to the input from the repair on
    const Eigen::VectorXd rho = triangle_density(unit, normals, params.eta);      // Eqs. 22-24
    LiftedPoints lifted = unit.points; // nu = 0: the plain surface in 3D
    if (const double reach = wall_reach(params.nu, spacing); params.nu > 0.0 && reach > 0.0) {
        // Eq. 12, lifted more where a wall is thinner than the spacing, so that its two sides
        // stay apart on the lifted surface (thin_walls.h).
        const Eigen::VectorXd thickness = wall_thickness(input, input_tree, reach * to_unit.scale) / to_unit.scale;
        lifted = lift(unit.points, normals, thin_wall_lifting(thickness, params.nu, spacing));
    } else if (params.nu > 0.0) {
        lifted = lift(unit.points, normals, params.nu); // Eq. 12: nu alone keeps every wall's sides apart
    }
    const LiftedSurface surface = make_lifted_surface(lifted, unit.triangles, density_weights(rho, params.delta));
    clock.end();

    clock.begin("optimize");
    LiftedPoints sites = random_sites(surface, sites_wanted, params.seed);
    RvdCache diagram; // the optimiser's neighbour lists and seeds, reused by the triangulation
    const OptimizeResult opt =
        optimize_sites(surface, sites, params.sigma, params.iterations, params.threads, progress, &diagram);
    report.sites = sites.rows();
    report.iterations = opt.iterations;
    report.evaluations = opt.evaluations;
    report.energy_initial = opt.energy_initial;
    report.energy_final = opt.energy_final;
    clock.end();

    clock.begin("rdt");
    Mesh& out = result.mesh;
    // Eq. 4, Algorithm 3, line 11
    RestrictedDelaunay rdt = restricted_delaunay(surface, sites, params.threads, {}, &diagram);
    out = std::move(rdt.mesh);
    report.sites_split = rdt.split_sites;
    if (out.triangles.rows() == 0)
        throw TopologyFailure("the restricted Delaunay triangulation is empty: too few vertices for this surface");
    clock.end();

    clock.begin("repair");
    const RepairStats repaired = make_manifold(out);
    report.triangles_removed = repaired.degenerate_removed + repaired.duplicates_removed + repaired.nonmanifold_removed;
    if (params.fill_holes) {
        const Eigen::Index first_fill = out.triangles.rows();
        report.holes_filled = fill_holes(out, hole_is_artefact(unit, out.points, 1.5 * spacing)); // Section 5.2.2
        // Vertices inside the patches, which the paper leaves empty: at most a tenth of those asked for.
        refine_patches(out, first_fill, spacing, sites_wanted / 10);
    }
    if (out.triangles.rows() == 0) throw TopologyFailure("no triangle is left after the manifold repair");
    report.edges_collapsed = collapse_short_edges(out);
    undo_transform(to_unit, out.points);
    // After the collapse, which may keep an interior end point of an edge at the boundary, and in
    // the input's coordinates, so that snapped corners are exactly the input's.
    const BoundarySnapStats snapped = snap_boundary(out, input, {}, &input_tree);
    report.boundary_vertices_snapped = snapped.moved();
    report.triangles_removed += snapped.flaps_removed;
    // Sharp edges cut off by a chamfer (edge crunching, Section 6.2.2) get their crease points;
    // after the snap, so that an open input's boundary, where the output now lies, is no witness.
    HausdorffRefinementParams towards_input;
    towards_input.tolerance = 0.15 * spacing * to_unit.scale;
    towards_input.sample_spacing = 0.5 * spacing * to_unit.scale;
    towards_input.max_distance = spacing * to_unit.scale;
    towards_input.max_inserted = sites_wanted / 100;
    report.vertices_inserted =
        snapped.corners_inserted + refine_towards_input(out, input, towards_input, &input_tree).inserted;
    // Knife edges, which the feature term leaves cut (crease_snap.h): after the refinement, which
    // inserts the points of their corners and of a few places.
    CreaseSnapParams onto_creases;
    onto_creases.radius = 0.35 * spacing * to_unit.scale;
    onto_creases.corner_radius = spacing * to_unit.scale;
    onto_creases.tolerance = towards_input.tolerance;
    onto_creases.kappa_floor = towards_input.kappa_floor;
    const CreaseSnapStats onto_crease = snap_to_acute_creases(out, input, input_tree, onto_creases);
    // The worst triangles raised by flips and vertex moves that keep the surface on the input.
    QualityPolishParams polish;
    polish.tolerance = towards_input.tolerance;
    const QualityPolishStats polished = polish_quality(out, input_tree, polish);
    report.edges_flipped = onto_crease.flipped + polished.flipped;
    report.vertices_moved = onto_crease.moved + polished.moved;
    // Triangles passing through each other, untangled by flips (untangle.h). The tree and the
    // crossings left serve the report.
    AabbTree output_tree(out);
    std::vector<std::pair<int32_t, int32_t>> crossings = self_intersecting_pairs(out, output_tree);
    if (!crossings.empty()) {
        output_tree = AabbTree(Mesh{}); // freed while untangling, which makes its own
        UntangleParams untangling;
        untangling.tolerance = towards_input.tolerance;
        UntangleStats untangled = untangle(out, input_tree, std::move(crossings), untangling);
        report.edges_flipped += untangled.flipped;
        crossings = std::move(untangled.crossings);
        output_tree = AabbTree(out);
    }
    clock.end();

    clock.begin("quality");
    report.output = measure_quality(out);
    report.input.self_intersections = count_self_intersections(input, input_tree);
    report.output.self_intersections = static_cast<long>(crossings.size());
    const DistanceStats distance = hausdorff_distance(input, input_tree, out, output_tree); // the input's: the repair stage's
    report.hausdorff_relative = distance.hausdorff / report.bbox_diagonal;
    report.mean_distance_relative = distance.mean / report.bbox_diagonal;
    clock.end();
    report.warnings = report_warnings(report);
    return result;
}

} // namespace liftremesh
