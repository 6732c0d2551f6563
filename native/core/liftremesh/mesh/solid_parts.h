// The input split into the pieces that are remeshed on their own: each closed connected
// component (a solid's boundary) apart from the rest. A FreeCAD assembly exported as one STL
// has solids that touch or nearly touch, closer together than the edge length; remeshed
// together, their restricted Voronoi cells reach across the gap and the restricted Delaunay
// triangulation joins the solids with slivers across it (a wrong Euler characteristic), as
// Section 2.2 warns for regions where the surface is thin. A closed component shares no vertex
// with the others, so each is a surface of its own, whatever lies near it, as Gmsh and FreeCAD's
// Mesh workbench treat each solid. Open components stay together, as one piece: they are patches
// of one surface with gaps between them (an STL export's cracks), which the geometric
// neighbourhoods of Section 5.2.1 join.
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace liftremesh {

struct SolidPart {
    std::vector<int32_t> triangles; //!< in increasing order
    bool closed = false;            //!< a closed connected component, not the open ones together
};

//! One part per closed connected component (vertices shared, every edge used by two triangles
//! or more), in order of first triangle, then the open components together (last). A single
//! part holding every triangle when the mesh is one component, or when no component is closed.
std::vector<SolidPart> solid_parts(const Mesh& mesh);

} // namespace liftremesh
