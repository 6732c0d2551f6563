// Reading and writing triangle meshes: STL (ASCII and binary), OBJ, OFF, chosen by extension.
#pragma once

#include "liftremesh/mesh/mesh.h"

#include <string>
#include <string_view>

namespace liftremesh {

//! Reads a triangle mesh. Format by extension (case-insensitive): .stl (ASCII or binary,
//! detected from the content), .obj (v/f records; polygons fan-triangulated; negative indices
//! allowed), .off. Vertices with exactly equal coordinates are welded into one (STL stores
//! triangles, not shared vertices); every triangle is kept as the file lists it (remesh()'s
//! clean_input drops and counts the degenerate and repeated ones). Throws InvalidInput with a
//! one-line message naming the file and the problem (missing file, unknown extension,
//! malformed line N, truncated binary STL, no triangle, none with three distinct vertices).
//!
//! Details: a .stl is binary when its size is 84 + 50 n (n = the count at byte 80), ASCII when
//! it starts with "solid" and holds no NUL byte, else a truncated binary STL. OBJ records other
//! than v and f are ignored; f accepts "i", "i/t", "i//n", "i/t/n". OFF accepts '#' comments,
//! counts on the header line and the COFF/NOFF/STOFF variants (extra values ignored). Vertices
//! keep their file order (after welding, in order of first occurrence); unreferenced vertices
//! are kept. NaN and infinite coordinates are read as they are: check_mesh rejects them.
//! Numbers are parsed independently of the C locale.
Mesh read_mesh(const std::string& path);

//! read_mesh on the bytes `data` of a file named `path` (the name gives the format and the
//! messages): for data that is not in a file, as the fuzz targets (tests/fuzz) feed it.
Mesh parse_mesh(const std::string& path, std::string_view data);

//! Writes a mesh; format by extension: .stl (binary), .obj, .off. Throws InvalidInput for an
//! unknown extension or a file that cannot be written, and for a triangle index out of range.
//! Text formats write the shortest decimal that reads back to the same double (exact round
//! trip); binary STL stores float32 coordinates and recomputed unit normals.
void write_mesh(const std::string& path, const Mesh& mesh);

//! Throws InvalidInput, as read_mesh and write_mesh would, if `path` has no supported extension.
//! Lets a caller refuse a bad output name before any work is done.
void check_mesh_extension(const std::string& path);

//! Welds vertices with exactly equal coordinates (an STL lists each facet's corners apart) and
//! renumbers the triangles; drops none: clean_input (input_cleaning.h) drops the degenerate and
//! repeated ones and counts them. Used by read_mesh and clean_input.
//! Coordinates are compared as doubles (-0.0 equals 0.0; identical NaN bit patterns are merged);
//! the kept vertex is the first occurrence and the order of first occurrences is kept.
//! Throws InvalidInput if a triangle index is out of range.
void weld_exact(Mesh& mesh);

} // namespace liftremesh
