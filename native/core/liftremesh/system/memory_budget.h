// How much memory a remeshing needs, checked before anything large is allocated: a request
// the machine cannot hold fails at once with a message, instead of running for minutes and
// being stopped by the system (losing, in FreeCAD, the user's session).
#pragma once

#include <cstdint>

namespace liftremesh {

//! Estimated peak memory of remesh() in bytes, for `sites` sites on an input of `triangles`
//! triangles with `threads` threads. Measured on this project's machine (peak resident size,
//! /usr/bin/time -v): about 1.1 kB a site (sites, L-BFGS history of 7 pairs, neighbour lists,
//! output, per-chunk gradient sums), 0.1 kB a site for each thread (scratch), under 1 kB an input triangle,
//! and some 64 MiB of fixed costs (quality samples). Rounded up: an estimate, not a bound.
std::uint64_t estimated_peak_bytes(long sites, long triangles, int threads);

//! Physical memory of this machine in bytes, or 0 if it cannot be told.
std::uint64_t physical_memory_bytes();

//! Throws InvalidInput if the estimate exceeds `available` bytes (0 = unknown: no check),
//! naming the vertex count, the memory it needs and the memory there is.
void check_memory_budget(long sites, long triangles, int threads, std::uint64_t available);

} // namespace liftremesh
