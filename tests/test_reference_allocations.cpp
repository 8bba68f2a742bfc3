// ReferenceAgentSimulation::step() allocates nothing once warmed up (reference/agent_simulation.hpp promises
// it: every buffer is sized in the constructor). Counted here for real: this file replaces the
// global operator new of the test program with one that counts while a test has armed it, and on
// glibc also interposes malloc/calloc/realloc, because Eigen (the backward-Euler solve) allocates
// its temporaries with std::malloc, not with operator new. Outside an armed window both only
// forward to the normal allocator, so every other test is unaffected.
#include "common/setup/agent_inputs.hpp"
#include "common/scene/default_scene.hpp"
#include "common/scene/scene.hpp"
#include "common/surface/surface_domain.hpp"
#include "reference/agent_simulation.hpp"
#include "delaunay_domain.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

std::atomic<bool> g_armed{false};
std::atomic<long> g_new_calls{0};
std::atomic<long> g_malloc_calls{0};

void count_new() {
  if (g_armed.load(std::memory_order_relaxed)) g_new_calls.fetch_add(1, std::memory_order_relaxed);
}

void* allocate(std::size_t size) {
  count_new();
  if (size == 0) size = 1;
  if (void* p = std::malloc(size)) return p;
  throw std::bad_alloc();
}

void* allocate_aligned(std::size_t size, std::align_val_t alignment) {
  count_new();
  const std::size_t a = static_cast<std::size_t>(alignment);
  if (size == 0) size = 1;
  size = (size + a - 1) / a * a;  // aligned_alloc wants a multiple of the alignment
  if (void* p = std::aligned_alloc(a, size)) return p;
  throw std::bad_alloc();
}

}  // namespace

// ---- the replaced global allocation functions (all forms, so new and delete always match) ----------
void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t a) { return allocate_aligned(size, a); }
void* operator new[](std::size_t size, std::align_val_t a) { return allocate_aligned(size, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

// ---- malloc interposition (glibc only; sanitizers bring their own malloc) ------------------------
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define PHYSARUM_COUNTS_MALLOC 1
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);

void* malloc(std::size_t size) {
  if (g_armed.load(std::memory_order_relaxed)) g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  if (g_armed.load(std::memory_order_relaxed)) g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  if (g_armed.load(std::memory_order_relaxed)) g_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
}
#else
#define PHYSARUM_COUNTS_MALLOC 0
#endif

namespace physarum {
namespace {

// Counts allocations between arm() and disarm().
struct AllocationCounter {
  void arm() {
    g_new_calls = 0;
    g_malloc_calls = 0;
    g_armed = true;
  }
  void disarm() { g_armed = false; }
  long new_calls() const { return g_new_calls; }
  long malloc_calls() const { return g_malloc_calls; }
};

// The counter itself works: a vector growing inside the window is seen (by operator new, and by
// malloc where malloc is interposed), and nothing outside the window is counted.
TEST(ReferenceAllocations, CounterSeesAnAllocation) {
  AllocationCounter counter;
  counter.arm();
  auto* volatile v = new std::vector<double>(1000, 1.0);
  counter.disarm();
  delete v;
  EXPECT_GE(counter.new_calls(), 2);  // the vector object and its buffer
  if (PHYSARUM_COUNTS_MALLOC) {
    EXPECT_GE(counter.malloc_calls(), 2);
  }
  auto* volatile w = new std::vector<double>(10, 1.0);
  delete w;
  EXPECT_GE(counter.new_calls(), 2);
  EXPECT_LE(counter.new_calls(), 2) << "an allocation outside the armed window was counted";
}

Scene uniform_scene(Integrator integrator) {
  Scene s = default_scene_parameters(500);
  s.agent_model().parameters[Param::mean_lifetime] = 0.2;  // short, so respawns happen inside the counted steps
  s.agent_model().parameters[Param::activation_time] = 0.05;
  s.agent_model().integrator = integrator;
  s.seed = 5;
  return s;
}

// Warm-up (10 steps: the first deposits, respawns and face crossings are behind us), then 50 counted
// steps: every agent moves, senses across faces and deposits, agents respawn, the pheromone steps.
void expect_steps_allocate_nothing(Integrator integrator) {
  const SurfaceDomain domain = testing::delaunay_domain("shape:sphere");
  ReferenceAgentSimulation sim(domain, constant_parameters(uniform_scene(integrator), domain), simulation_settings(uniform_scene(integrator)));
  sim.run(10);
  const long long respawns_before = sim.counters().respawns;
  AllocationCounter counter;
  counter.arm();
  for (int s = 0; s < 50; ++s) sim.step();
  counter.disarm();
  ASSERT_GT(sim.counters().respawns, respawns_before) << "the counted steps must include respawns";
  EXPECT_EQ(counter.new_calls(), 0) << "operator new calls in 50 steps";
  EXPECT_EQ(counter.malloc_calls(), 0) << "malloc/calloc/realloc calls in 50 steps";
}

// Competing species too: the sensed sums and every species' deposits live in buffers sized once.
TEST(ReferenceAllocations, TwoSpeciesStepAllocatesNothing) {
  const SurfaceDomain domain = testing::delaunay_domain("shape:sphere");
  const Scene scene = uniform_scene(Integrator::Forward);
  const VertexParameters params = VertexParameters::constant(scene.agent_model().parameters, domain.vertex_count);
  SpeciesSet species;
  species.species = {Species{300, params}, Species{200, params}};
  species.sensing = {1.0, -0.5, -0.5, 1.0};
  ReferenceAgentSimulation sim(domain, species, SimulationControls{}, simulation_settings(scene));
  sim.run(10);
  AllocationCounter counter;
  counter.arm();
  for (int s = 0; s < 50; ++s) sim.step();
  counter.disarm();
  EXPECT_EQ(counter.new_calls(), 0) << "operator new calls in 50 steps";
  EXPECT_EQ(counter.malloc_calls(), 0) << "malloc/calloc/realloc calls in 50 steps";
}

TEST(ReferenceAllocations, ForwardEulerStepAllocatesNothing) { expect_steps_allocate_nothing(Integrator::Forward); }
TEST(ReferenceAllocations, BackwardEulerStepAllocatesNothing) { expect_steps_allocate_nothing(Integrator::Backward); }

}  // namespace
}  // namespace physarum
