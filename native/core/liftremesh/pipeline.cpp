#include "liftremesh/pipeline.h"

#include "liftremesh/cvt/crease_sites.h"
#include "liftremesh/cvt/optimizer.h"
#include "liftremesh/cvt/rdt.h"
#include "liftremesh/cvt/rvd.h"
#include "liftremesh/cvt/sampling.h"
#include "liftremesh/edit/acute_creases.h"
#include "liftremesh/edit/edge_collapse.h"
#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/lift/density.h"
#include "liftremesh/lift/normals.h"
#include "liftremesh/lift/size_field.h"
#include "liftremesh/lift/thin_walls.h"
#include "liftremesh/measure/quality.h"
#include "liftremesh/mesh/components.h"
#include "liftremesh/mesh/creases.h"
#include "liftremesh/mesh/geometry.h"
#include "liftremesh/mesh/input_cleaning.h"
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/mesh/solid_parts.h"
#include "liftremesh/repair/hole_filling.h"
#include "liftremesh/repair/patch_refinement.h"
#include "liftremesh/repair/repair.h"
#include "liftremesh/repair/stray_components.h"
#include "liftremesh/spatial/neighbor_search.h"
#include "liftremesh/spatial/reference.h"
#include "liftremesh/spatial/self_intersection.h"
#include "liftremesh/steps.h"
#include "liftremesh/system/memory_budget.h"
#include "liftremesh/system/threads.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
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

namespace {

// One piece of the input (solid_parts.h), lifted and ready for its sites.
struct Piece {
    const Mesh* input = nullptr; // the piece in input units: the whole input when it is the only piece
    const Mesh* unit = nullptr;  // the same in the unit ball
    Mesh own_input, own_unit;    // the piece's copies, when it is not the whole input
    std::unique_ptr<AabbTree> tree; // over *input: thin walls, then distances to the input in the repair
    bool closed = false;            // a closed component (solid_parts.h)
    LiftedSurface surface;
    long sites = 0;
    // The local sizing (size_field.h), in unit-ball units: the vertices it asks for at the
    // spacing, its smallest size and the areas it refined (its sizes, once in the weights, dropped).
    double sized_count = 0.0;
    double size_smallest = 0.0;
    SizeField size_areas;
    long midpoints_allowed = 0; // the thin walls' midpoints it could take when lifted
};

// Facets turning by more than this are creases, not a bend the size field refines: a CAD
// tessellation's facets of a hole turn by up to its angular deflection, FreeCAD's default 28.6°.
constexpr double kBendMaxTurnDeg = 45.0;

// The size field's bounds for a spacing (unit-ball units): the largest is the spacing, or the
// largest edge if smaller; the smallest the smallest edge if set (at most the largest), else a
// quarter of the largest: the weights' contrast, (largest / smallest)^4, slows the optimiser
// down on the small cells, and leaves their triangles worse for the same iterations.
SizeFieldParams size_bounds(const RemeshParams& params, const UnitBallTransform& to_unit, double spacing) {
    SizeFieldParams bounds;
    bounds.largest = params.max_edge > 0.0 ? std::min(spacing, params.max_edge / to_unit.scale) : spacing;
    bounds.smallest = params.min_edge > 0.0 ? std::min(bounds.largest, params.min_edge / to_unit.scale)
                                            : 0.25 * bounds.largest;
    bounds.gradation = params.gradation;
    return bounds;
}

// Vertex normals, densities and the lifted surface of a piece (Section 5.2.1, Eqs. 12, 22-24), from
// its own triangles only: a solid's normals and walls are its own, however near another one lies.
// With local sizing, the weights are rho^delta times the size field's (size_field.h).
// `midpoints_left`: what the thin walls' sampling may still add, over all pieces (decreased).
void lift_piece(Piece& piece, const RemeshParams& params, const UnitBallTransform& to_unit, double spacing,
                long sites_wanted, double total_area, long& midpoints_left) {
    piece.midpoints_allowed = midpoints_left;
    const Mesh& input = *piece.input;
    const Mesh& unit = *piece.unit;
    // One tree over the input serves the normals and, later, the thin walls and the projections
    // back onto it (and a second lifting, remesh_soundly): the unit-ball copy's normals at eta
    // are the input's at eta times the scale.
    if (!piece.tree) piece.tree = std::make_unique<AabbTree>(input);
    const Points normals = vertex_normals(input, *piece.tree, params.eta * to_unit.scale); // Section 5.2.1
    const Eigen::VectorXd turn = triangle_normal_turn(unit, normals, params.eta); // Eqs. 22-23
    const Eigen::VectorXd weights = density_weights((1.0 + turn.array()).matrix(), params.delta); // Eqs. 24-25
    const double reach = wall_reach(params.nu, spacing);
    const bool thin_walls = params.nu > 0.0 && reach > 0.0;
    const SizeFieldParams bounds = size_bounds(params, to_unit, spacing);
    if (!thin_walls && !params.local_sizing) {
        // Eq. 12: nu alone keeps every wall's sides apart; nu = 0, the plain surface in 3D.
        piece.surface = make_lifted_surface(params.nu > 0.0 ? lift(unit.points, normals, params.nu) : LiftedPoints(unit.points),
                                            unit.triangles, weights);
        return;
    }
    // Eq. 12, lifted more where a wall is thinner than the spacing, so that its two sides stay
    // apart on the lifted surface (thin_walls.h), and the sizes made smaller there; on triangles
    // split where their vertices alone would miss a wall: the same surface, normals and densities.
    WallSamplingParams walls;
    walls.reach = thin_walls ? reach * to_unit.scale : 0.0;
    walls.nu = params.nu * to_unit.scale;
    walls.spacing = spacing * to_unit.scale;
    walls.tolerance = 0.1 * walls.spacing;
    walls.min_edge = 0.25 * std::min(walls.spacing, bounds.largest * to_unit.scale);
    walls.max_midpoints = midpoints_left;
    walls.largest_size = params.local_sizing ? bounds.largest * to_unit.scale : 0.0;
    const WallSampling sampled = sample_wall_thickness(input, *piece.tree, walls);
    midpoints_left -= static_cast<long>(sampled.midpoints.size());
    const Eigen::VectorXd thickness = sampled.thickness / to_unit.scale;
    // The mesh the surface is made of: the piece's, or its split copy, whose triangles take their
    // parents' turn and weight.
    Mesh split;
    const bool was_split = !sampled.midpoints.empty();
    if (was_split) {
        split.points = with_midpoints(unit.points, sampled.midpoints);
        split.triangles = sampled.triangles;
    }
    const Mesh& mesh = was_split ? split : unit;
    const auto per_triangle = [&](const Eigen::VectorXd& values) {
        if (!was_split) return values;
        Eigen::VectorXd out(static_cast<Eigen::Index>(sampled.parent.size()));
        for (size_t f = 0; f < sampled.parent.size(); ++f) out[static_cast<Eigen::Index>(f)] = values[sampled.parent[f]];
        return out;
    };
    Eigen::VectorXd surface_weights = per_triangle(weights);
    // The spacing the sites will have at each vertex, from which a wall's sides must lie apart.
    Eigen::VectorXd local_spacing = Eigen::VectorXd::Constant(thickness.size(), spacing);
    if (params.local_sizing) {
        // Bends seen by both the input's own facets, which a crease does not fool (the eta-ball
        // normals turn fast across it too), and the eta-ball normals, which a scan's noise does
        // not (its facets turn fast from one to the next).
        const Eigen::VectorXd bend =
            triangle_bend(unit, std::min(params.feature_angle, kBendMaxTurnDeg)).cwiseMin(turn);
        piece.size_areas = size_field(mesh, thickness, per_triangle(bend), bounds);
        const Eigen::VectorXd density = site_density(mesh, piece.size_areas.size, bounds.largest);
        surface_weights = sized_weights(surface_weights, density);
        piece.sized_count = sized_vertex_count(mesh, density, bounds.largest);
        piece.size_smallest = piece.size_areas.size.minCoeff();
        // The field's sizes are lengths with an edge length or a largest edge; with a vertex
        // count they all scale to meet this piece's share of it (by area).
        const bool lengths = params.target_edge_length > 0.0 || params.max_edge > 0.0;
        const double share = static_cast<double>(sites_wanted) * surface_area(unit) / total_area;
        const double scale = lengths || !(share > 0.0) ? 1.0 : std::sqrt(piece.sized_count / share);
        local_spacing = scale * piece.size_areas.size;
        piece.size_areas.size = Eigen::VectorXd(); // in the weights now: only the areas are reported
    }
    const Eigen::VectorXd lifting = thin_walls ? thin_wall_lifting(thickness, params.nu, local_spacing.cwiseMin(spacing))
                                               : Eigen::VectorXd::Constant(thickness.size(), params.nu);
    const Points mesh_normals = was_split ? with_midpoints(normals, sampled.midpoints) : Points();
    const Points& surface_normals = was_split ? mesh_normals : normals;
    piece.surface = make_lifted_surface(params.nu > 0.0 ? lift(mesh.points, surface_normals, lifting) : LiftedPoints(mesh.points),
                                        mesh.triangles, std::move(surface_weights));
}

// The sites the local sizing asks for over all pieces (size_field.h), and its summary in the
// report. With an edge length, the field's sizes are lengths: the count is what they give. With
// a vertex count, that count is the budget, every size scaled by the same factor to meet it,
// unless a largest edge is set and needs more.
long sized_site_count(const std::vector<Piece>& pieces, const RemeshParams& params, const UnitBallTransform& to_unit,
                      double spacing, long wanted, double input_area, RemeshReport& report) {
    const SizeFieldParams bounds = size_bounds(params, to_unit, spacing);
    double count = 0.0, smallest = bounds.largest;
    SizeFieldSummary& summary = report.size_field;
    for (const Piece& piece : pieces) {
        count += piece.sized_count;
        smallest = std::min(smallest, piece.size_smallest);
        summary.walls += piece.size_areas.wall_area;
        summary.curvature += piece.size_areas.curvature_area;
        summary.refined += piece.size_areas.graded_area;
    }
    const double area = input_area / (to_unit.scale * to_unit.scale), per = area > 0.0 ? 1.0 / area : 0.0;
    summary.walls *= per;
    summary.curvature *= per;
    summary.refined *= per;
    long sites = wanted;
    if (params.target_edge_length > 0.0 || params.max_edge > 0.0) {
        const double n = std::round(count);
        if (!(n <= static_cast<double>(kMaxVertices))) {
            std::ostringstream message;
            message << "the local sizing asks for " << n << " vertices, more than " << kMaxVertices
                    << ": expected a larger smallest edge (min_edge) or edge length";
            throw InvalidInput(message.str());
        }
        sites = std::max(params.target_edge_length > 0.0 ? 4L : wanted, static_cast<long>(n));
    }
    // The sizes the sites reach: the field's, scaled so that their count is the sites'.
    const double scale = count > 0.0 ? std::sqrt(count / static_cast<double>(sites)) * to_unit.scale : to_unit.scale;
    summary.smallest = smallest * scale;
    summary.largest = bounds.largest * scale;
    return sites;
}

// The sites each piece gets: the number wanted, shared as random_sites would spread them over
// the pieces together (by sampling_mass), largest remainders rounded up, and at least 4 per
// piece with any mass, so that no solid is left without a surface. A single piece gets all.
void share_sites(std::vector<Piece>& pieces, long wanted) {
    if (pieces.size() == 1) {
        pieces[0].sites = wanted;
        return;
    }
    std::vector<double> mass(pieces.size());
    double total = 0.0;
    for (size_t k = 0; k < pieces.size(); ++k) total += mass[k] = sampling_mass(pieces[k].surface);
    std::vector<std::pair<double, size_t>> remainder;
    long given = 0;
    for (size_t k = 0; k < pieces.size(); ++k) {
        const double share = total > 0.0 ? static_cast<double>(wanted) * mass[k] / total : 0.0;
        pieces[k].sites = static_cast<long>(std::floor(share));
        given += pieces[k].sites;
        remainder.emplace_back(share - std::floor(share), k);
    }
    std::sort(remainder.begin(), remainder.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t i = 0; i < remainder.size() && given < wanted; ++i, ++given) ++pieces[remainder[i].second].sites;
    for (size_t k = 0; k < pieces.size(); ++k)
        if (mass[k] > 0.0) pieces[k].sites = std::max(pieces[k].sites, 4L);
}

// The triangles under the floor mended (edge_collapse.h), then the edges round the vertices
// its splits added flipped where that raises them (quality_polish.h); counts added to `report`.
// Again while a pass mends something, at most kMendPasses times: a split's triangles can be
// under the floor themselves, and the next pass may collapse one of their edges.
void mend_poor(Mesh& out, const Reference& reference, const QualityPolishParams& polish, RemeshReport& report) {
    constexpr int kMendPasses = 4; // each pass's splits add vertices: a bound on them
    for (int pass = 0; pass < kMendPasses; ++pass) {
        const PoorTriangleStats mended = mend_poor_triangles(out, reference);
        report.edges_collapsed += mended.collapsed;
        report.vertices_inserted += mended.split;
        report.edges_flipped += mended.flipped;
        if (!mended.added.empty()) // the triangles round its new vertices
            report.edges_flipped += flip_around(out, reference, polish, mended.added);
        if (mended.collapsed + mended.split == 0) break;
    }
}

// The creases that the output's passes farther than 0.07 h from, where two of them converge
// (crease_snap.h: crease_gaps), given vertices of their own under the refinement's floor, in
// `mesh` (h the spacing in its units); returns the vertices added. In a few passes, each
// against the mesh the last one left: a point's insertion splits the triangles round it, and a
// point along the strip whose try failed may then find the short edges it needs. Only those
// within h of a vertex the last pass added are tried again: elsewhere the mesh is as their tries
// left it. None within 2 h of triangles that cross others, which the untangling moves apart
// under kappa 0.2 (a member thinner than the edges): a vertex inserted beside them is one more
// it may move. A pass that lays triangles through others is undone, and the passes end there.
long insert_crease_gaps(Mesh& mesh, const Reference& reference, const AcuteCreases& creases,
                        const CreaseSnapParams& snap, const HausdorffRefinementParams& refinement, double h) {
    constexpr int kGapPasses = 3;
    auto near_any = [](const KdTree& tree, const Eigen::Vector3d& p, double r) {
        std::vector<int32_t> found;
        tree.within(p.data(), r, found);
        return !found.empty();
    };
    bool counted = false;          // the crossings, once there are gaps
    long crossings = 0;
    std::optional<KdTree> tangled; // the corners of the triangles crossing, if any
    std::optional<KdTree> added;   // the vertices the last pass added
    long total = 0;
    for (int pass = 0; pass < kGapPasses; ++pass) {
        std::vector<Eigen::Vector3d> gaps = crease_gaps(mesh, creases, snap);
        if (!gaps.empty() && !counted) {
            counted = true;
            const auto pairs = self_intersecting_pairs(mesh, AabbTree(mesh));
            crossings = static_cast<long>(pairs.size());
            if (!pairs.empty()) {
                Points corners(6 * pairs.size(), 3);
                Eigen::Index row = 0;
                for (const auto& [s, t] : pairs)
                    for (const int32_t f : {s, t})
                        for (int j = 0; j < 3; ++j) corners.row(row++) = mesh.points.row(mesh.triangles(f, j));
                tangled.emplace(corners);
            }
        }
        gaps.erase(std::remove_if(gaps.begin(), gaps.end(),
                                  [&](const Eigen::Vector3d& g) {
                                      return (tangled && near_any(*tangled, g, 2.0 * h)) ||
                                             (added && !near_any(*added, g, h));
                                  }),
                   gaps.end());
        if (gaps.empty()) break;
        Mesh before = mesh;
        const long inserted =
            insert_input_points(mesh, reference, gaps, snap.min_depth, refinement).inserted;
        if (inserted == 0) break;
        if (count_self_intersections(mesh, AabbTree(mesh)) > crossings) {
            mesh = std::move(before);
            break;
        }
        total += inserted;
        added.emplace(Points(mesh.points.bottomRows(mesh.points.rows() - before.points.rows()))); // appended
    }
    return total;
}

// Optimises the sites of one piece, triangulates them and repairs the result (all but the
// untangling, which sees every piece at once), in input units; adds its counts to the report.
Mesh remesh_piece(Piece& piece, std::uint64_t seed, const RemeshParams& params, const UnitBallTransform& to_unit,
                  double spacing, StageClock& clock, const ProgressCallback& progress, RemeshReport& report) {
    const long sites_wanted = piece.sites;

    const StepSettings steps = step_settings(spacing, to_unit.scale, sites_wanted);
    const Reference reference{*piece.input, *piece.tree};

    clock.begin("optimize");
    // With hold_creases, every crease over the feature angle and its corners get sites held
    // still, the others are seeded at random off them and, where the optimisation leaves one
    // crowding a crease, seeded again (crease_sites.h). At 180 degrees, none: the feature term.
    std::optional<CreaseSites> creases;
    if (params.hold_creases && params.feature_angle < 180.0)
        creases.emplace(piece.surface,
                        long_crease_chains(*piece.input,
                                           creases_over_balls(*piece.input, *piece.tree, crease_edges(*piece.input, params.feature_angle),
                                                              params.eta * to_unit.scale, params.feature_angle),
                                           steps.feature_snap.min_length),
                        sites_wanted);
    const long held_count = creases ? creases->held().rows() : 0;
    LiftedPoints sites(sites_wanted, piece.surface.dimension());
    if (creases) {
        sites.topRows(held_count) = creases->held();
        sites.bottomRows(sites_wanted - held_count) = creases->free_sites(piece.surface, sites_wanted - held_count, seed);
    } else {
        sites = random_sites(piece.surface, sites_wanted, seed);
    }
    RvdCache diagram; // the optimiser's neighbour lists and seeds, reused by the triangulation
    HeldSites held;
    held.count = held_count;
    if (held_count > 0)
        held.reseat = [&](LiftedPoints& s) { return creases->reseat_crowding_sites(piece.surface, s, held_count, seed + 1); };
    const OptimizeResult opt =
        optimize_sites(piece.surface, sites, params.sigma, params.iterations, params.threads, progress, &diagram, held);
    report.crease_sites += held_count;
    report.sites += sites.rows();
    report.iterations = std::max(report.iterations, opt.iterations);
    report.evaluations += opt.evaluations;
    report.energy_initial += opt.energy_initial;
    report.energy_final += opt.energy_final;
    clock.end();

    clock.begin("rdt");
    // Eq. 4, Algorithm 3, line 11
    RestrictedDelaunayParams triangulation;
    triangulation.held = creases && creases->rows_held() ? held_count : 0;
    RestrictedDelaunay rdt = restricted_delaunay(piece.surface, sites, params.threads, triangulation, &diagram);
    Mesh out = std::move(rdt.mesh);
    report.sites_split += rdt.split_sites;
    if (out.triangles.rows() == 0)
        throw TopologyFailure("the restricted Delaunay triangulation is empty: too few vertices for this surface");
    clock.end();

    // The triangulation made an oriented manifold without holes it should not have, in the unit
    // ball (repair/).
    clock.begin("repair");
    const RepairStats repaired = make_manifold(out);
    report.triangles_removed += repaired.degenerate_removed + repaired.duplicates_removed + repaired.nonmanifold_removed;
    if (params.fill_holes) {
        HoleFillingParams holes;
        holes.should_fill = hole_is_artefact(*piece.unit, out.points, steps.hole_reach); // Section 5.2.2
        if (const long darts = remove_darts(out, holes); darts > 0) {
            report.triangles_removed += darts;
            remove_unreferenced_vertices(out);
        }
        const Eigen::Index first_fill = out.triangles.rows();
        report.holes_filled += fill_holes(out, holes).filled;
        PatchRefinementParams patches = steps.patch_refinement;
        patches.first = first_fill;
        refine_patches(out, patches);
    }
    if (out.triangles.rows() == 0) throw TopologyFailure("no triangle is left after the manifold repair");
    report.edges_collapsed += collapse_short_edges(out, steps.short_edges).collapsed;
    clock.end();

    // The surface onto the input's boundary and features, in the input's coordinates, so that
    // snapped corners are exactly the input's (snap/, polish/hausdorff_refinement.h).
    clock.begin("snap");
    undo_transform(to_unit, out.points);
    // After the collapse, which may keep an interior end point of an edge at the boundary.
    const BoundarySnapStats snapped = snap_boundary(out, reference, steps.boundary_snap);
    report.boundary_vertices_snapped += snapped.moved();
    report.triangles_removed += snapped.flaps_removed;
    // Sharp edges cut off by a chamfer (edge crunching, Section 6.2.2) get their crease points;
    // after the snap, so that an open input's boundary, where the output now lies, is no witness.
    report.vertices_inserted +=
        snapped.corners_inserted + refine_towards_input(out, reference, steps.hausdorff_refinement).inserted;
    // Knife edges, which the feature term leaves cut, and every crease over the feature angle
    // (crease_snap.h): after the refinement, which inserts the points of their corners and of a
    // few places. At feature_angle 180 only the knife edges, which are a repair (Section 6.2.2).
    CreaseSnapParams onto_creases = params.feature_angle < 180.0 ? steps.feature_snap : steps.crease_snap;
    onto_creases.min_turn_deg = std::min(onto_creases.min_turn_deg, params.feature_angle);
    // Found once: the crease curves below follow the same creases (their length too).
    const AcuteCreases creases_over_angle(*piece.input, onto_creases.min_turn_deg, 0.5 * onto_creases.radius,
                                          onto_creases.min_length);
    const CreaseSnapStats onto_crease = snap_to_acute_creases(out, reference, creases_over_angle, onto_creases);
    // A junction of creases that no vertex could move onto (a quarter of an edge from another,
    // whose vertex it took, or the corner of a knife edge cut short) gets a vertex of its own,
    // with the explicit creases only; a knife edge's under the snap's floor for knife edges.
    if (params.feature_angle < 180.0) {
        // (onto_creases.kappa_floor is the refinement's: steps.cpp.)
        std::vector<double> floors;
        for (const double turn : creases_over_angle.junction_turns()) floors.push_back(onto_creases.kappa_floor_beside(turn));
        report.vertices_inserted += insert_input_points(out, reference, creases_over_angle.junctions(),
                                                        onto_creases.min_depth, steps.hausdorff_refinement, floors).inserted;
        // And a bend of a crease that the output's crease passes as a chord (crease_snap.h), under
        // a floor of its own (quality_floors.h) and the refinement's 1% of the vertices.
        std::vector<Eigen::Vector3d> bends;
        for (const AcuteCreases::Bend& b : bends_off_mesh_creases(out, creases_over_angle, onto_creases))
            bends.push_back(b.point);
        HausdorffRefinementParams at_bends = steps.hausdorff_refinement;
        at_bends.kappa_floor = kKappaFloorBend;
        report.vertices_inserted +=
            insert_input_points(out, reference, bends, onto_creases.bend_distance, at_bends).inserted;
    }
    clock.end();

    // The worst triangles raised by flips and vertex moves that keep the surface on the input;
    // then pairs of triangles folded shut, which no step above sees (edge_collapse.h).
    clock.begin("polish");
    const QualityPolishStats polished = polish_quality(out, reference, steps.quality_polish);
    report.edges_flipped += onto_crease.flipped + polished.flipped;
    report.vertices_moved += onto_crease.moved + polished.moved;
    report.edges_collapsed += collapse_folded_pairs(out, reference, steps.folded_pairs).collapsed;
    mend_poor(out, reference, steps.quality_polish, report);
    // The snap again, over the fans the steps since have changed: a vertex beside the rim of a
    // hole an edge or two across could not move onto it while its fan reached across the bore
    // (the triangle to the next rim vertex would span it), and can once a split has put a
    // vertex on the rim beside it. The moves keep the snap's floor, so none undoes a mending.
    const CreaseSnapStats again = snap_to_acute_creases(out, reference, creases_over_angle, onto_creases);
    report.edges_flipped += again.flipped;
    report.vertices_moved += again.moved;
    // Then the creases that the output's still passes far from, where two of them converge.
    if (params.feature_angle < 180.0)
        report.vertices_inserted += insert_crease_gaps(out, reference, creases_over_angle, onto_creases,
                                                       steps.hausdorff_refinement, spacing * to_unit.scale);
    // Last, as every step before keeps the surface on the input: the vertices on the chords of a
    // curved crease onto the curve (crease_curves.h), with the explicit creases only.
    if (params.feature_angle < 180.0) {
        CreaseCurveParams curves = steps.crease_curves;
        curves.min_turn_deg = onto_creases.min_turn_deg;
        curves.min_length = onto_creases.min_length;
        report.vertices_moved += move_onto_crease_curves(out, *piece.input, creases_over_angle, curves).moved;
    }
    // And the Hausdorff refinement once more: the steps since its first run (the snaps and their
    // flips, the polish, the mending, the insertions above, the curve moves) keep the surface
    // near the input where they edit it, but a fan they reshaped beside a thin wedge can still
    // cut into it (a vertex of one face joined to two vertices of the face across the wedge
    // notches its tip), which a point of the input there, inserted with its flips, mends.
    report.vertices_inserted += refine_towards_input(out, reference, steps.hausdorff_refinement).inserted;
    clock.end();
    return out;
}

// A run's counts (all but the qualities and timings) added to the whole run's.
void add_counts(RemeshReport& to, const RemeshReport& run) {
    to.sites += run.sites;
    to.iterations = std::max(to.iterations, run.iterations);
    to.evaluations += run.evaluations;
    to.energy_initial += run.energy_initial;
    to.energy_final += run.energy_final;
    to.crease_sites += run.crease_sites;
    to.parts_unheld += run.parts_unheld;
    to.parts_eta_reduced += run.parts_eta_reduced;
    to.sites_split += run.sites_split;
    to.holes_filled += run.holes_filled;
    to.triangles_removed += run.triangles_removed;
    to.edges_collapsed += run.edges_collapsed;
    to.vertices_inserted += run.vertices_inserted;
    to.edges_flipped += run.edges_flipped;
    to.vertices_moved += run.vertices_moved;
    to.boundary_vertices_snapped += run.boundary_vertices_snapped;
}

// Whether `out` has the Euler characteristic the report expects of the remeshed `in`, so that it
// raises no topology warning.
bool keeps_topology(const MeshQuality& in, const MeshQuality& out) {
    RemeshReport run;
    run.input = in;
    run.output = out;
    return out.euler_characteristic == expected_euler_characteristic(run);
}

// What a piece's output (`out`, measured) has wrong that its input (`in`) has not: a topology
// other than the report expects of it, and each edge folded shut, non-manifold edge or hole more
// than the input's. Zero for a sound surface; no triangle at all counts as the worst.
long surface_defects(const MeshQuality& in, const MeshQuality& out) {
    if (out.triangles == 0) return std::numeric_limits<long>::max();
    return (keeps_topology(in, out) ? 0 : 1) + std::max(0L, out.folded_edges - in.folded_edges) +
           std::max(0L, out.nonmanifold_edges - in.nonmanifold_edges) +
           std::max(0L, out.boundary_loops - in.boundary_loops);
}

// Whether a small closed piece came out as the surface it is (closed, with no defect its input
// has not: the Euler characteristic the report expects of it, no edge folded shut) and with no
// triangle worse than its input's worst, or kKappaFloor: else its input's triangles are better.
bool keeps_piece(const MeshQuality& in, const MeshQuality& out) {
    return out.triangles > 0 && out.boundary_edges == 0 && out.nonmanifold_edges == 0 &&
           surface_defects(in, out) == 0 && out.kappa_min >= std::min(in.kappa_min, kKappaFloor);
}

// A piece's output measured; an empty one (a run that made no triangle) has no triangle.
MeshQuality measured(const Mesh& out) { return out.triangles.rows() > 0 ? measure_quality(out) : MeshQuality{}; }

// Largest share of the input's area a closed piece may have to come out as its input's triangles
// when remeshing it fails (remesh_or_keep).
constexpr double kSmallPiece = 0.05;

// The eta-ball of a piece's second lifting (remesh_soundly), in spacings: a ball wider than a
// part's members (the frame's 3 mm members round 1.8 mm pin holes, under a default ball of 3.6
// mm) averages their sides' normals with their faces', so that the lifting no longer sets a
// member's sides apart; a quarter of the spacing sees one side at a time where the sites can
// tell the sides apart at all.
constexpr double kSecondEtaSpacings = 0.25;

// What a piece's runs are measured against: its input's quality and, made when first needed,
// the limits of the stray pieces the whole output's pass removes (stray_components.h).
struct PieceInput {
    const Mesh& mesh;
    const MeshQuality& quality;
    std::optional<StrayComponentParams> strays;

    const StrayComponentParams& stray_limits() {
        if (!strays) strays = stray_component_params(mesh_components(mesh));
        return *strays;
    }
};

// One run of remesh_piece on a piece, measured as it will be handed on: a defect that is only a
// stray bubble (surface_defects counts its Euler characteristic) is not one.
struct PieceRun {
    Mesh mesh;
    Mesh handed; // the mesh less its stray pieces, if it has any
    MeshQuality quality;
    RemeshReport report;
    long crossings = -1; // pairs of triangles crossing (self_intersection.h), counted when needed
};

long crossings(PieceRun& run) {
    if (run.crossings < 0) {
        const Mesh& mesh = run.handed.triangles.rows() > 0 ? run.handed : run.mesh;
        run.crossings = count_self_intersections(mesh, AabbTree(mesh));
    }
    return run.crossings;
}

// Runs remesh_piece, measured; a run that makes no triangle (TopologyFailure) comes out empty
// when `may_fail`, else throws.
PieceRun run_piece(Piece& piece, PieceInput& in, std::uint64_t seed, const RemeshParams& params,
                   const UnitBallTransform& to_unit, double spacing, StageClock& clock,
                   const ProgressCallback& progress, bool may_fail) {
    PieceRun run;
    try {
        run.mesh = remesh_piece(piece, seed, params, to_unit, spacing, clock, progress, run.report);
    } catch (const TopologyFailure&) { // too few sites for a triangle
        if (!may_fail) throw;
    }
    run.quality = measured(run.mesh);
    if (run.quality.triangles > 0 && surface_defects(in.quality, run.quality) > 0) {
        Mesh handed = run.mesh;
        if (remove_stray_components(handed, in.stray_limits()).removed > 0) {
            run.quality = measured(handed);
            run.handed = std::move(handed);
        }
    }
    return run;
}

// Whether run `b` is a sounder surface than run `a` for a piece whose input measured `in`: it
// keeps the topology the report expects where `a` does not, or has the same verdict and fewer of
// the other defects (surface_defects), pairs of triangles crossing counted in if both keep it. A
// run that lost the topology is wrong wherever members merged, whatever its crossings; and these
// are counted before the untangling, which removes most, so they decide only between sound runs.
bool sounder(const MeshQuality& in, PieceRun& a, PieceRun& b) {
    if (b.quality.triangles == 0) return false;
    if (a.quality.triangles == 0) return true;
    const bool a_keeps = keeps_topology(in, a.quality), b_keeps = keeps_topology(in, b.quality);
    if (a_keeps != b_keeps) return b_keeps;
    if (!a_keeps) return surface_defects(in, b.quality) < surface_defects(in, a.quality);
    return surface_defects(in, b.quality) + crossings(b) < surface_defects(in, a.quality) + crossings(a);
}

// Remeshes a piece and, while its output has a defect its input (measured `in`) has not
// (surface_defects), again in the ways that may avoid it, keeping the soundest run:
// - with hold_creases, its creases snapped to rather than held (report.parts_unheld): held
//   sites on creases closer together than the spacing (a bore meeting a chamfer a fraction of
//   it away) hold cells too narrow for the triangulation to join as the surface does, where
//   free sites move apart;
// - then, with its creases as asked, lifted with normals averaged over a ball of
//   kSecondEtaSpacings spacings if that is smaller than eta (report.parts_eta_reduced): a cause
//   of its own, which held sites do not make worse.
// Each run replaces the one kept if it is sounder. `small`: a piece whose first run may make no
// triangle, and that remesh_or_keep runs again with more sites if it does not come out whole.
PieceRun remesh_soundly(Piece& piece, std::uint64_t seed, const RemeshParams& params, const UnitBallTransform& to_unit,
                        double spacing, double unit_area, long sites_wanted, PieceInput& input, bool small,
                        StageClock& clock, const ProgressCallback& progress) {
    const MeshQuality& in = input.quality;
    PieceRun kept = run_piece(piece, input, seed, params, to_unit, spacing, clock, progress, small);
    const bool holding = params.hold_creases && params.feature_angle < 180.0;
    if (holding && kept.report.crease_sites > 0 && surface_defects(in, kept.quality) > 0) {
        RemeshParams snapped_params = params;
        snapped_params.hold_creases = false;
        PieceRun snapped = run_piece(piece, input, seed, snapped_params, to_unit, spacing, clock, progress, true);
        if (sounder(in, kept, snapped)) {
            kept = std::move(snapped);
            kept.report.parts_unheld = 1;
        }
    }
    // Not a small piece: thinner than its few cells, it gets more sites (remesh_or_keep).
    const double second_eta = kSecondEtaSpacings * spacing;
    if (!small && params.nu > 0.0 && second_eta < params.eta && surface_defects(in, kept.quality) > 0) {
        RemeshParams narrow = params;
        narrow.eta = second_eta;
        long midpoints = piece.midpoints_allowed;
        piece.surface = LiftedSurface{}; // freed first: on a million triangles, hundreds of MB
        clock.begin("normals");
        lift_piece(piece, narrow, to_unit, spacing, sites_wanted, unit_area, midpoints);
        clock.end();
        PieceRun again = run_piece(piece, input, seed, narrow, to_unit, spacing, clock, progress, true);
        if (sounder(in, kept, again)) {
            again.report.parts_eta_reduced = 1;
            kept = std::move(again);
        }
    }
    return kept;
}

// One piece, its counts added to the report (remesh_soundly). A closed piece of at most
// kSmallPiece of the input's area that does not come out as the surface it is (keeps_piece),
// being thinner than its cells (a ring lower than the spacing, given a few sites), is remeshed
// again with twice the sites while `retry_sites` (shared by all pieces) lasts, each time at most
// max(64, wanted / 10); if none does, it comes out as its input's triangles (report.parts_kept),
// as Gmsh keeps a surface smaller than the mesh size with its curves' own points. A larger
// piece, or the open ones, comes out as remesh_soundly makes it: the report's warnings tell.
// `whole`: the input's quality when the piece is all of it (the report's, measured once: on a
// million triangles it takes seconds).
Mesh remesh_or_keep(Piece& piece, std::uint64_t seed, const RemeshParams& params, const UnitBallTransform& to_unit,
                    double spacing, double unit_area, double input_area, long sites_wanted, long& retry_sites,
                    StageClock& clock, const ProgressCallback& progress, const MeshQuality* whole,
                    RemeshReport& report) {
    if (piece.sites == 0) return {}; // no triangle of positive area: nothing to remesh
    const bool small = piece.closed && surface_area(*piece.input) <= kSmallPiece * input_area;
    const MeshQuality in = whole ? *whole : measure_quality(*piece.input);
    PieceInput input{*piece.input, in, std::nullopt};
    for (;;) {
        PieceRun run = remesh_soundly(piece, seed, params, to_unit, spacing, unit_area, sites_wanted, input, small,
                                      clock, progress);
        if (!small || keeps_piece(in, run.quality)) {
            add_counts(report, run.report);
            return std::move(run.mesh);
        }
        const long more = 2 * piece.sites;
        if (more > std::max(64L, sites_wanted / 10) || more > retry_sites) {
            ++report.parts_kept;
            return *piece.input;
        }
        retry_sites -= more;
        piece.sites = more;
    }
}

} // namespace

RemeshResult remesh(const Mesh& input_raw, const RemeshParams& params, const ProgressCallback& progress) {
    params.validate();
    const ThreadCountScope threads(params.threads); // every parallel loop of the run, not just the diagram's
    RemeshResult result;
    RemeshReport& report = result.report;
    StageClock clock(report, progress);

    clock.begin("prepare");
    check_mesh(input_raw, "input");
    Mesh input = input_raw;
    remove_unreferenced_vertices(input);
    // Before the cleaning: a corrupt file's far vertex makes a needle of the facets using it,
    // which the cleaning would drop as of zero area (relative to its longest side) unsaid.
    check_extent(input, "input");
    report.input_cleaning = clean_input(input); // a careless export's facets made into its surface
    remove_unreferenced_vertices(input);
    if (input.triangles.rows() == 0)
        throw InvalidInput("input mesh has no triangle of positive area: all " + std::to_string(input_raw.triangles.rows()) +
                           " have a repeated vertex or zero area");
    const double input_area = surface_area(input);
    long sites_wanted = target_site_count(params, input_area); // the local sizing's, once it is known
    check_memory_budget(sites_wanted, input.triangles.rows(), resolve_threads(params.threads), physical_memory_bytes());
    report.input = measure_quality(input);
    report.bbox_diagonal = bounding_box_diagonal(input.points);
    const UnitBallTransform to_unit = unit_ball_transform(input); // Section 5.1
    Mesh unit = input;
    apply_transform(to_unit, unit.points);
    // The edge length of an equilateral mesh with the vertices asked for, in unit-ball units.
    const double unit_area = surface_area(unit);
    const double spacing = std::sqrt(unit_area / area_per_vertex(1.0) / static_cast<double>(sites_wanted));
    // Each closed component on its own (solid_parts.h); one piece, the whole input, most often.
    std::vector<Piece> pieces;
    {
        const std::vector<SolidPart> parts = solid_parts(input);
        pieces.resize(parts.size());
        for (size_t k = 0; k < parts.size(); ++k) pieces[k].closed = parts[k].closed;
        if (parts.size() == 1) {
            pieces[0].input = &input;
            pieces[0].unit = &unit;
        } else {
            for (size_t k = 0; k < parts.size(); ++k) {
                pieces[k].own_input = submesh(input, parts[k].triangles);
                pieces[k].own_unit = submesh(unit, parts[k].triangles);
                pieces[k].input = &pieces[k].own_input;
                pieces[k].unit = &pieces[k].own_unit;
            }
            unit = Mesh{};
        }
    }
    report.parts = static_cast<long>(pieces.size());
    clock.end();

    long midpoints_left = 2 * sites_wanted; // the thin walls' sampling, over all pieces
    for (Piece& piece : pieces) {
        clock.begin("normals");
        lift_piece(piece, params, to_unit, spacing, sites_wanted, unit_area, midpoints_left);
        clock.end();
    }
    if (params.local_sizing) {
        const long asked = sites_wanted;
        sites_wanted = sized_site_count(pieces, params, to_unit, spacing, asked, input_area, report);
        if (sites_wanted > asked)
            check_memory_budget(sites_wanted, input.triangles.rows(), resolve_threads(params.threads), physical_memory_bytes());
    }
    share_sites(pieces, sites_wanted);
    if (pieces.size() > 1) { // at least 4 sites a piece: many small solids may need more than asked for
        long shared = 0;
        for (const Piece& piece : pieces) shared += piece.sites;
        if (shared > sites_wanted)
            check_memory_budget(shared, input.triangles.rows(), resolve_threads(params.threads), physical_memory_bytes());
    }

    Mesh& out = result.mesh;
    long retry_sites = sites_wanted; // remesh_or_keep's retries: at most one more run's worth
    int furthest = 0;                // the optimiser's progress shown so far, over all pieces
    for (size_t k = 0; k < pieces.size(); ++k) {
        Piece& piece = pieces[k];
        // The optimiser's progress as one run over all pieces, each the same share; a piece
        // remeshed again (remesh_or_keep) holds the bar where it was rather than take it back.
        const ProgressCallback piece_progress =
            progress ? ProgressCallback([&progress, &furthest, k, n = static_cast<int>(pieces.size())](const Progress& p) {
                Progress all = p;
                if (all.total > 0) {
                    all.iteration = furthest = std::max(furthest, all.iteration + static_cast<int>(k) * all.total);
                    all.total *= n;
                }
                return progress(all);
            })
                     : ProgressCallback();
        append(out, remesh_or_keep(piece, params.seed + k, params, to_unit, spacing, unit_area, input_area,
                                   sites_wanted, retry_sites, clock, piece_progress,
                                   pieces.size() == 1 ? &report.input : nullptr, report));
        if (pieces.size() > 1) piece = Piece{}; // its copies, surface and tree freed (the only one's serves below)
    }
    if (out.triangles.rows() == 0)
        throw TopologyFailure("no part of the surface came out: too few vertices for this surface");

    // The whole input's tree: the only piece's, or built once the pieces' trees are freed.
    const AabbTree input_tree = pieces.size() == 1 ? std::move(*pieces[0].tree) : AabbTree(input);
    pieces.clear();

    clock.begin("untangle");
    // Closed pieces that stand for no part of the input (stray_components.h): bubbles the
    // triangulation closed where a member is thinner than the cells. Counted against the whole
    // input, once every piece is in; before the untangling, which then sees what is handed on.
    const StrayComponentStats strays = remove_stray_components(out, stray_component_params(mesh_components(input)));
    report.stray_components_removed = strays.removed;
    report.stray_inward_removed = strays.inward_removed;
    // Triangles passing through each other, untangled by flips (untangle.h), across pieces too.
    // The tree and the crossings left serve the report.
    const StepSettings steps = step_settings(spacing, to_unit.scale, sites_wanted);
    UntangleStats untangled = untangle(out, Reference{input, input_tree}, steps.untangle);
    report.edges_flipped += untangled.flipped;
    report.vertices_moved += untangled.moved;
    report.edges_collapsed += untangled.removed; // a tent's apex goes as onto a corner of its rim
    std::vector<std::pair<int32_t, int32_t>> crossings = std::move(untangled.crossings);
    AabbTree output_tree = std::move(*untangled.tree);
    // A tent's rim triangle, in the place of its three, can be as thin as the wall it stood
    // through: mended as the polish mends (mend_poor), kept if that makes no crossing more.
    if (untangled.removed > 0) {
        Mesh mended = out;
        RemeshReport counts;
        mend_poor(mended, Reference{input, input_tree}, steps.quality_polish, counts);
        AabbTree mended_tree(mended);
        std::vector<std::pair<int32_t, int32_t>> mended_crossings = self_intersecting_pairs(mended, mended_tree);
        if (mended_crossings.size() <= crossings.size()) {
            out = std::move(mended);
            output_tree = std::move(mended_tree);
            crossings = std::move(mended_crossings);
            add_counts(report, counts);
        }
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
