// How many threads the parallel parts of a remeshing use. The diagram and the objective take the
// count as an argument; the other parallel loops (vertex normals, crease-point witnesses, quality
// and distance measures) use OpenMP's default count, which a ThreadCountScope sets for a whole
// run, so that RemeshParams::threads (the CLI's --threads) holds everywhere.
#pragma once

namespace liftremesh {

//! The number of threads actually used for a requested count (0 = all cores).
int resolve_threads(int threads);

//! The calling thread's number in the parallel region it runs (0 outside any).
int thread_index();

//! Makes `threads` (> 0) the default thread count of the OpenMP regions this thread starts, until
//! it goes out of scope, when the caller's count comes back. 0 leaves the default as it is.
//! Only the calling thread's setting changes (OpenMP keeps it per thread), so a remeshing run on
//! a worker thread leaves its host application's other threads alone.
class ThreadCountScope {
public:
    explicit ThreadCountScope(int threads);
    ~ThreadCountScope();
    ThreadCountScope(const ThreadCountScope&) = delete;
    ThreadCountScope& operator=(const ThreadCountScope&) = delete;

private:
    int previous_ = 0; // 0: nothing to restore
};

} // namespace liftremesh
