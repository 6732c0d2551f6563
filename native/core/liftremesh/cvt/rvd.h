// The restricted Voronoi diagram (RVD) of sites on a triangulated surface in R^d, d = 3 or 6
// (Section 2.2): for every site k and triangle T_p, the convex polygon Omega_{k|T_p} of the
// points of T_p nearer to site k than to any other site (Eq. 3).
//
// Computed as in Levy and Bonneel (Section 2.2.2): no Voronoi diagram is built; each triangle is
// clipped by the bisectors of a site and its nearest neighbours (kd-tree), stopping when the
// next neighbour is farther than twice the polygon's radius around the site (the security
// radius: no farther site can cut it). Each triangle is processed on its own, starting from the
// site nearest to its centroid and propagating to the sites across the bisector edges found;
// the cells' dual graph within a convex triangle is connected, so none is missed, and no input
// connectivity is used, so gaps and T-junctions need no special case. Runs of triangles are
// spread over threads with OpenMP.
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/neighbor_search.h"
#include "liftremesh/system/threads.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

namespace liftremesh {

//! The (lifted) surface the diagram is restricted to, with what every evaluation needs. Its
//! triangles, and the rows of every per-triangle field, lie along a Morton curve of their 3D
//! centroids: the diagram's processing order, in which neighbouring triangles, which share
//! sites, are neighbours in memory too, whatever order they came in (a soup, a mesh whose
//! triangles were split and appended).
struct LiftedSurface {
    LiftedPoints points;     //!< #V by d, in the order given
    Triangles triangles;     //!< #F by 3
    Eigen::VectorXd weights; //!< #F objective weights rho_p^delta (Eq. 25)
    LiftedPoints u1, u2;     //!< #F by d orthonormal tangent basis of each triangle (Eq. 15)
    std::vector<char> valid; //!< #F false for flat triangles (no basis): ignored (Section 3.1)
    //! #F: the row of each triangle as they were given (the k-th given is row row_of[k]). Sums
    //! over the triangles and the random sampling take them in that order, so that neither
    //! depends on the processing order.
    std::vector<int32_t> row_of;
    int dimension() const { return static_cast<int>(points.cols()); }
};

//! Builds the surface and its tangent bases, the triangles and weights reordered (see above).
//! `weights` empty means all ones.
LiftedSurface make_lifted_surface(LiftedPoints points, Triangles triangles, Eigen::VectorXd weights = {});

//! Total area of the valid triangles of the (lifted) surface.
double lifted_area(const LiftedSurface& surface);

//! A site seen from the plane of triangle T_p, with w = v - x0 (x0 the triangle's first vertex):
//! its in-plane coordinates ab = (w . u1, w . u2) and |w|^2. Its squared distance to the plane
//! is |w|^2 - |ab|^2.
struct PlanarSite {
    Eigen::Vector2d ab;
    double norm2 = 0.0;
    double off_plane2() const { return std::max(0.0, norm2 - ab.squaredNorm()); }
};

//! One polygon Omega_{k|T_p} of the diagram, valid only during the visitor call. It lies in the
//! plane of T_p and is given in that triangle's frame: vertex i is
//! x0 + planar[2i] u1 + planar[2i+1] u2, with x0 the triangle's first vertex and (u1, u2) its
//! tangent basis (Eq. 15, surface.u1/u2).
struct RvdPolygon {
    int32_t site = -1;               //!< k
    int32_t triangle = -1;           //!< p: the surface's row (LiftedSurface::row_of maps the given triangles to it)
    int size = 0;                    //!< number of vertices (>= 3), in the triangle's orientation
    const double* planar = nullptr;  //!< size by 2 vertex coordinates in the triangle's frame
    //! edges[i] is the line carrying the edge from vertex i to vertex i+1: a site l >= 0 for the
    //! bisector of k and l, or -1 - j for edge j of the triangle (from its vertex j to j+1).
    const int32_t* edges = nullptr;
    PlanarSite site_planar;              //!< site k in the triangle's frame
    const PlanarSite* edge_sites = nullptr; //!< per edge, site l in the frame (bisector edges only)
    //! Site k's rank among the sites of this polygon's chunk, in the order the chunk first visits
    //! them (0, 1, 2, ...): a new site comes with the chunk's next rank. Lets a visitor keep one
    //! sum per site and chunk in a short array instead of one per polygon or a #S array per chunk.
    int32_t chunk_rank = -1;
};

//! Called for every non-empty polygon with the chunk it belongs to, in [0, rvd_chunks(surface)).
using PolygonVisitor = std::function<void(int chunk, const RvdPolygon& polygon)>;

//! A visitor's per-chunk accumulator, on a cache line of its own: threads write the slots of
//! their chunks on every polygon, and slots sharing a line would make them invalidate each
//! other's caches.
template <class T>
struct alignas(64) ChunkSlot {
    T value{};
};

//! The number of chunks the diagram's triangles are split into: runs of the processing order
//! that threads take one at a time. Depends on the triangle count only (at most 256), not on
//! the thread count.
int rvd_chunks(const LiftedSurface& surface);

struct RvdCache;   // below
struct RvdScratch; // rvd.cpp: per-thread scratch that one diagram hands to the next

//! Per-site sums of a visitor, kept per chunk (one entry per site of the chunk, found by
//! RvdPolygon::chunk_rank) and added up chunk after chunk: the same sums, to the bit, whatever
//! the thread count.
template <class T>
class ChunkSiteSums {
public:
    //! With `cache`, each chunk's room is made for as many sites as its chunk held in the cache's
    //! last diagram (RvdCache::chunk_sites), so that the sums grow without moving.
    ChunkSiteSums(const LiftedSurface& surface, const T& zero, const RvdCache* cache = nullptr);
    //! The running sum of the polygon's site in its chunk, `zero` the first time; from the visitor.
    T& of(int chunk, const RvdPolygon& polygon) {
        std::vector<Entry>& entries = chunks_[chunk].value;
        if (polygon.chunk_rank == static_cast<int32_t>(entries.size())) entries.push_back({zero_, polygon.site});
        return entries[polygon.chunk_rank].sum;
    }
    //! Calls add(site, sum) for every entry, chunk after chunk, each chunk's sites in rank order.
    template <class Add>
    void for_each(Add add) const {
        for (const auto& chunk : chunks_)
            for (const Entry& e : chunk.value) add(e.site, e.sum);
    }

private:
    struct Entry {
        T sum;
        int32_t site;
    };
    T zero_;
    std::vector<ChunkSlot<std::vector<Entry>>> chunks_;
};

//! What one diagram can hand to the next when the sites move little between them (the
//! optimiser's iterates): a kd-tree of the sites and nearest-neighbour lists, both made at
//! earlier positions (the anchor), and, per triangle, a site whose cell met it.
//! If no site moved more than delta since the anchor, a site listed (or found in the tree) at
//! anchor distance d0 is now at least d0 - 2 delta away, and so is every site after it in
//! anchor order, so the security radius test stays exact with stale lists and a stale tree.
//! The few sites that moved farther than 0.35 times the typical spacing (movers: while the
//! sites settle, a handful keeps moving) are left out of that bound and checked on their own
//! against every polygon near them; the tree and lists are rebuilt only once movers are more
//! than max(32, 1/128 of the sites). Optional: the diagram is the same with or without it (up
//! to rounding).
struct RvdCache {
    std::shared_ptr<const KdTree> tree; //!< 3D kd-tree over `anchor`
    LiftedPoints anchor;             //!< #S by 3 site positions the lists and tree were made at
    std::vector<int32_t> neighbours; //!< #S by k, nearest first at `anchor` (3D distances)
    std::vector<double> distances2;  //!< #S by k squared distances at `anchor`
    int k = 0;
    double spacing = 0.0;            //!< median distance from a site to its nearest one, at `anchor`
    double rebuild_distance = 0.0;   //!< sites farther than this from `anchor` are movers
    std::vector<int32_t> seeds;      //!< #F a site whose cell met the triangle last time, or -1
    //! #F, by row: the work each triangle took last time (polygons
    //! and bisector tests), which splits the next diagram's triangles into chunks of even work.
    std::vector<int32_t> work;
    long rebuilds = 0;               //!< how many times the lists were made (for benchmarks)
    std::vector<int32_t> chunk_sites; //!< per chunk, the sites it visited last time
    //! Per thread, the per-site scratch of the last diagram (rvd.cpp), kept so that the next
    //! one reuses its memory: at 100k sites, 5.6 MB a thread that fresh pages would fault in at
    //! every evaluation.
    std::shared_ptr<RvdScratch> scratch;
};

template <class T>
ChunkSiteSums<T>::ChunkSiteSums(const LiftedSurface& surface, const T& zero, const RvdCache* cache)
    : zero_(zero), chunks_(rvd_chunks(surface)) {
    if (cache && cache->chunk_sites.size() == chunks_.size())
        for (size_t c = 0; c < chunks_.size(); ++c) chunks_[c].value.reserve(cache->chunk_sites[c] + 8);
}

//! Computes the diagram of `sites` (#S by d, d = surface.dimension()) and visits its polygons.
//! The triangles are split into rvd_chunks(surface) contiguous runs of the processing order,
//! with even work as measured by the cache's last diagram (or even counts); threads take the
//! next chunk as they finish one, so that a thread slowed down by the host does not hold the
//! others up. Each chunk is visited by one thread, its polygons always in the same order;
//! chunks are visited concurrently, in any order. A visitor that keeps per-chunk state and
//! combines the chunks in their order gets the same result, to the bit, whatever the thread
//! count. `cache` (may be null) carries neighbour lists from one call to the next, see RvdCache.
void compute_rvd(const LiftedSurface& surface, const LiftedPoints& sites, int threads, const PolygonVisitor& visit,
                 RvdCache* cache = nullptr);

//! Area of a polygon of the diagram (in R^d: the frame is orthonormal).
double polygon_area(const RvdPolygon& polygon);

//! #S areas |Omega_{k|S}| of the restricted cells; they add up to lifted_area(surface).
//! `cache` as in compute_rvd.
Eigen::VectorXd restricted_cell_areas(const LiftedSurface& surface, const LiftedPoints& sites, int threads = 0,
                                      RvdCache* cache = nullptr);

//! #S masses of the restricted cells, sum over p of w_p |Omega_{k|T_p}| (the weights of Eq. 25):
//! half the objective's Hessian at each site, a cell's own block (Eq. 7). `cache` as in compute_rvd.
Eigen::VectorXd restricted_cell_masses(const LiftedSurface& surface, const LiftedPoints& sites, int threads = 0,
                                       RvdCache* cache = nullptr);

} // namespace liftremesh
