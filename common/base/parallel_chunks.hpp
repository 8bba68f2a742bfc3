#pragma once
// Data-parallel loops for the output stages (texture baking, point location): the work is cut into
// independent chunks (bands of image rows, ranges of faces) that the host's cores take one at a
// time from a shared counter, so uneven chunks still balance. Each chunk must write only its own
// data; the result then does not depend on the number of threads or their timing.
#include <functional>

namespace physarum {

// The number of worker threads parallel_chunks uses: the hardware's, at least 1.
int parallel_worker_count();

// Runs work(c) for every c in [0, chunks), on up to parallel_worker_count() threads (the caller's
// among them). When some work(c) throws, the remaining chunks are skipped and the first exception
// is rethrown once every thread has stopped.
void parallel_chunks(int chunks, const std::function<void(int chunk)>& work);

}  // namespace physarum
