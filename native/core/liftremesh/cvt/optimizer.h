// Minimisation of the CVT objective with L-BFGS (libLBFGS, Liu and Nocedal [19]) in the
// two-phase schedule of Section 6.2.2.
#pragma once

#include "liftremesh/cvt/rvd.h"
#include "liftremesh/progress.h"

#include <functional>

namespace liftremesh {

struct OptimizeResult {
    int iterations = 0;          //!< L-BFGS iterations done, both phases
    int evaluations = 0;         //!< objective evaluations (RVD computations)
    double energy_initial = 0.0; //!< F at the start, with the first phase's sigma (1 unless iterations <= 10)
    double energy_final = 0.0;   //!< F at the last iterate, with its phase's sigma
};

//! The iteration counts of the two phases for `iterations` in all: sigma = 1 for the first
//! 90%, then sigma for the rest, at least 10 (all of them if iterations <= 10).
struct Schedule {
    int plain = 0;   //!< iterations with sigma = 1
    int feature = 0; //!< iterations with sigma
};
Schedule two_phase_schedule(int iterations);

//! Weights varying by more than this factor over the surface make optimize_sites precondition
//! the sites by their cells' masses (optimizer.cpp).
constexpr double kPreconditionContrast = 16.0;

//! Sites held still through the optimisation, and a reseating of the free ones (crease_sites.h).
struct HeldSites {
    long count = 0; //!< the first `count` sites stay where they are (0 <= count <= #S)
    //! If set, called once, after `reseat_after` of the iterations (in the phase with sigma = 1),
    //! with the sites, which it may change from row `count` on (not their number); returns how many
    //! it changed. The L-BFGS memory starts afresh after it.
    std::function<long(LiftedPoints&)> reseat;
    double reseat_after = 0.3; //!< a fraction of the iterations, in [0, 1]
};

//! Moves `sites` (#S by d) to a local minimum of the objective (Eq. 25) by L-BFGS, Algorithm 3
//! lines 6-9. With sigma == 1 the whole budget is one phase. `progress` (may be empty) is called
//! after each iteration; returning false throws Cancelled. A line search that fails (the
//! objective is only C^2 almost everywhere, Section 3.2.3) ends the phase at the best point.
//! `cache` (may be null) is the diagram's RvdCache the evaluations use: given, it is left with
//! the lists and seeds of the last diagram, which the restricted Delaunay triangulation of the
//! result can start from. Where the weights vary by more than kPreconditionContrast, the
//! sites are preconditioned by their cells' masses (optimizer.cpp). `held`: sites that do not
//! move, and a reseating of the others (see HeldSites); InvalidInput if out of range.
OptimizeResult optimize_sites(const LiftedSurface& surface, LiftedPoints& sites, double sigma, int iterations,
                              int threads, const ProgressCallback& progress = {}, RvdCache* cache = nullptr,
                              const HeldSites& held = {});

} // namespace liftremesh
