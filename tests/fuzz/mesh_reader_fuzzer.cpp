// libFuzzer target for the mesh readers (mesh_io.h): the fuzzer's bytes are a file's content,
// read as LIFTREMESH_FUZZ_FORMAT says. Built four times (CMakeLists.txt):
//   stl_ascii   "solid " + bytes, as an ASCII STL (the bytes rarely start with "solid" else)
//   stl_binary  an 80-byte header and a facet count that fit the bytes, as a binary STL
//               (random bytes are rarely 84 + 50 n long: they would test the size check alone)
//   obj, off    the bytes as they are
// A reader may refuse a file with InvalidInput; anything else (a crash, another exception, a
// sanitizer report, a hang past -timeout) is a bug.
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/mesh_io.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace {

std::string file_bytes(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
#if defined(LIFTREMESH_FUZZ_STL_ASCII)
    return "solid " + bytes;
#elif defined(LIFTREMESH_FUZZ_STL_BINARY)
    const size_t facets = size / 50;
    std::string file(80, '\0');
    for (int k = 0; k < 4; ++k) file += static_cast<char>((facets >> (8 * k)) & 0xff);
    return file + bytes.substr(0, 50 * facets);
#else
    return bytes;
#endif
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const liftremesh::Mesh mesh = liftremesh::parse_mesh("fuzz." LIFTREMESH_FUZZ_EXTENSION, file_bytes(data, size));
        // What a reader returns refers to its own vertices (check_indices would throw the
        // InvalidInput caught below: a bug here must abort instead).
        if (mesh.triangles.size() > 0 &&
            (mesh.triangles.minCoeff() < 0 || mesh.triangles.maxCoeff() >= mesh.points.rows()))
            std::abort();
    } catch (const liftremesh::InvalidInput&) {
    }
    return 0;
}
