#include "liftremesh/system/threads.h"

#include <omp.h>

namespace liftremesh {

int resolve_threads(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

int thread_index() { return omp_get_thread_num(); }

ThreadCountScope::ThreadCountScope(int threads) {
    if (threads <= 0) return;
    previous_ = omp_get_max_threads();
    omp_set_num_threads(threads);
}

ThreadCountScope::~ThreadCountScope() {
    if (previous_ > 0) omp_set_num_threads(previous_);
}

} // namespace liftremesh
