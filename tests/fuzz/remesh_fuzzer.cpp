// libFuzzer target for remesh() (pipeline.h): the fuzzer's bytes are the facets of a binary
// STL (50 bytes each, as stl_binary frames them), remeshed at 40 vertices with 12 iterations
// on one thread, so that a slow run is a finding. Every stage runs but the last, "quality",
// which the progress callback cancels: its Hausdorff distance samples 100k points a side
// whatever the size (measure/quality.h), 20 s a run under ASan, where the rest takes well
// under a second. remesh() may refuse an input (InvalidInput), fail on it (TopologyFailure,
// NumericalFailure) or be cancelled (Cancelled): the typed errors of exceptions.h; anything
// else is a bug.
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/pipeline.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const size_t facets = size / 50;
    if (facets > 400) return 0; // a bounded run: large inputs only slow the search
    std::string file(80, '\0');
    for (int k = 0; k < 4; ++k) file += static_cast<char>((facets >> (8 * k)) & 0xff);
    file.append(reinterpret_cast<const char*>(data), 50 * facets);
    liftremesh::RemeshParams params;
    params.target_vertices = 40;
    params.iterations = 12;
    params.threads = 1;
    const auto stop_before_quality = [](const liftremesh::Progress& p) { return p.stage != "quality"; };
    try {
        liftremesh::remesh(liftremesh::parse_mesh("fuzz.stl", file), params, stop_before_quality);
    } catch (const liftremesh::Error&) {
    }
    return 0;
}
