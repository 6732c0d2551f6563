// The input's acute creases: its edges whose two triangles (a consistently oriented pair) turn
// by more than a given angle, as segments, with the points where they end or meet, and the
// nearest of them to a point found through samples along them. On a CAD tessellation a turn of
// over 120 degrees between neighbours is a feature (a knife edge, an interior angle under 60
// degrees), never a faceted smooth surface: the repair steps move vertices onto them
// (crease_snap.h) and keep what stands for them (edge_collapse.h) without any tagging.
#pragma once

#include "liftremesh/mesh/mesh.h"
#include "liftremesh/spatial/segment_index.h"

#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace liftremesh {

class AcuteCreases {
public:
    //! The creases of `input` turning by more than `min_turn_deg` (crease_edges), sampled every
    //! `spacing` or closer for closest(); of those, the chains (crease edges joined at their
    //! ends) at least `min_length` long in all.
    AcuteCreases(const Mesh& input, double min_turn_deg, double spacing, double min_length = 0.0);

    //! The number of crease edges.
    long size() const { return static_cast<long>(segments_.size()); }
    //! Where a crease ends or meets others: its input vertices with other than two crease edges,
    //! in lexicographic order.
    const std::vector<Eigen::Vector3d>& corners() const { return corners_; }
    //! Of the corners, those where three or more creases meet, in the same order.
    const std::vector<Eigen::Vector3d>& junctions() const { return junctions_; }
    //! Per junction, the turn of its sharpest crease, in degrees: over 120 at a knife edge's.
    const std::vector<double>& junction_turns() const { return junction_turns_; }
    //! An input vertex inside a chain of creases (two crease edges meet there) where the chain
    //! turns: a tessellation's vertex of a curved crease, the rim of a hole.
    struct Bend {
        Eigen::Vector3d point;
        double turn_deg; //!< between the directions of its two crease edges, in [0, 180]
    };
    //! The bends turning by `min_turn_deg` degrees or more, in lexicographic order.
    std::vector<Bend> bends(double min_turn_deg) const;
    //! The input vertices (a, b) of crease edge `s`, in [0, size()).
    const std::pair<int32_t, int32_t>& ends(long s) const { return ends_[s]; }
    //! Crease edge `s`'s end points, those of its input vertices ends(s).
    const std::pair<Eigen::Vector3d, Eigen::Vector3d>& segment(long s) const { return segments_[s]; }
    //! The distance from p to the nearest crease edge other than `s` whose nearest point to p
    //! is not an end it shares with `s` (where a chain turns on from s, its next edge is nearest
    //! there; a crease running beside s, or back along it past a hairpin, is nearest across),
    //! if one passes within `radius`, else more than `radius`. Not thread-safe (as nearest).
    double distance_across(const Eigen::Vector3d& p, long s, double radius) const;
    //! How far crease edge `s`'s two triangles turn, in degrees.
    double turn(long s) const { return turns_[s]; }

    //! A crease edge's point nearest to a point: the edge, its place t in [0, 1] from a to b,
    //! and the point.
    struct Nearest {
        long segment = -1;
        double t = 0.0;
        Eigen::Vector3d point;
    };
    //! The crease point nearest to p, if one lies within `radius`.
    std::optional<Nearest> nearest(const Eigen::Vector3d& p, double radius) const;
    //! nearest(p, radius)'s point.
    std::optional<Eigen::Vector3d> closest(const Eigen::Vector3d& p, double radius) const;

private:
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments_;
    std::vector<std::pair<int32_t, int32_t>> ends_; // each segment's input vertices
    std::vector<double> turns_;                     // each segment's turn, in degrees
    std::unordered_map<int32_t, int> degree_; // crease edges at an input vertex
    std::vector<Eigen::Vector3d> corners_;
    std::vector<Eigen::Vector3d> junctions_;
    std::vector<double> junction_turns_; // each junction's sharpest crease, in degrees
    std::optional<SegmentIndex> index_; // over segments_, sampled every spacing
    mutable std::vector<int32_t> found_;
};

} // namespace liftremesh
