// Sites held on the input's creases (issue 35): one on each corner of the creases, and along
// each chain of crease edges between two corners (or round a closed loop) as many as the local
// spacing fits, evenly. Held still through the optimisation, they become vertices exactly on the
// creases and their corners, and the free sites' Voronoi cells settle round them (Algorithm 3 with
// these sites fixed): the triangles along a crease have their CVT shape, where moving a vertex
// onto the crease after the triangulation (snap/crease_snap.h) must spoil them or give up.
//
// The spacing is the one the free sites reach: on a surface a cell's area goes as
// density^(-1/2) and its size as density^(-1/4) (Eq. 25's weights w_p = rho_p^delta, with the
// size field's when local sizing is on), so a vertex's spacing is
// h_v = sqrt((M / N) / (sqrt(3) / 2 * d_v)), with M the surface's sampling mass (sum of
// |T_p| sqrt(w_p), sampling.h), N the sites and d_v the mean of sqrt(w_p) over the triangles at
// v. A candidate site closer than half its spacing to one taken before (corners
// first) is dropped: two creases nearer than that (the rims of a sliver ring) cannot both have
// their own row of vertices without triangles far thinner than the rest.
#pragma once

#include "liftremesh/cvt/rvd.h"
#include "liftremesh/mesh/creases.h"
#include "liftremesh/spatial/segment_index.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace liftremesh {

struct CreaseSitesParams {
    //! Candidates closer than this times their spacing to one taken before are dropped. Not
    //! negative.
    double min_separation = 0.5;
    //! At most this fraction of the sites is held: past it, the corners alone, and past it
    //! again, none (a part whose creases the budget cannot follow). In [0, 1].
    double max_fraction = 0.25;
    //! When the corners alone fit in max_fraction, the parts of chains nearer than this times
    //! the spacing to another chain are held with them, within the fraction: there two creases
    //! bound a strip narrower than the cells (a thread's crest running out into its end face),
    //! which the snap cannot give a vertex on each side without folding it. None within two
    //! spacings of a corner, where every chain is near the others, and none alone on its chain
    //! (two creases parting at a narrow angle, a knife's tip): runs of two or more. 0 holds the
    //! corners alone. Not negative.
    double crowded = 0.8;
    //! Free sites closer than this times the spacing to a crease crowd it (free_sites,
    //! reseat_crowding_sites); to a crease whose faces meet at an interior angle alpha under 90
    //! degrees, closer than this over sin(alpha), at most twice this: a site there is nearer to
    //! the other face than the clearance. Not negative.
    double clearance = 0.5;
};

//! The sites held on the creases of a surface, and the free sites that crowd them.
class CreaseSites {
public:
    //! For `sites` sites in all on `surface`, whose first vertices are those `creases` (the crease
    //! edges: crease_edges() in mesh/creases.h) index. Throws InvalidInput for an index or a
    //! parameter out of range.
    CreaseSites(const LiftedSurface& surface, const std::vector<CreaseEdge>& creases, long sites,
                const CreaseSitesParams& params = {});

    //! The held sites (rows, lifted like the surface's points): corners (vertices with other
    //! than two crease edges) first, by vertex index, then the chains' (their crowded parts
    //! only, when the chains do not all fit: see CreaseSitesParams::crowded).
    const LiftedPoints& held() const { return held_; }
    //! Whether sites are held along the creases' chains, not only on their corners.
    bool rows_held() const { return rows_held_; }

    //! `count` sites drawn as random_sites(surface, count, seed) draws them, none of which crowds
    //! a crease (lies closer than the clearance times the spacing there to one, on the lifted
    //! surface: the other side of a wall lifted apart, thin_walls.h, is not near) unless too few
    //! others were drawn.
    LiftedPoints free_sites(const LiftedSurface& surface, long count, std::uint64_t seed) const;

    //! Replaces the rows of `sites` from `first` on that crowd a crease by free_sites; returns
    //! how many. A local minimum of the objective can leave a free site in a face narrower than
    //! the spacing between two rows of held sites, or just off a row, where its cell parts two
    //! held neighbours: their crease edge is then missing, and the triangles cut across.
    long reseat_crowding_sites(const LiftedSurface& surface, LiftedPoints& sites, long first, std::uint64_t seed) const;

private:
    std::vector<CreaseEdge> creases_;
    Eigen::VectorXd spacing_;    // per vertex, the local spacing (0 where no crease passes)
    LiftedPoints held_;
    bool rows_held_ = false;
    std::optional<SegmentIndex> edges_; // the crease edges in 3D, once some site is held
    std::vector<std::pair<Eigen::RowVectorXd, Eigen::RowVectorXd>> lifted_ends_; // per crease edge
    double reach_ = 0.0; // the farthest a site that crowds a crease can be from it
    CreaseSitesParams params_;

    double clearance(double turn_deg) const;
    bool crowds(const Eigen::Ref<const Eigen::RowVectorXd>& site, std::vector<int32_t>& found) const;
};

} // namespace liftremesh
