// SerialBlasScope (common/numerics/blas_threads.hpp): OpenBLAS runs one thread while a scope is open,
// also with scopes nested or open on several threads, and gets its own count back when the last closes.
#include "common/numerics/blas_threads.hpp"

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <thread>

namespace physarum {
namespace {

using GetThreads = int (*)();

GetThreads openblas_get_num_threads() {
  if (void* f = dlsym(RTLD_DEFAULT, "openblas_get_num_threads")) return reinterpret_cast<GetThreads>(f);
  void* blas = dlopen("libblas.so.3", RTLD_LAZY | RTLD_NOLOAD);
  return blas ? reinterpret_cast<GetThreads>(dlsym(blas, "openblas_get_num_threads")) : nullptr;
}

TEST(SerialBlasScope, OneThreadInsideTheOwnCountAfter) {
  const GetThreads threads = openblas_get_num_threads();
  if (!threads) GTEST_SKIP() << "the BLAS loaded is not OpenBLAS: nothing to switch";
  const int own = threads();
  if (own < 2) GTEST_SKIP() << "OpenBLAS runs " << own << " thread here (one core, or OPENBLAS_NUM_THREADS=1)";
  {
    const SerialBlasScope outer(true);
    EXPECT_EQ(threads(), 1);
    {
      const SerialBlasScope inner(true);
      EXPECT_EQ(threads(), 1);
    }
    EXPECT_EQ(threads(), 1);  // the outer scope is still open
    std::thread other([&] {
      const SerialBlasScope on_another_thread(true);
      EXPECT_EQ(threads(), 1);
    });
    other.join();
    EXPECT_EQ(threads(), 1);
  }
  EXPECT_EQ(threads(), own);
  {
    const SerialBlasScope off(false);
    EXPECT_EQ(threads(), own);
  }
}

}  // namespace
}  // namespace physarum
