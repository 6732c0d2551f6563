// A triangle mesh under local edits (edge and triangle splits, edge flips), as the steps after
// the restricted Delaunay triangulation make them: refining hole patches (patch_refinement.h),
// inserting the input's farthest points (hausdorff_refinement.h), moving vertices onto creases
// (crease_snap.h). Points and triangles in plain vectors; edges are found through edge_uses(),
// made again after a batch of edits, or, for many small edits in a large mesh, through each
// point's fan kept current (keep_fans()), which finds an edit's neighbourhood without a scan of
// the triangles. An edit journal (begin_edits()) undoes a try that did not work out.
#pragma once

#include "liftremesh/mesh/compressed_rows.h"
#include "liftremesh/mesh/mesh.h"

#include <array>
#include <functional>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace liftremesh {

class EditableMesh {
public:
    using Tri = std::array<int32_t, 3>;
    //! A triangle's use of an edge: the edge runs tris[tri][j] -> tris[tri][j + 1].
    struct Use {
        int tri, j;
    };
    //! The uses of one edge: how many, and the first two (all an edge of a manifold has).
    struct Uses {
        int count = 0;
        std::array<Use, 2> first{};
        size_t size() const { return static_cast<size_t>(count); }
        const Use& operator[](int i) const { return first[i]; }
    };
    //! The two triangles of an edge used once each way: t1 runs a -> b -> c and t2 b -> a -> d
    //! (the quad a -> d -> b -> c).
    struct Quad {
        int t1, t2;
        int32_t a, b, c, d;
    };

    //! All points of `mesh`, and its triangles from index `first` on (the editable ones).
    explicit EditableMesh(const Mesh& mesh, Eigen::Index first = 0);

    std::vector<Eigen::Vector3d> points;
    std::vector<Tri> tris;

    //! The uses of every edge of `tris`, by edge_key.
    std::unordered_map<uint64_t, Uses> edge_uses() const;
    //! The uses of the edges with at least one end flagged (#points flags): for edits in a small
    //! part of a large mesh, all it needs there (the quads of the flagged triangles' edges, and
    //! whether two flagged vertices are joined) for one scan of the triangles.
    std::unordered_map<uint64_t, Uses> edge_uses_around(const std::vector<char>& flagged) const;
    //! The quad of an edge with exactly two uses in opposite directions, the first use's
    //! triangle as t1; none otherwise (boundary, non-manifold or misoriented edge).
    std::optional<Quad> quad_of(const Uses& uses) const;
    //! Each point's triangles (its fan), in triangle order.
    CompressedRows fans() const;

    //! Keeps each point's fan current from now on (fan()). While they are kept, change the
    //! triangles only through set_tri(), add_tri() and the edits below, which use them.
    void keep_fans();
    //! A point's triangles, in no particular order (keep_fans(); none for a point without).
    const std::vector<int32_t>& fan(int32_t v) const;
    //! Triangle t becomes `tri` (journalled, and its fans kept, if they are).
    void set_tri(int t, const Tri& tri);
    //! Appends a triangle and returns its index (its fans kept, if they are).
    int add_tri(const Tri& tri);
    //! Starts a journal of the edits: the triangles changed, each as it was, and how many points
    //! and triangles there were (a point moved is not journalled).
    void begin_edits();
    //! Puts the triangles back as begin_edits() found them, drops the points appended since,
    //! and ends the journal.
    void roll_back();
    //! Ends the journal, keeping the edits.
    void keep_edits();

    // The following find an edit's neighbourhood through the kept fans (keep_fans()).

    //! The uses of the edges with an end among `near` (points), as edge_uses_around gives them.
    std::unordered_map<uint64_t, Uses> edge_uses_near(std::vector<int32_t> near) const;
    //! The quad of edge j of triangle t (t as t1), as quad_of gives it.
    std::optional<Quad> quad_at(int t, int j) const;
    //! Whether an edge joins u and v.
    bool joined(int32_t u, int32_t v) const;
    //! Some points' fans as they were when listed, each in triangle order. Called with a point,
    //! gives its fan as a pair of pointers (flip_rules.h: TrianglesOf), empty if not listed.
    class FanSnapshot {
    public:
        std::pair<const int32_t*, const int32_t*> operator()(int32_t v) const;

    private:
        friend class EditableMesh;
        std::vector<int32_t> points_; // ascending, each with a row
        CompressedRows rows_;
    };
    //! The fans of the corners of the triangles that share a point with one of `tris`, as they
    //! are now: every corner of a quad with a triangle among `tris` has its whole fan here.
    FanSnapshot fans_near(const std::vector<int>& tris) const;
    //! flip_pass_around over the triangles `tris` lists (flip_pass_around's `around`); `flipped`
    //! comes back listing the triangles changed, in no particular order.
    long flip_pass_near(std::vector<int> tris, const std::function<bool(const Quad&)>& accept,
                        std::vector<int>& flipped);
    //! A flag per point: an end of an edge without exactly two triangles.
    std::vector<char> border_points() const;

    //! The positions of a triangle's three corners.
    std::array<Eigen::Vector3d, 3> corners(const Tri& t) const { return {points[t[0]], points[t[1]], points[t[2]]}; }
    //! Normal of a triangle, of length twice its area (zero if degenerate).
    Eigen::Vector3d normal(const Tri& t) const;
    //! Aspect ratio kappa (Eq. 26).
    double kappa(const Tri& t) const;
    //! Whether u and v (any non-zero lengths) make at most 30 degrees; false if one is zero.
    static bool turns_little(const Eigen::Vector3d& u, const Eigen::Vector3d& v);

    //! The two triangles (a, d, c), (d, b, c) that replace the quad's when its edge is flipped
    //! to c-d; they keep the quad's orientation.
    static std::pair<Tri, Tri> flipped(const Quad& q);
    //! Whether flipping the quad's edge is a fair quality flip: the quad is nearly planar (its
    //! triangles, and each new one against their mean normal, turn by at most 30 degrees) and
    //! the smaller kappa of its two triangles goes up.
    bool flip_improves_quality(const Quad& q) const;
    //! Flips the quad's edge: t1 and t2 become flipped(q).
    void flip(const Quad& q);
    //! One pass of flips over `keys`, edges of `uses` (made from `tris` before the pass), in
    //! that order: an edge whose two triangles the pass has not changed yet is flipped to c-d
    //! when its quad has c != d, no edge c-d exists (in `uses`, in `fixed_edges`, or flipped in
    //! earlier in the pass) and accept(quad) holds. `flipped` comes back with a flag per triangle
    //! changed. Returns the number of flips.
    long flip_pass(const std::unordered_map<uint64_t, Uses>& uses, const std::vector<uint64_t>& keys,
                   const std::unordered_set<uint64_t>& fixed_edges, const std::function<bool(const Quad&)>& accept,
                   std::vector<char>& flipped);
    //! One flip_pass over the edges of the triangles flagged in `around` (#tris flags), in edge
    //! key order, with the uses of every edge near them: `flipped` as in flip_pass.
    long flip_pass_around(const std::vector<char>& around, const std::function<bool(const Quad&)>& accept,
                          std::vector<char>& flipped);
    //! Splits the quad's edge at p, a new point m: t1 and t2 become (a, m, c) and (b, m, d),
    //! (m, b, c) and (m, a, d) are appended. Returns m.
    int32_t split_edge(const Quad& q, const Eigen::Vector3d& p);

    //! The points and the editable triangles as a mesh (all of the mesh when first was 0).
    Mesh to_mesh() const;
    //! Writes the edits back into the mesh it was made from: its points replaced by `points`
    //! (moved ones moved, new ones appended), its triangles from `first` on by `tris`.
    void write_to(Mesh& mesh, Eigen::Index first = 0) const;

private:
    CompressedRows fans_of(const std::vector<char>* listed) const;
    // The triangles with a corner among `near` (points), ascending.
    std::vector<int> tris_near(const std::vector<int32_t>& near) const;

    struct Journal {
        size_t points = 0, tris = 0;
        std::vector<std::pair<int, Tri>> changed; // in order: undone last to first
    };
    bool keep_ = false;
    std::vector<std::vector<int32_t>> fans_; // kept fans, grown with the points they meet
    std::optional<Journal> journal_;
};

} // namespace liftremesh
