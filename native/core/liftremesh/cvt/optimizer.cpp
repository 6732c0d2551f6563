#include "liftremesh/cvt/optimizer.h"

#include "liftremesh/cvt/cvt_energy.h"
#include "liftremesh/exceptions.h"

#include <lbfgs.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

namespace liftremesh {

Schedule two_phase_schedule(int iterations) {
    Schedule s;
    s.feature = std::min(iterations, std::max(10, static_cast<int>(std::ceil(0.1 * iterations))));
    s.plain = iterations - s.feature;
    return s;
}

namespace {

// State shared with libLBFGS's C callbacks through its `instance` pointer (no globals).
struct Problem {
    const LiftedSurface* surface;
    double sigma;
    int threads;
    long rows, cols;
    const ProgressCallback* progress;
    int iteration_offset, total;
    int evaluations = 0;
    int iterations = 0;
    double first_energy = 0.0; // at the start point, first phase's sigma
    double last_energy = 0.0;  // at the last accepted iterate, its phase's sigma
    bool cancelled = false;
    std::exception_ptr error; // an exception from the objective, rethrown after lbfgs returns
    LiftedPoints sites, gradient;
    RvdCache* cache = nullptr; // neighbour lists carried from one iterate to the next
    // The variables L-BFGS sees are scale_k v_k (empty: v_k), scale_k = sqrt(m_k / mean m) for
    // the cells' masses m_k at the start of a run: the objective's Hessian is about 2 m_k per
    // site (Eq. 7), so that where the density varies by orders of magnitude (size_field.h) its
    // condition number falls back to what a uniform density gives, and the iterations converge
    // on the small cells as on the large ones.
    Eigen::VectorXd scale;
    long fixed = 0;          // the first sites, held where they are: their gradient is zero
    LiftedPoints held_rows;  // their coordinates, restored exactly (the scaling may round them)
};

lbfgsfloatval_t evaluate(void* instance, const lbfgsfloatval_t* x, lbfgsfloatval_t* g, const int n,
                         const lbfgsfloatval_t) {
    auto& p = *static_cast<Problem*>(instance);
    try {
        p.sites = Eigen::Map<const LiftedPoints>(x, p.rows, p.cols);
        if (p.scale.size() > 0) p.sites.array().colwise() /= p.scale.array();
        p.sites.topRows(p.fixed) = p.held_rows;
        const double f = cvt_objective(*p.surface, p.sites, p.sigma, p.threads, p.gradient, p.cache);
        // A zero gradient keeps a site still: L-BFGS's steps are sums of gradients and of past
        // steps, all zero in its coordinates.
        p.gradient.topRows(p.fixed).setZero();
        if (p.scale.size() > 0) p.gradient.array().colwise() /= p.scale.array();
        std::copy(p.gradient.data(), p.gradient.data() + n, g);
        if (p.evaluations++ == 0) p.first_energy = f; // libLBFGS evaluates the start point first
        return f;
    } catch (...) {
        // Unwinding through C is not allowed: report a non-finite value so the line search stops.
        p.error = std::current_exception();
        std::fill(g, g + n, 0.0);
        return std::numeric_limits<double>::quiet_NaN();
    }
}

int on_iteration(void* instance, const lbfgsfloatval_t*, const lbfgsfloatval_t*, const lbfgsfloatval_t fx,
                 const lbfgsfloatval_t, const lbfgsfloatval_t gnorm, const lbfgsfloatval_t, int, int k, int) {
    auto& p = *static_cast<Problem*>(instance);
    p.iterations = k;
    p.last_energy = fx;
    if (p.error) return 1;
    if (*p.progress) {
        Progress info{"optimize", p.iteration_offset + k, p.total, fx, gnorm};
        if (!(*p.progress)(info)) {
            p.cancelled = true;
            return 1; // non-zero stops lbfgs()
        }
    }
    return 0;
}

// sqrt(m_k / mean m) for the cells' masses m_k (Problem::scale); an empty cell's, or one of
// almost no mass, as if it had a hundredth of the mean.
Eigen::VectorXd preconditioner(const LiftedSurface& surface, const LiftedPoints& sites, int threads, RvdCache* cache) {
    const Eigen::VectorXd mass = restricted_cell_masses(surface, sites, threads, cache);
    const double mean = mass.mean();
    Eigen::VectorXd scale(mass.size());
    for (Eigen::Index k = 0; k < mass.size(); ++k)
        scale[k] = mean > 0.0 ? std::sqrt(std::max(mass[k] / mean, 0.01)) : 1.0;
    return scale;
}

// One phase: up to `iterations` L-BFGS iterations at a fixed sigma. Returns iterations done.
int run_phase(Problem& problem, LiftedPoints& sites, int iterations) {
    lbfgs_parameter_t param;
    lbfgs_parameter_init(&param);
    param.m = 7;
    param.max_iterations = iterations;
    param.epsilon = 1e-12; // run the requested iterations: the budget is the stop criterion
    param.past = 0;
    param.max_linesearch = 20;
    const int n = static_cast<int>(sites.size());
    lbfgsfloatval_t* x = lbfgs_malloc(n);
    if (!x) throw NumericalFailure("out of memory for " + std::to_string(n) + " optimisation variables");
    if (problem.scale.size() > 0) problem.scale = preconditioner(*problem.surface, sites, problem.threads, problem.cache);
    LiftedPoints start = sites;
    if (problem.scale.size() > 0) start.array().colwise() *= problem.scale.array();
    std::copy(start.data(), start.data() + n, x);
    lbfgsfloatval_t fx = 0.0;
    problem.iterations = 0;
    const int status = lbfgs(n, x, &fx, evaluate, on_iteration, &problem, &param);
    // On success, a reached budget, or a failed line search, x holds the best point found.
    if (!problem.error && std::all_of(x, x + n, [](double v) { return std::isfinite(v); })) {
        std::copy(x, x + n, sites.data());
        if (problem.scale.size() > 0) sites.array().colwise() /= problem.scale.array();
        sites.topRows(problem.fixed) = problem.held_rows;
    }
    lbfgs_free(x);
    if (problem.cancelled) throw Cancelled("remeshing was cancelled during the optimisation");
    if (problem.error) std::rethrow_exception(problem.error);
    if (status == LBFGSERR_OUTOFMEMORY) throw NumericalFailure("L-BFGS ran out of memory");
    return problem.iterations;
}

} // namespace

OptimizeResult optimize_sites(const LiftedSurface& surface, LiftedPoints& sites, double sigma, int iterations,
                              int threads, const ProgressCallback& progress, RvdCache* cache, const HeldSites& held) {
    OptimizeResult result;
    RvdCache own;
    const Schedule schedule = sigma > 1.0 ? two_phase_schedule(iterations) : Schedule{iterations, 0};
    Problem problem;
    problem.surface = &surface;
    problem.sigma = 1.0;
    problem.threads = resolve_threads(threads);
    problem.rows = sites.rows();
    problem.cols = sites.cols();
    problem.progress = &progress;
    if (held.count < 0 || held.count > sites.rows() || !(held.reseat_after >= 0.0 && held.reseat_after <= 1.0))
        throw InvalidInput("optimize_sites: the held sites must be between 0 and the number of sites, and the "
                           "reseating between 0 and 1 of the iterations");
    problem.fixed = held.count;
    problem.held_rows = sites.topRows(held.count);
    problem.cache = cache ? cache : &own;
    problem.iteration_offset = 0;
    problem.total = iterations;
    // Preconditioned where the weights vary more than rho^delta alone makes them (at most
    // (1 + 2 / eta)^delta, 6.3 with the defaults): a size field's (size_field.h).
    if (surface.weights.size() > 0 && surface.weights.maxCoeff() > kPreconditionContrast * surface.weights.minCoeff())
        problem.scale = Eigen::VectorXd::Ones(sites.rows());
    // Phase 1 (sigma = 1), then phase 2 (sigma) (Section 6.2.2). A phase whose line search
    // fails early is restarted (fresh L-BFGS memory) while it still makes progress.
    // The reseating, if any, splits the first phase in two.
    const int reseat_at = held.reseat ? std::min(schedule.plain, static_cast<int>(std::lround(held.reseat_after * iterations))) : 0;
    const std::pair<double, int> phases[3] = {{1.0, reseat_at}, {1.0, schedule.plain - reseat_at}, {sigma, schedule.feature}};
    for (int phase = 0; phase < 3; ++phase) {
        const auto& [phase_sigma, budget] = phases[phase];
        if (phase == 1 && held.reseat) {
            const Eigen::Index rows = sites.rows(), cols = sites.cols();
            const bool changed = held.reseat(sites) > 0;
            if (sites.rows() != rows || sites.cols() != cols || sites.topRows(held.count) != problem.held_rows)
                throw InvalidInput("optimize_sites: the reseating changed the number of sites or a held one");
            if (changed) *problem.cache = RvdCache{}; // lists of other sites
        }
        problem.sigma = phase_sigma;
        int left = budget;
        while (left > 0) {
            problem.iteration_offset = result.iterations;
            const int done = run_phase(problem, sites, left);
            result.iterations += done;
            left -= done;
            if (done == 0) break;
        }
    }
    result.evaluations = problem.evaluations;
    result.energy_initial = problem.first_energy;
    result.energy_final = result.iterations > 0 ? problem.last_energy : problem.first_energy;
    return result;
}

} // namespace liftremesh
