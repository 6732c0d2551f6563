// The report of a remesh run: quality of input and output, distance, timings; as JSON.
#pragma once

#include "liftremesh/measure/quality.h"
#include "liftremesh/mesh/input_cleaning.h"

#include <string>
#include <vector>

namespace liftremesh {

struct StageTime {
    std::string stage; //!< "read", "normals", "optimize", "rdt", ...
    double seconds = 0.0;
};

//! What the local size field (size_field.h) asked for, over all pieces; zeros without one.
struct SizeFieldSummary {
    double smallest = 0.0;  //!< the field's smallest edge, input units, scaled as the sites asked for meet it
    double largest = 0.0;   //!< its largest
    double walls = 0.0;     //!< share of the input's area refined for walls or slots thinner than the largest
    double curvature = 0.0; //!< share refined for bends tighter than the largest allows
    double refined = 0.0;   //!< share under the largest in the end, the grading around both included
};

struct RemeshReport {
    InputCleaning input_cleaning;        //!< the input's facets dropped and turned before remeshing (input_cleaning.h)
    MeshQuality input;                   //!< once cleaned
    MeshQuality output;
    double bbox_diagonal = 0.0;          //!< of the input, input units
    double hausdorff_relative = 0.0;     //!< two-sided Hausdorff / bbox_diagonal
    double mean_distance_relative = 0.0; //!< mean sampled distance / bbox_diagonal
    long sites = 0;                      //!< number of sites optimised
    long parts = 1;                      //!< pieces remeshed on their own: each closed component, and the
                                         //!< open ones together (solid_parts.h)
    long parts_kept = 0;                 //!< of those, closed components too thin or small for their sites,
                                         //!< which keep the input's triangles (pipeline.h)
    SizeFieldSummary size_field;         //!< the local sizing's sizes and where it refined
    int iterations = 0;                  //!< L-BFGS iterations done
    int evaluations = 0;                 //!< objective evaluations (diagrams computed), line searches included
    double energy_initial = 0.0;         //!< objective at the random start (first phase's sigma)
    double energy_final = 0.0;           //!< objective at the last iterate (its phase's sigma)
    long crease_sites = 0;               //!< sites held on the creases and their corners (crease_sites.h)
    long parts_unheld = 0;               //!< parts whose creases were snapped to, not held: holding them
                                         //!< broke the part's surface (pipeline.h)
    long parts_eta_reduced = 0;          //!< parts lifted again with normals over a smaller ball: the
                                         //!< part's surface broke with eta's (pipeline.h)
    long sites_split = 0;                //!< sites whose restricted cell came in pieces, a vertex each (rdt.h)
    long holes_filled = 0;
    long triangles_removed = 0;          //!< by the manifold repair (repair.h), darts jutting into the holes
                                         //!< it fills (hole_filling.h), and flaps beyond an open input's
                                         //!< boundary (boundary_snap.h)
    long edges_collapsed = 0;            //!< short edges, folded pairs and edges of triangles under kappa 0.3
                                         //!< collapsed (edge_collapse.h), crossing tents (untangle.h)
    long vertices_inserted = 0;          //!< input points inserted where a sharp edge (hausdorff_refinement.h) or an
                                         //!< acute corner of an open boundary (boundary_snap.h) was cut off, or
                                         //!< where a triangle under kappa 0.3 had its longest edge split (edge_collapse.h)
    long edges_flipped = 0;              //!< edges flipped at the end: for quality (quality_polish.h), onto knife
                                         //!< edges (crease_snap.h), out of crossings (untangle.h)
    long vertices_moved = 0;             //!< vertex moves onto creases (crease_snap.h) and their curves
                                         //!< (crease_curves.h), for triangle quality at the end
                                         //!< (quality_polish.h), out of crossings (untangle.h)
    long boundary_vertices_snapped = 0;  //!< moved onto the input's boundary (boundary_snap.h)
    long stray_components_removed = 0;   //!< small closed pieces standing for no part of the input,
                                         //!< removed (stray_components.h)
    long stray_inward_removed = 0;       //!< of those, facing inward
    std::vector<StageTime> timings;
    //! What a user should know about a result that is not a faithful copy of its input, as
    //! sentences (report_warnings()); empty when all is well.
    std::vector<std::string> warnings;
};

//! Relative Hausdorff distance above which the result is reported as far from its input (1%).
constexpr double kFarFromInput = 0.01;

//! The input's boundary loops the result does not have: cracks (unwelded seams, slits narrower
//! than the cells) that the diagram spans and the result closes. 0 if it has as many or more.
long cracks_closed(const RemeshReport& report);

//! The fans of the input's non-manifold vertices that the result does not have (extra_vertex_fans
//! in minus out): parts touching at a point, a vertex of each fan in the result. 0 if none.
long vertex_fans_split(const RemeshReport& report);

//! The Euler characteristic the result has when it keeps the input's topology: the input's, plus
//! one per crack closed and one per vertex fan split (each is the repair asked for).
int expected_euler_characteristic(const RemeshReport& report);

//! The warnings of a finished report: components the input does not have (more than its
//! components), closed components facing inward beyond the input's (its cavities),
//! stray pieces removed (stray_components_removed), another topology than the input's (parts thinner than
//! the target edge length merge or break: "Problems may happen if the number of samples is
//! insufficient, in regions where S is thin", Section 2.2), more boundary loops than the input
//! (holes), closed parts of the input that keep its triangles (parts_kept), triangles passing through each other (output.self_intersections, whatever the
//! input's), or a Hausdorff distance above kFarFromInput. The input's cracks that the result
//! closes (fewer boundary loops) and the non-manifold vertices it splits are not another
//! topology: its Euler characteristic may be expected_euler_characteristic().
std::vector<std::string> report_warnings(const RemeshReport& report);

//! The report as a JSON object (keys documented in docs/report.md), indented by two spaces and
//! ending with a newline. Doubles have 9 significant digits; NaN and infinities are written
//! as null. A stage listed twice in `timings` appears once, with the summed time.
std::string to_json(const RemeshReport& report);

} // namespace liftremesh
