#pragma once
// Counter-based random numbers: a thin wrapper over Random123's Philox4x32-10 (both backends
// draw the same numbers for the same agent, step and purpose). The reference and the OpenCL kernels compile the very same Random123 header, so
// everything here is deliberately trivial: pack the words, call philox4x32, convert with exact
// arithmetic. Any change here must be mirrored word for word in the kernel side.
//
//   key     = (seed, stream)                  -- stream: agent id, or any other independent stream
//   counter = (step, purpose, index, 0)       -- purpose: which decision (sensing, turning, ...),
//                                                 index: which draw within that decision
//   result  = four independent uint32 words
//
// Uniforms in the OPEN interval (0, 1) (never 0, so -ln(u) is finite; never 1, so ln(1-u) is finite):
//
//   float : u01f(w)      = (float)(w >> 9) * 2^-23 + 2^-24
//           = (2k+1) * 2^-24 with k = w >> 9 in [0, 2^23): an odd multiple of 2^-24 below 2^24, so
//           every value is exactly representable in float32 and both operations are exact (no
//           rounding, hence identical with or without FMA contraction, on any IEEE device).
//           Range: [2^-24, 1 - 2^-24].
//   double: u01d(w0, w1) = (double)k * 2^-52 + 2^-53, k = ((w0 >> 6) << 26) | (w1 >> 6) in [0, 2^52)
//           = (2k+1) * 2^-53: exact in float64 for the same reason. Range: [2^-53, 1 - 2^-53].
//
// Why 23 (52) bits and not 24 (53): (2k+1) * 2^-25 with k < 2^24 needs 25 significant bits, so the
// largest values would round up to exactly 1.0f.
#include <Random123/philox.h>

#include <array>
#include <cstdint>

namespace physarum {

using PhiloxWords = std::array<std::uint32_t, 4>;

// Philox4x32 with 10 rounds on a raw counter and key (the form of Random123's known-answer vectors).
inline PhiloxWords philox4x32_10(const std::array<std::uint32_t, 4>& counter, const std::array<std::uint32_t, 2>& key) {
  philox4x32_ctr_t c = {{counter[0], counter[1], counter[2], counter[3]}};
  philox4x32_key_t k = {{key[0], key[1]}};
  const philox4x32_ctr_t r = philox4x32_R(10, c, k);
  return {r.v[0], r.v[1], r.v[2], r.v[3]};
}

// The project's packing: key = (seed, stream), counter = (step, purpose, index, 0).
inline PhiloxWords random_words(std::uint32_t seed, std::uint32_t stream, std::uint32_t step, std::uint32_t purpose,
                                std::uint32_t index = 0) {
  return philox4x32_10({step, purpose, index, 0u}, {seed, stream});
}

// Uniform float in (0, 1) from one word; formula and exactness argument above.
inline float uniform01_float(std::uint32_t word) {
  return static_cast<float>(word >> 9) * 0x1p-23f + 0x1p-24f;
}

// Uniform double in (0, 1) from two words (52 random bits); formula above.
inline double uniform01_double(std::uint32_t word0, std::uint32_t word1) {
  const std::uint64_t k = (static_cast<std::uint64_t>(word0 >> 6) << 26) | static_cast<std::uint64_t>(word1 >> 6);
  return static_cast<double>(k) * 0x1p-52 + 0x1p-53;
}

}  // namespace physarum
