// Reading and writing triangle meshes: STL (ASCII and binary), OBJ, OFF, chosen by extension.
#pragma once

#include "liftremesh/mesh.h"

#include <string>

namespace liftremesh {

//! Reads a triangle mesh. Format by extension (case-insensitive): .stl (ASCII or binary,
//! detected from the content), .obj (v/f records; polygons fan-triangulated; negative indices
//! allowed), .off. Vertices with exactly equal coordinates are welded into one (STL stores
//! triangles, not shared vertices). Triangles with a repeated vertex index after welding are
//! dropped. Throws InvalidInput with a one-line message naming the file and the problem
//! (missing file, unknown extension, malformed line N, truncated binary STL, no triangle).
Mesh read_mesh(const std::string& path);

//! Writes a mesh; format by extension: .stl (binary), .obj, .off. Throws InvalidInput for an
//! unknown extension or a file that cannot be written.
void write_mesh(const std::string& path, const Mesh& mesh);

//! Welds vertices with exactly equal coordinates and drops triangles that become degenerate
//! (a repeated index). Used by read_mesh; exposed for meshes that arrive as arrays.
void weld_exact(Mesh& mesh);

} // namespace liftremesh
