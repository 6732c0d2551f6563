#include "liftremesh/report.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace liftremesh {

namespace {

//! A number as JSON: 9 significant digits, locale-independent; NaN and infinities as null.
std::string json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 9);
    return std::string(buffer, result.ptr);
}

std::string json_number(long value) { return std::to_string(value); }

//! A string as JSON: quotes, backslashes and control characters escaped.
std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char escape[8];
                std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned char>(c));
                out += escape;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

//! Members of a JSON object as (key, already-formatted value), written one per line.
using Members = std::vector<std::pair<std::string, std::string>>;

std::string json_object(const Members& members, int indent) {
    if (members.empty()) return "{}";
    const std::string inner(static_cast<size_t>(indent + 2), ' ');
    std::string out = "{\n";
    for (size_t i = 0; i < members.size(); ++i) {
        out += inner + json_string(members[i].first) + ": " + members[i].second;
        out += i + 1 < members.size() ? ",\n" : "\n";
    }
    return out + std::string(static_cast<size_t>(indent), ' ') + "}";
}

//! A JSON array on one line, each item written by `format` (json_number, json_string).
template <class Items, class Format>
std::string json_array(const Items& items, Format format) {
    std::string out = "[";
    for (const auto& item : items) out += (out.size() > 1 ? ", " : "") + format(item);
    return out + "]";
}

//! A component as a one-line JSON object; signed_volume null for an open one.
std::string json_component(const MeshComponent& c) {
    return "{\"triangles\": " + json_number(c.triangles) + ", \"area\": " + json_number(c.area) +
           ", \"closed\": " + (c.closed ? "true" : "false") +
           ", \"signed_volume\": " + (c.closed ? json_number(c.signed_volume) : std::string("null")) +
           ", \"cavity\": " + (c.cavity ? "true" : "false") + "}";
}

std::string json_quality(const MeshQuality& q, int indent) {
    const std::string histogram = json_array(q.kappa_histogram, [](long n) { return json_number(n); });
    return json_object({{"vertices", json_number(q.vertices)},
                        {"triangles", json_number(q.triangles)},
                        {"kappa_min", json_number(q.kappa_min)},
                        {"kappa_mean", json_number(q.kappa_mean)},
                        {"kappa_histogram", histogram},
                        {"min_angle_deg", json_number(q.min_angle_deg)},
                        {"edge_length_min", json_number(q.edge_length_min)},
                        {"edge_length_max", json_number(q.edge_length_max)},
                        {"boundary_edges", json_number(q.boundary_edges)},
                        {"boundary_loops", json_number(q.boundary_loops)},
                        {"nonmanifold_edges", json_number(q.nonmanifold_edges)},
                        {"nonmanifold_vertices", json_number(q.nonmanifold_vertices)},
                        {"extra_vertex_fans", json_number(q.extra_vertex_fans)},
                        {"oriented", q.oriented ? "true" : "false"},
                        {"components", json_number(q.components)},
                        {"closed_components", json_number(q.closed_components)},
                        {"inward_components", json_number(q.inward_components)},
                        {"cavities", json_number(q.cavities)},
                        {"component_list", json_array(q.component_list, json_component)},
                        {"euler_characteristic", json_number(static_cast<long>(q.euler_characteristic))},
                        {"sharp_edge_length", json_number(q.sharp_edge_length)},
                        {"folded_edges", json_number(q.folded_edges)},
                        {"folded_edge_length", json_number(q.folded_edge_length)},
                        {"self_intersections", json_number(q.self_intersections)}},
                       indent);
}

//! Stage timings in their order; a stage named twice appears once with the summed time, so that
//! the object has no duplicate key.
std::string json_timings(const std::vector<StageTime>& timings, int indent) {
    std::vector<std::pair<std::string, double>> merged;
    for (const StageTime& t : timings) {
        auto it = merged.begin();
        while (it != merged.end() && it->first != t.stage) ++it;
        if (it == merged.end())
            merged.emplace_back(t.stage, t.seconds);
        else
            it->second += t.seconds;
    }
    Members members;
    for (const auto& [stage, seconds] : merged) members.emplace_back(stage, json_number(seconds));
    return json_object(members, indent);
}

} // namespace

long cracks_closed(const RemeshReport& report) {
    return std::max(0L, report.input.boundary_loops - report.output.boundary_loops);
}

long vertex_fans_split(const RemeshReport& report) {
    return std::max(0L, report.input.extra_vertex_fans - report.output.extra_vertex_fans);
}

int expected_euler_characteristic(const RemeshReport& report) {
    return report.input.euler_characteristic + static_cast<int>(cracks_closed(report) + vertex_fans_split(report));
}

std::vector<std::string> report_warnings(const RemeshReport& report) {
    std::vector<std::string> found;
    const MeshQuality &in = report.input, &out = report.output;
    // Each crack of the source that the result closes (a boundary loop narrower than the cells,
    // which the diagram spans) raises the Euler characteristic by one, as a filled hole does, and
    // so does each fan of a non-manifold vertex that the (manifold) result gives a vertex of its
    // own: that is the repair asked for, not another topology.
    if (out.euler_characteristic != expected_euler_characteristic(report))
        found.push_back("the result's topology differs from the source's (Euler characteristic " +
                        std::to_string(out.euler_characteristic) + ", source " + std::to_string(in.euler_characteristic) +
                        "): parts thinner than the target edge length merged or broke; ask for more vertices or a "
                        "smaller edge length");
    if (out.components > in.components)
        found.push_back("the result has " + std::to_string(out.components) + " components, the source " +
                        std::to_string(in.components) + ": pieces the source does not have");
    if (out.inward_components > in.inward_components)
        found.push_back("the result has " + std::to_string(out.inward_components) +
                        " closed components facing inward (negative volume), the source " +
                        std::to_string(in.inward_components) + ": FEM and TetGen refuse them");
    if (report.stray_components_removed > 0)
        found.push_back(std::to_string(report.stray_components_removed) + " small closed " +
                        (report.stray_components_removed == 1 ? "piece" : "pieces") + " standing for no part of the source (" +
                        std::to_string(report.stray_inward_removed) +
                        " facing inward) removed from the result; ask for more vertices or a smaller edge length");
    if (report.parts_kept > 0)
        found.push_back("of the source's " + std::to_string(report.parts) + " parts, " +
                        std::to_string(report.parts_kept) +
                        (report.parts_kept == 1 ? " is thinner or smaller than the target edge length and keeps"
                                                : " are thinner or smaller than the target edge length and keep") +
                        " the source's triangles; ask for more vertices or a smaller edge length");
    // "n of the source's N parts", for the parts remeshed again another way.
    auto of_the_parts = [&report](long n) {
        return std::to_string(n) + " of the source's " + std::to_string(report.parts) +
               (report.parts == 1 ? " part" : " parts");
    };
    if (report.parts_unheld > 0)
        found.push_back("the creases of " + of_the_parts(report.parts_unheld) +
                        " were snapped to, not held: sites held on them broke the surface (creases closer "
                        "together than the target edge length); ask for a smaller edge length to hold them");
    if (report.parts_eta_reduced > 0)
        found.push_back("the normals of " + of_the_parts(report.parts_eta_reduced) +
                        " were averaged over balls a quarter of the target edge length wide, not eta: with eta's "
                        "the surface broke (members or holes smaller than eta)");
    if (out.boundary_loops > in.boundary_loops)
        found.push_back("the result has " + std::to_string(out.boundary_loops) + " boundary loops, the source " +
                        std::to_string(in.boundary_loops) + ": holes the source does not have");
    if (out.self_intersections > 0)
        found.push_back("the result has " + std::to_string(out.self_intersections) +
                        " pairs of triangles passing through each other or touching (the source " +
                        std::to_string(in.self_intersections) + "): a tetrahedral mesher will refuse it");
    // A knife edge of the source, followed, is folded too: only a longer total is news (a tenth
    // more, for its resampling).
    if (out.folded_edges > 0 && out.folded_edge_length > 1.1 * in.folded_edge_length)
        found.push_back("the result has " + std::to_string(out.folded_edges) +
                        " edges whose two triangles are folded onto each other (the source " +
                        std::to_string(in.folded_edges) + "): a tetrahedral mesher will refuse it");
    if (report.hausdorff_relative > kFarFromInput) {
        char text[160];
        std::snprintf(text, sizeof text, "the result is up to %.2g %% of the bounding-box diagonal away from the source",
                      100.0 * report.hausdorff_relative);
        found.emplace_back(text);
    }
    return found;
}

std::string to_json(const RemeshReport& report) {
    return json_object({{"input", json_quality(report.input, 2)},
                        {"output", json_quality(report.output, 2)},
                        {"input_duplicates_removed", json_number(report.input_cleaning.duplicates_removed)},
                        {"input_degenerate_removed", json_number(report.input_cleaning.degenerate_removed)},
                        {"input_facets_turned", json_number(report.input_cleaning.facets_turned)},
                        {"bbox_diagonal", json_number(report.bbox_diagonal)},
                        {"hausdorff_relative", json_number(report.hausdorff_relative)},
                        {"mean_distance_relative", json_number(report.mean_distance_relative)},
                        {"sites", json_number(report.sites)},
                        {"parts", json_number(report.parts)},
                        {"parts_kept", json_number(report.parts_kept)},
                        {"size_smallest", json_number(report.size_field.smallest)},
                        {"size_largest", json_number(report.size_field.largest)},
                        {"size_refined_walls", json_number(report.size_field.walls)},
                        {"size_refined_curvature", json_number(report.size_field.curvature)},
                        {"size_refined", json_number(report.size_field.refined)},
                        {"iterations", json_number(static_cast<long>(report.iterations))},
                        {"evaluations", json_number(static_cast<long>(report.evaluations))},
                        {"energy_initial", json_number(report.energy_initial)},
                        {"energy_final", json_number(report.energy_final)},
                        {"crease_sites", json_number(report.crease_sites)},
                        {"parts_unheld", json_number(report.parts_unheld)},
                        {"parts_eta_reduced", json_number(report.parts_eta_reduced)},
                        {"sites_split", json_number(report.sites_split)},
                        {"holes_filled", json_number(report.holes_filled)},
                        {"triangles_removed", json_number(report.triangles_removed)},
                        {"edges_collapsed", json_number(report.edges_collapsed)},
                        {"vertices_inserted", json_number(report.vertices_inserted)},
                        {"edges_flipped", json_number(report.edges_flipped)},
                        {"vertices_moved", json_number(report.vertices_moved)},
                        {"boundary_vertices_snapped", json_number(report.boundary_vertices_snapped)},
                        {"stray_components_removed", json_number(report.stray_components_removed)},
                        {"stray_inward_removed", json_number(report.stray_inward_removed)},
                        {"cracks_closed", json_number(cracks_closed(report))},
                        {"vertex_fans_split", json_number(vertex_fans_split(report))},
                        {"expected_euler_characteristic",
                         json_number(static_cast<long>(expected_euler_characteristic(report)))},
                        {"timings", json_timings(report.timings, 2)},
                        {"warnings", json_array(report.warnings, json_string)}},
                       0) +
           "\n";
}

} // namespace liftremesh
