// The feature-sensitive, density-weighted CVT objective on the lifted surface (Eq. 25) and its
// gradient (Algorithm 2), one entry point for both as in geogram's CVT.
#pragma once

#include "liftremesh/cvt/rvd.h"

namespace liftremesh {

//! F(V, sigma, delta) = sum_k sum_p rho_p^delta int_{Omega_{k|T_p}} |M_p(sigma)(x - v_k)|^2 dx
//! (Eq. 25, with M_p(sigma) = I + (sigma - 1) Pi_p, Eq. 14), for `sites` #S by d.
//! Writes dF/dV into `gradient` (#S by d): the inner term 2 |Omega| M^t M (v - g) (Eqs. 7, 17)
//! and, for sigma > 1, the bisector boundary term (Eq. 20). The density weights rho_p^delta are
//! surface.weights. Returns F.
//!
//! Two printing slips of Algorithm 2 are corrected here (and checked against finite differences
//! in cvt_energy_test): line 12 adds (sigma^2 - 1) |Omega| |w_perp|^2 (Eq. 11; no factor 2), and
//! line 13 adds -2 |Omega| (sigma^2 - 1) w_perp, since w_perp = Pi (c - v_k) points away from v_k.
//! `cache` (may be null) carries the diagram's neighbour lists between calls (RvdCache).
double cvt_objective(const LiftedSurface& surface, const LiftedPoints& sites, double sigma, int threads,
                     LiftedPoints& gradient, RvdCache* cache = nullptr);

} // namespace liftremesh
