#pragma once
// OpenBLAS's own threads, turned off for a scope. CHOLMOD calls the BLAS for every supernode; for a
// factor of a few 10^9 flops (a 10^4-vertex shell's Hessian) the supernodes are too small for
// OpenBLAS to split well, and after each parallel call its worker threads spin on sched_yield for a
// while, taking the cores from whatever runs next (the shell's element Hessians). Measured on two
// cores (bench/README.md, "Memory, the upper triangle and OpenBLAS's threads"): a 9,241-vertex
// shell's factorization (1.9e9 flops) 130 ms threaded, 97 ms serial, and a whole growth run 58 ->
// 47.5-53 s; a 10^5-vertex shell's (7.7e10 flops) and a 655k-vertex heat system's (2.0e10) are
// faster threaded (1.25x, 1.08x): SharedCholesky decides by the factor's flops.
//
// Where the BLAS is not OpenBLAS (Debian's alternatives may select the reference BLAS or BLIS), or
// OpenBLAS runs one thread anyway, this does nothing: the functions are looked up at run time.
namespace physarum {

class SerialBlasScope {
 public:
  // `serial` false: nothing happens (so a caller can decide per call).
  explicit SerialBlasScope(bool serial);
  ~SerialBlasScope();
  SerialBlasScope(const SerialBlasScope&) = delete;
  SerialBlasScope& operator=(const SerialBlasScope&) = delete;

 private:
  bool active_ = false;
};

}  // namespace physarum
