#include "common/numerics/blas_threads.hpp"

#include <dlfcn.h>

#include <mutex>

namespace physarum {
namespace {

using SetThreads = void (*)(int);
using GetThreads = int (*)();

// A function of the BLAS CHOLMOD was linked with: in the global scope (an executable), or in the
// already loaded libblas.so.3 (a Python extension, whose libraries are loaded locally).
void* blas_function(const char* name) {
  if (void* f = dlsym(RTLD_DEFAULT, name)) return f;
  void* blas = dlopen("libblas.so.3", RTLD_LAZY | RTLD_NOLOAD);
  return blas ? dlsym(blas, name) : nullptr;  // the handle stays open: the library stays loaded anyway
}

// OpenBLAS's thread count is one setting for the whole process: scopes on several threads share
// it, the first to open sets 1, the last to close restores what it was.
struct OpenBlasThreads {
  SetThreads set = reinterpret_cast<SetThreads>(blas_function("openblas_set_num_threads"));
  GetThreads get = reinterpret_cast<GetThreads>(blas_function("openblas_get_num_threads"));
  std::mutex mutex;
  int open_scopes = 0;
  int saved = 1;
};

OpenBlasThreads& openblas_threads() {
  static OpenBlasThreads threads;
  return threads;
}

}  // namespace

SerialBlasScope::SerialBlasScope(bool serial) {
  OpenBlasThreads& t = openblas_threads();
  if (!serial || !t.set || !t.get) return;
  const std::lock_guard<std::mutex> lock(t.mutex);
  if (t.open_scopes++ == 0) {
    t.saved = t.get();
    if (t.saved > 1) t.set(1);
  }
  active_ = true;
}

SerialBlasScope::~SerialBlasScope() {
  if (!active_) return;
  OpenBlasThreads& t = openblas_threads();
  const std::lock_guard<std::mutex> lock(t.mutex);
  if (--t.open_scopes == 0 && t.saved > 1) t.set(t.saved);
}

}  // namespace physarum
